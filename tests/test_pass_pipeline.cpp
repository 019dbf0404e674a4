// A pipeline made from its pass (Pass::pipeline) takes the pass's attachment
// formats, sample count, depth state and binding slots; attachments whose
// sample counts differ, or a texture not made yet, are refused naming the pass.
#include <gtest/gtest.h>

#include <stdexcept>

#include "gpu_test_util.h"
#include "render/graph/pass.h"

namespace {

using namespace sb;

class PassPipeline : public sbtest::BackendTest {
 protected:
  Texture texture(const std::string& name, Format f, uint32_t samples = 1, uint32_t layers = 1) {
    return dev_->createTexture({name, Owner::Test, f, 16, 16, false, layers, samples});
  }
};

TEST_P(PassPipeline, TakesFormatsDepthAndSlotsFromThePass) {
  const Texture color = texture("color", Format::RGBA32F), count = texture("count", Format::R32F);
  const Texture layered = texture("layered", Format::RGBA32UI, 1, 2);
  const Texture depth = texture("depth", Format::Depth32F);
  const Buffer params = dev_->createBuffer({"params", Owner::Test, BufferUsage::Uniform, 16});
  const Pass p = Pass("test.accumulate")
                     .color(color, LoadOp::Clear)
                     .color(count, LoadOp::Load)
                     .colorUint(layered, LoadOp::Clear, {}, 1)
                     .depth(depth, LoadOp::Clear)
                     .uniform(3, params)
                     .sample(4, color);
  const PipelineDesc d = p.pipeline(*dev_, "test.pipeline", "test");
  EXPECT_EQ(d.name, "test.pipeline");
  EXPECT_EQ(d.technique, "test");
  EXPECT_EQ(d.colorFormats, (std::vector<Format>{Format::RGBA32F, Format::R32F, Format::RGBA32UI}));
  EXPECT_EQ(d.samples, 1u);
  EXPECT_TRUE(d.hasDepth);
  EXPECT_TRUE(d.depthTest);
  EXPECT_TRUE(d.depthWrite);
  EXPECT_EQ(d.depthFormat, Format::Depth32F);
  ASSERT_EQ(d.bindings.size(), 2u);
  EXPECT_EQ(d.bindings[0].binding, 3u);
  EXPECT_EQ(d.bindings[0].kind, BindingKind::UniformBuffer);
  EXPECT_EQ(d.bindings[1].binding, 4u);
  EXPECT_EQ(d.bindings[1].kind, BindingKind::SampledTexture);
  // What the technique sets itself is left as a PipelineDesc starts.
  EXPECT_EQ(d.vertex, nullptr);
  EXPECT_EQ(d.fragment, nullptr);
  EXPECT_TRUE(d.blend.empty());
  EXPECT_EQ(d.depthCompare, CompareOp::Less);

  // A depth only tested: not written; no depth attachment: no depth at all.
  const PipelineDesc ro = Pass("test.read_only")
                              .color(color, LoadOp::Load)
                              .depthReadOnly(depth)
                              .pipeline(*dev_, "test.read_only");
  EXPECT_TRUE(ro.hasDepth);
  EXPECT_TRUE(ro.depthTest);
  EXPECT_FALSE(ro.depthWrite);
  const PipelineDesc none = Pass("test.color").color(color, LoadOp::Clear).pipeline(*dev_, "c");
  EXPECT_FALSE(none.hasDepth);
  EXPECT_FALSE(none.depthTest);
  EXPECT_FALSE(none.depthWrite);
  EXPECT_EQ(none.colorFormats, std::vector<Format>{Format::RGBA32F});

  // A pass without attachments (a size, or a compute dispatch): slots only.
  const PipelineDesc sized =
      Pass("test.splat").size(8, 8).storage(2, params).pipeline(*dev_, "test.splat");
  EXPECT_TRUE(sized.colorFormats.empty());
  EXPECT_FALSE(sized.hasDepth);
  EXPECT_EQ(sized.samples, 1u);
  ASSERT_EQ(sized.bindings.size(), 1u);
  EXPECT_EQ(sized.bindings[0].kind, BindingKind::StorageBuffer);
}

TEST_P(PassPipeline, TakesTheAttachmentsSampleCountAndRefusesMismatches) {
  if (!(dev_->info().sampleCounts & 4u)) GTEST_SKIP() << "no 4-sample textures";
  const Texture color4 = texture("color4", Format::RGBA32F, 4);
  const Texture depth4 = texture("depth4", Format::Depth32F, 4);
  const Texture resolved = texture("resolved", Format::RGBA32F);
  const Texture depth1 = texture("depth1", Format::Depth32F);
  const PipelineDesc d = Pass("test.msaa")
                             .color(color4, LoadOp::Clear)
                             .resolveInto(resolved)  // single-sampled, not an attachment
                             .depth(depth4, LoadOp::Clear)
                             .pipeline(*dev_, "test.msaa");
  EXPECT_EQ(d.samples, 4u);
  EXPECT_EQ(d.colorFormats, std::vector<Format>{Format::RGBA32F});

  const Pass mismatched =
      Pass("test.mismatched").color(color4, LoadOp::Clear).depth(depth1, LoadOp::Clear);
  try {
    mismatched.pipeline(*dev_, "test.mismatched");
    FAIL() << "attachments of 4 and 1 samples were accepted";
  } catch (const std::logic_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'test.mismatched'"), std::string::npos) << what;
    EXPECT_NE(what.find("sample count"), std::string::npos) << what;
  }
}

TEST_P(PassPipeline, RefusesATextureNotMadeYet) {
  const Pass early = Pass("test.early").color(Texture{}, LoadOp::Clear);
  try {
    early.pipeline(*dev_, "test.early");
    FAIL() << "a pipeline was made before its attachment's texture";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("'test.early'"), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, PassPipeline, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

}  // namespace
