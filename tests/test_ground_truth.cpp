// The two ground truths must agree: exact shadows by depth peeling from the
// light and by sorted light-space fragment lists (identical per-texel fragment
// keys), exact transparency by depth peeling from the eye and by an eye-space
// A-buffer (images within 1e-4), on both backends, on three scenes, one with
// depth complexity >= 100.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "gpu_test_util.h"
#include "imaging/image.h"
#include "imaging/metrics.h"
#include "scenes/view.h"
#include "techniques/exact/exact.h"
#include "render/frame/renderer.h"

namespace sb {
namespace {

struct Case {
  std::string scene;
  uint32_t size;
  uint32_t minEyeComplexity;
};

struct GroundTruth {
  Image image;
  ExactShadow::Lists lists;
  DepthComplexity eye, light;
  std::vector<std::string> warnings;
};

// method: peel | abuffer, for both the shadows and the transparency;
// layerCap: ",layers=N" to cap peeling, or "".
GroundTruth render(Device& dev, const Case& c, const std::string& method,
                   const std::string& layerCap = "") {
  const Scene scene = makeScene(Spec::parse(c.scene));
  const RenderSettings s = sbtest::fittedSettings(scene, c.size);
  const std::string size = std::to_string(c.size);
  Renderer r(
      dev, scene, s,
      makeShadowTechnique(Spec::parse("exact:size=" + size + ",method=" + method + layerCap)),
      makeOitTechnique(Spec::parse(method + (layerCap.empty() ? "" : ":" + layerCap.substr(1)))));
  r.renderFrame();
  GroundTruth g;
  g.image = imageFromRows(r.readColor(), int(c.size), int(c.size), PixelType::Float32, 4);
  g.lists = dynamic_cast<ExactShadow&>(r.shadow()).readLists(dev);
  g.eye = *r.oit().depthComplexity();
  g.light = *r.shadow().depthComplexity();
  g.warnings = r.warnings();
  return g;
}

class GroundTruthTest : public sbtest::BackendTest {};

TEST_P(GroundTruthTest, PeelingAndFragmentListsAgree) {
  const std::vector<Case> cases = {
      {"straight:strands=400,points=10,alpha=0.5,shadow_alpha=0.3", 64, 1},
      {"curly:strands=300,points=24,alpha=0.4,head=0", 64, 1},
      {"clustered:strands=1500,points=6,head=0,alpha=0.2", 48, 100},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.scene);
    const GroundTruth peel = render(*dev_, c, "peel");
    const GroundTruth lists = render(*dev_, c, "abuffer");
    std::cout << "[ measured ] " << GetParam() << " " << c.scene << ": eye depth complexity max "
              << peel.eye.max << " mean " << peel.eye.mean << ", light max " << peel.light.max
              << " mean " << peel.light.mean << "\n";
    EXPECT_TRUE(peel.warnings.empty()) << peel.warnings.front();
    EXPECT_TRUE(lists.warnings.empty()) << lists.warnings.front();
    // Shadows: the same fragments, in the same order, in every light texel.
    EXPECT_EQ(peel.lists.stored, lists.lists.stored);
    EXPECT_EQ(peel.lists.keys, lists.lists.keys);
    uint64_t stored = 0;
    for (uint32_t n : peel.lists.stored) stored += n;
    EXPECT_EQ(stored, peel.light.total);
    EXPECT_GT(stored, 0u);
    // Transparency: the same image.
    const ImageError e = compareImages(peel.image, lists.image, 1e-4);
    EXPECT_LE(e.maxAbs, 1e-4);
    EXPECT_EQ(peel.eye.max, lists.eye.max);
    EXPECT_GE(peel.eye.max, c.minEyeComplexity);
  }
}

// The agreement check can fail: peeling capped below the depth complexity
// stores fewer fragments, differs from the lists, and says so.
TEST_P(GroundTruthTest, CappedPeelingDisagreesAndIsReported) {
  const Case c{"clustered:strands=600,points=6,head=0,alpha=0.3", 32, 1};
  const GroundTruth capped = render(*dev_, c, "peel", ",layers=3");
  const GroundTruth lists = render(*dev_, c, "abuffer");
  ASSERT_GT(lists.light.max, 3u);
  EXPECT_NE(capped.lists.stored, lists.lists.stored);
  EXPECT_GT(compareImages(capped.image, lists.image).maxAbs, 1e-4);
  ASSERT_FALSE(capped.warnings.empty());
  EXPECT_NE(capped.warnings.front().find("capped"), std::string::npos) << capped.warnings.front();
}

// Hair behind the opaque mesh is no part of the truth: its fragments are
// neither counted nor composited (storage writes need early depth tests).
TEST_P(GroundTruthTest, HairBehindTheMeshIsLeftOut) {
  const Case withHead{"curly:strands=300,points=24,alpha=0.4", 64, 1};
  const Case noHead{"curly:strands=300,points=24,alpha=0.4,head=0", 64, 1};
  for (const std::string method : {"peel", "abuffer"}) {
    const GroundTruth a = render(*dev_, withHead, method);
    const GroundTruth b = render(*dev_, noHead, method);
    EXPECT_LT(a.eye.total, b.eye.total) << method;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, GroundTruthTest, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

}  // namespace
}  // namespace sb
