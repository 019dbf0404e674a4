// Every rule of the device contract, broken on purpose on GL and on Vulkan: the
// front end (backends/device.cpp) must reject it on both, with the same message,
// before the driver sees it.
#include <gtest/gtest.h>

#include <cctype>
#include <cstring>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "backends/device.h"

namespace sb {
namespace {

ShaderCode shader(const std::string& name, const std::string& text) {
  return ShaderCode{name, text, {name}};
}

const ShaderCode kVert = shader("tests/contract.vert", R"(
layout(std430, binding = 0) readonly buffer Positions { vec4 pos[]; };
void main() { gl_Position = pos[gl_VertexIndex]; }
)");
const ShaderCode kFrag = shader("tests/contract.frag", R"(
layout(binding = 1) uniform sampler2D tex;
layout(location = 0) out vec4 outColor;
void main() { outColor = texelFetch(tex, ivec2(0), 0); }
)");
const ShaderCode kArrayFrag = shader("tests/contract_array.frag", R"(
layout(binding = 1) uniform sampler2DArray tex;
layout(location = 0) out vec4 outColor;
void main() { outColor = texelFetch(tex, ivec3(0, 0, textureSize(tex, 0).z - 1), 0); }
)");
const ShaderCode kComp = shader("tests/contract.comp", R"(
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Data { uint v[]; };
void main() { v[0] = 1u; }
)");

// A small world for each rule: targets (one a two-layer array), a buffer and
// three pipelines.
struct World {
  Device& dev;
  Texture color, other, depth, small, array;
  Buffer data;
  Pipeline draw, drawArray, compute;
  explicit World(Device& d) : dev(d) {
    color = dev.createTexture({"color", Owner::Test, Format::RGBA32F, 8, 8, false});
    other = dev.createTexture({"other", Owner::Test, Format::RGBA32F, 8, 8, false});
    depth = dev.createTexture({"depth", Owner::Test, Format::Depth32F, 8, 8, false});
    small = dev.createTexture({"small", Owner::Test, Format::RGBA32F, 4, 4, false});
    array = dev.createTexture({"array", Owner::Test, Format::RGBA32F, 8, 8, false, 2});
    data = dev.createBuffer({"data", Owner::Test, BufferUsage::Storage, 64});
    PipelineDesc g;
    g.name = "contract.draw";
    g.technique = "tests";
    g.vertex = &kVert;
    g.fragment = &kFrag;
    g.colorFormats = {Format::RGBA32F};
    g.bindings = {{0, BindingKind::StorageBuffer}, {1, BindingKind::SampledTexture}};
    draw = dev.createPipeline(g);
    g.name = "contract.draw_array";
    g.fragment = &kArrayFrag;
    g.bindings = {{0, BindingKind::StorageBuffer}, {1, BindingKind::SampledTextureArray}};
    drawArray = dev.createPipeline(g);
    PipelineDesc c;
    c.name = "contract.compute";
    c.technique = "tests";
    c.compute = &kComp;
    c.bindings = {{0, BindingKind::StorageBuffer}};
    compute = dev.createPipeline(c);
  }
  PassDesc pass(Texture target, std::vector<Texture> sampled = {}, uint32_t layer = 0) const {
    PassDesc p;
    p.name = "contract.pass";
    p.color = {{target, LoadOp::Clear, {0, 0, 0, 0}, {}, layer}};
    p.sampledTextures = std::move(sampled);
    return p;
  }
  std::vector<Binding> goodBindings() const {
    return {Binding::buf(0, data), Binding::tex(1, other)};
  }
  // A pass onto `targets` layers of one array, and a pipeline with as many targets.
  PassDesc widePass(uint32_t targets) const {
    const Texture wide =
        dev.createTexture({"wide", Owner::Test, Format::RGBA8, 8, 8, false, targets});
    PassDesc p;
    p.name = "contract.wide";
    for (uint32_t i = 0; i < targets; ++i) p.color.push_back({wide, LoadOp::Clear, {}, {}, i});
    p.sampledTextures = {other};
    return p;
  }
  // An 8x8 RGBA32F texture with 4 samples per pixel.
  Texture multisampled() const {
    return dev.createTexture({"ms", Owner::Test, Format::RGBA32F, 8, 8, false, 1, 4});
  }
  Pipeline widePipeline(uint32_t targets) const {
    PipelineDesc d;
    d.name = "contract.wide";
    d.technique = "tests";
    d.vertex = &kVert;
    d.fragment = &kFrag;
    d.colorFormats.assign(targets, Format::RGBA8);
    d.bindings = {{0, BindingKind::StorageBuffer}, {1, BindingKind::SampledTexture}};
    return dev.createPipeline(d);
  }
};

struct Rule {
  std::string name;
  std::string expected;  // a part of the message
  std::function<void(World&)> breakIt;
};

std::vector<Rule> rules() {
  return {
      {"zero-size buffer", "createBuffer('empty'): zero size",
       [](World& w) {
         w.dev.createBuffer({"empty", Owner::Test, BufferUsage::Storage, 0});
       }},
      {"buffer made an acceleration structure by its usage",
       "createBuffer('tlas'): usage AccelerationStructure (use createAccelerationStructure)",
       [](World& w) {
         w.dev.createBuffer({"tlas", Owner::Test, BufferUsage::AccelerationStructure, 64});
       }},
      // The system's Mesa 22.3 has no ray queries on either API (Mesa 25.0.7's
      // lavapipe has: tests/test_rt_shadows.cpp, RtTiers).
      {"acceleration structure without ray queries", "createAccelerationStructure('scene'): ",
       [](World& w) {
         try {
           w.dev.createAccelerationStructure("scene", Owner::Test, w.data, 2);
         } catch (const DeviceError& e) {
           if (std::string(e.what()).find("offers no ray queries (DeviceInfo::rayQuery)") ==
               std::string::npos)
             ADD_FAILURE() << e.what();
           throw;
         }
       }},
      {"zero-size texture", "createTexture('flat'): zero size",
       [](World& w) {
         w.dev.createTexture({"flat", Owner::Test, Format::RGBA8, 0, 4, false});
       }},
      {"texture without layers", "createTexture('none'): 0 layers (1..256)",
       [](World& w) {
         w.dev.createTexture({"none", Owner::Test, Format::RGBA8, 4, 4, false, 0});
       }},
      {"texture with too many layers", "createTexture('deep'): 257 layers (1..256)",
       [](World& w) {
         w.dev.createTexture({"deep", Owner::Test, Format::RGBA8, 4, 4, false, 257});
       }},
      {"depth texture with layers", "createTexture('depths'): a depth texture has one layer, not 2",
       [](World& w) {
         w.dev.createTexture({"depths", Owner::Test, Format::Depth32F, 4, 4, false, 2});
       }},
      {"pipeline without shaders", "give either vertex+fragment or compute shaders",
       [](World& w) {
         PipelineDesc d;
         d.name = "nothing";
         w.dev.createPipeline(d);
       }},
      {"pipeline with graphics and compute shaders",
       "give either vertex+fragment or compute shaders",
       [](World& w) {
         PipelineDesc d;
         d.name = "both";
         d.vertex = &kVert;
         d.fragment = &kFrag;
         d.compute = &kComp;
         w.dev.createPipeline(d);
       }},
      {"depth format as a colour target", "depth format as colour target",
       [](World& w) {
         PipelineDesc d;
         d.name = "depth-colour";
         d.vertex = &kVert;
         d.fragment = &kFrag;
         d.colorFormats = {Format::Depth32F};
         w.dev.createPipeline(d);
       }},
      {"binding declared twice", "binding 1 declared twice",
       [](World& w) {
         PipelineDesc d;
         d.name = "twice";
         d.vertex = &kVert;
         d.fragment = &kFrag;
         d.colorFormats = {Format::RGBA32F};
         d.bindings = {{1, BindingKind::SampledTexture}, {1, BindingKind::UniformBuffer}};
         w.dev.createPipeline(d);
       }},
      {"more blend states than targets", "2 blend states for 1 colour targets",
       [](World& w) {
         PipelineDesc d;
         d.name = "blends";
         d.vertex = &kVert;
         d.fragment = &kFrag;
         d.colorFormats = {Format::RGBA32F};
         d.blend = {BlendState::additive(), BlendState::additive()};
         w.dev.createPipeline(d);
       }},
      // The count and the limit are the device's (9 and 8 on llvmpipe and
      // lavapipe): the whole message is checked in
      // DeviceContract.ColourTargetsUpToTheDeviceLimit below.
      {"too many colour attachments in a pass", "colour targets; the device allows at most",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.widePass(w.dev.maxColorAttachments() + 1));
       }},
      {"too many colour targets in a pipeline", "colour targets; the device allows at most",
       [](World& w) { w.widePipeline(w.dev.maxColorAttachments() + 1); }},
      {"pass outside a frame", "beginPass('contract.pass'): outside a frame",
       [](World& w) { w.dev.beginPass(w.pass(w.color)); }},
      {"pass inside a pass", "inside pass 'contract.pass'",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color));
         w.dev.beginPass(w.pass(w.other));
       }},
      {"attachments of different sizes", "attachments differ in size ('small' is 4x4",
       [](World& w) {
         w.dev.beginFrame();
         PassDesc p = w.pass(w.color);
         p.color.push_back({w.small, LoadOp::Clear, {}, {}});
         w.dev.beginPass(p);
       }},
      {"a texture attached and sampled", "texture 'color' is both an attachment and sampled",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color, {w.color}));
       }},
      {"a texture attached twice", "texture 'color' attached twice",
       [](World& w) {
         w.dev.beginFrame();
         PassDesc p = w.pass(w.color);
         p.color.push_back({w.color, LoadOp::Clear, {}, {}});
         w.dev.beginPass(p);
       }},
      {"an array layer out of range", "layer 2 of texture 'array' is out of range (it has 2)",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.array, {}, 2));
       }},
      {"a layer of a one-layer texture", "layer 1 of texture 'color' is out of range (it has 1)",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color, {}, 1));
       }},
      {"an array layer attached twice", "texture 'array' layer 1 attached twice",
       [](World& w) {
         w.dev.beginFrame();
         PassDesc p = w.pass(w.array, {}, 1);
         p.color.push_back({w.array, LoadOp::Clear, {}, {}, 0});
         p.color.push_back({w.array, LoadOp::Load, {}, {}, 1});
         w.dev.beginPass(p);
       }},
      {"an array sampled while a layer is attached",
       "texture 'array' is both an attachment and sampled",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.array, {w.array}, 1));
       }},
      {"depth texture as colour attachment", "depth texture 'depth' as colour attachment",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.depth));
       }},
      {"colour texture as depth attachment", "'other' is not a depth texture",
       [](World& w) {
         w.dev.beginFrame();
         PassDesc p = w.pass(w.color);
         p.depth.texture = w.other;
         w.dev.beginPass(p);
       }},
      {"pass without attachments or size", "no attachments and no size",
       [](World& w) {
         w.dev.beginFrame();
         PassDesc p;
         p.name = "contract.pass";
         w.dev.beginPass(p);
       }},
      {"draw outside a pass", "draw('contract.draw'): outside a pass",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.draw(w.draw, w.goodBindings(), 3);
       }},
      {"pipeline targets differ from the pass", "targets do not match pass 'contract.pass'",
       [](World& w) {
         w.dev.beginFrame();
         PassDesc p = w.pass(w.color, {w.other});
         p.depth.texture = w.depth;
         w.dev.beginPass(p);
         w.dev.draw(w.draw, w.goodBindings(), 3);
       }},
      {"binding not declared by the pipeline", "binding 5 is not declared in the pipeline",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color, {w.other}));
         auto b = w.goodBindings();
         b.push_back(Binding::buf(5, w.data));
         w.dev.draw(w.draw, b, 3);
       }},
      {"declared binding not provided", "binding 1 not provided",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color, {w.other}));
         w.dev.draw(w.draw, {Binding::buf(0, w.data)}, 3);
       }},
      {"binding given twice", "binding 0 given twice",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color, {w.other}));
         auto b = w.goodBindings();
         b.push_back(Binding::buf(0, w.data));
         w.dev.draw(w.draw, b, 3);
       }},
      {"buffer where a texture is declared", "binding 1 needs a texture",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color, {w.other}));
         w.dev.draw(w.draw, {Binding::buf(0, w.data), Binding::buf(1, w.data)}, 3);
       }},
      {"texture where a buffer is declared", "binding 0 needs a buffer",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color, {w.other}));
         w.dev.draw(w.draw, {Binding::tex(0, w.other), Binding::tex(1, w.other)}, 3);
       }},
      {"sampling a texture the pass did not declare",
       "texture 'other' is sampled but pass 'contract.pass' does not list it",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color));
         w.dev.draw(w.draw, w.goodBindings(), 3);
       }},
      {"an array through a sampler2D slot",
       "binding 1: texture 'array' has 2 layers (a sampler2D slot; arrays need "
       "SampledTextureArray)",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color, {w.array}));
         w.dev.draw(w.draw, {Binding::buf(0, w.data), Binding::tex(1, w.array)}, 3);
       }},
      {"compute pipeline drawn", "a compute pipeline (use dispatch)",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color));
         w.dev.draw(w.compute, {Binding::buf(0, w.data)}, 3);
       }},
      {"dispatch inside a pass", "dispatch('contract.dispatch'): inside pass 'contract.pass'",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color));
         w.dev.dispatch("contract.dispatch", w.compute, {Binding::buf(0, w.data)}, 1);
       }},
      {"dispatch outside a frame", "dispatch('contract.dispatch'): outside a frame",
       [](World& w) {
         w.dev.dispatch("contract.dispatch", w.compute, {Binding::buf(0, w.data)}, 1);
       }},
      {"graphics pipeline dispatched", "'contract.draw' is not a compute pipeline",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.dispatch("contract.dispatch", w.draw, w.goodBindings(), 1);
       }},
      {"update past the end of a buffer", "60 bytes at offset 8 exceed its 64 bytes",
       [](World& w) {
         const std::vector<uint8_t> bytes(60);
         w.dev.updateBuffer(w.data, bytes.data(), bytes.size(), 8);
       }},
      {"update inside a pass", "updateBuffer('data'): inside pass 'contract.pass'",
       [](World& w) {
         const uint32_t v = 1;
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color));
         w.dev.updateBuffer(w.data, &v, sizeof v);
       }},
      {"fill inside a pass", "fillBuffer('data'): inside pass 'contract.pass'",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color));
         w.dev.fillBuffer(w.data, 0);
       }},
      {"read back inside a frame", "readTexture('color'): only outside a frame",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.readTexture(w.color);
       }},
      {"frame ended with a pass open", "endFrame: pass 'contract.pass' is still open",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color));
         w.dev.endFrame();
       }},
      {"frame begun twice", "beginFrame: a frame is already being recorded",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginFrame();
       }},
      {"a destroyed texture used", "unknown texture handle",
       [](World& w) {
         w.dev.destroy(w.other);
         w.dev.readTexture(w.other);
       }},
      // Multisampling (4 samples: both CPU drivers have them).
      {"unsupported sample count",
       "createTexture('odd'): 3 samples: not a count the device supports",
       [](World& w) {
         w.dev.createTexture({"odd", Owner::Test, Format::RGBA32F, 8, 8, false, 1, 3});
       }},
      {"multisampled array", "createTexture('msarray'): 4 samples and 2 layers",
       [](World& w) {
         w.dev.createTexture({"msarray", Owner::Test, Format::RGBA32F, 8, 8, false, 2, 4});
       }},
      {"multisampled integer texture", "of integer format RGBA32UI",
       [](World& w) {
         w.dev.createTexture({"msuint", Owner::Test, Format::RGBA32UI, 8, 8, false, 1, 4});
       }},
      {"pipeline with unsupported samples", "3 samples: not a count the device supports",
       [](World& w) {
         PipelineDesc d;
         d.name = "contract.ms3";
         d.technique = "tests";
         d.vertex = &kVert;
         d.fragment = &kFrag;
         d.colorFormats = {Format::RGBA32F};
         d.samples = 3;
         w.dev.createPipeline(d);
       }},
      {"attachments of different sample counts",
       "beginPass('contract.pass'): attachments differ in sample count ('depth' has 1, the pass 4)",
       [](World& w) {
         PassDesc p = w.pass(w.multisampled());
         p.depth = {w.depth, LoadOp::Clear, 1.0f};
         w.dev.beginFrame();
         w.dev.beginPass(p);
       }},
      {"pipeline samples differ from the pass",
       "draw('contract.draw'): the pipeline has 1 samples, pass 'contract.pass' 4",
       [](World& w) {
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.multisampled(), {w.other}));
         w.dev.draw(w.draw, w.goodBindings(), 3);
       }},
      {"multisampled texture sampled", "texture 'ms' is multisampled (4 samples) and cannot",
       [](World& w) {
         const Texture ms = w.multisampled();
         w.dev.beginFrame();
         w.dev.beginPass(w.pass(w.color, {ms}));
       }},
      {"multisampled texture read back", "readTexture('ms'): a multisampled texture",
       [](World& w) { w.dev.readTexture(w.multisampled()); }},
      {"resolve into another format", "resolve of 'ms' into 'narrow': formats differ",
       [](World& w) {
         PassDesc p = w.pass(w.multisampled());
         p.color[0].resolve =
             w.dev.createTexture({"narrow", Owner::Test, Format::RGBA8, 8, 8, false});
         w.dev.beginFrame();
         w.dev.beginPass(p);
       }},
      {"resolve of a single-sampled attachment",
       "resolve of 'color' into 'other': the attachment is not multisampled",
       [](World& w) {
         PassDesc p = w.pass(w.color);
         p.color[0].resolve = w.other;
         w.dev.beginFrame();
         w.dev.beginPass(p);
       }},
      {"resolve into one target twice",
       "resolve of 'ms' into 'color': the target is resolved into twice",
       [](World& w) {
         PassDesc p = w.pass(w.multisampled());
         p.color[0].resolve = w.color;
         p.color.push_back({w.multisampled(), LoadOp::Clear, {}, {}, 0, w.color});
         w.dev.beginFrame();
         w.dev.beginPass(p);
       }},
  };
}

// A device per backend that starts on this machine (none for one that does not).
std::vector<std::pair<std::string, std::unique_ptr<Device>>> availableDevices() {
  std::vector<std::pair<std::string, std::unique_ptr<Device>>> out;
  for (const std::string backend : {"gl", "vulkan"}) {
    try {
      out.emplace_back(backend,
                       createDevice({backend, backend == "gl" ? "egl" : "headless", false}));
    } catch (const DeviceError&) {
    }
  }
  return out;
}

// The message each backend gives for a rule; "" when it did not throw, and
// no entry when the backend is unavailable here.
std::map<std::string, std::string> messages(const Rule& rule) {
  std::map<std::string, std::string> out;
  for (auto& [backend, dev] : availableDevices()) {
    World w(*dev);
    try {
      rule.breakIt(w);
      out[backend] = "";
    } catch (const DeviceError& e) {
      out[backend] = e.what();
    }
  }
  return out;
}

// One test per rule: rejected on every backend here, with the same message on both.
class DeviceContractRule : public ::testing::TestWithParam<Rule> {};

TEST_P(DeviceContractRule, RejectedTheSameOnGlAndVulkan) {
  const Rule& rule = GetParam();
  const auto got = messages(rule);
  if (got.empty()) GTEST_SKIP() << "no backend available";
  for (const auto& [backend, message] : got) {
    EXPECT_NE(message.find(rule.expected), std::string::npos)
        << rule.name << " on " << backend << ": got '" << message << "'";
  }
  if (got.size() == 2) {
    EXPECT_EQ(got.at("gl"), got.at("vulkan")) << rule.name;
  }
}

INSTANTIATE_TEST_SUITE_P(Rules, DeviceContractRule, ::testing::ValuesIn(rules()),
                         [](const ::testing::TestParamInfo<Rule>& param) {
                           std::string id;
                           for (char c : param.param.name) id += std::isalnum(c) ? c : '_';
                           return id;
                         });

// The same world with every binding right is accepted on both: the rules above
// fail for the reason they name, not for a broken setup.
TEST(DeviceContract, TheUnbrokenWorldRendersOnBothApis) {
  const Rule valid{
      "valid", "", [](World& w) {
        w.dev.beginFrame();
        w.dev.beginPass(w.pass(w.color, {w.other}));
        w.dev.draw(w.draw, w.goodBindings(), 3);
        w.dev.endPass();
        // Both layers of the array in one pass, then the array
        // and a one-layer texture sampled as arrays.
        PassDesc layers = w.pass(w.array, {}, 1);
        layers.color.push_back({w.array, LoadOp::Clear, {}, {}, 0});
        w.dev.beginPass(layers);
        w.dev.endPass();
        w.dev.beginPass(w.pass(w.color, {w.array, w.other}));
        w.dev.draw(w.drawArray, {Binding::buf(0, w.data), Binding::tex(1, w.array)}, 3);
        w.dev.draw(w.drawArray, w.goodBindings(), 3);
        w.dev.endPass();
        w.dev.dispatch("contract.dispatch", w.compute, {Binding::buf(0, w.data)}, 1);
        w.dev.endFrame();
        w.dev.readTexture(w.color);
        if (w.dev.readTexture(w.array).size() != 2u * 8 * 8 * 16)
          throw DeviceError("an array reads back every layer");
      }};
  const auto got = messages(valid);
  if (got.empty()) GTEST_SKIP() << "no backend available";
  for (const auto& [backend, message] : got) EXPECT_EQ(message, "") << backend;
}

// Passes and pipelines with as many colour targets as the device allows render;
// one more is refused with a message naming the call, the count and the limit.
TEST(DeviceContract, ColourTargetsUpToTheDeviceLimit) {
  std::map<std::string, uint32_t> limits;
  for (auto& [backend, dev] : availableDevices()) {
    const uint32_t limit = dev->maxColorAttachments();
    limits[backend] = limit;
    EXPECT_EQ(dev->info().maxColorAttachments, limit) << backend;
    // What each API guarantees (GL 4.5: 8 draw buffers; Vulkan: 4).
    EXPECT_GE(limit, backend == "gl" ? 8u : 4u) << backend;
    World w(*dev);
    try {
      const Pipeline wide = w.widePipeline(limit);
      w.dev.beginFrame();
      w.dev.beginPass(w.widePass(limit));
      w.dev.draw(wide, w.goodBindings(), 3);
      w.dev.endPass();
      w.dev.endFrame();
    } catch (const DeviceError& e) {
      ADD_FAILURE() << backend << ": " << limit << " colour targets refused: " << e.what();
    }
    const std::string over = std::to_string(limit + 1) +
                             " colour targets; the device allows at most " + std::to_string(limit) +
                             " (Device::maxColorAttachments)";
    for (const auto& [call, breakIt] : std::vector<std::pair<std::string, std::function<void()>>>{
             {"createPipeline('contract.wide', technique 'tests'): ",
              [&] { w.widePipeline(limit + 1); }},
             {"beginPass('contract.wide'): ", [&] {
                w.dev.beginFrame();
                w.dev.beginPass(w.widePass(limit + 1));
              }}}) {
      try {
        breakIt();
        ADD_FAILURE() << backend << ": " << call << "accepted " << limit + 1 << " colour targets";
      } catch (const DeviceError& e) {
        EXPECT_EQ(e.what(), call + over) << backend;
      }
    }
  }
  if (limits.empty()) GTEST_SKIP() << "no backend available";
  std::cout << "[          ] maxColorAttachments:";
  for (const auto& [backend, limit] : limits) std::cout << " " << backend << " " << limit;
  std::cout << "\n";
}

// A multisampled pass on both APIs: a full-screen triangle whose fragment
// shader keeps 2 of 4 samples (gl_SampleMask), over multisampled depth, is
// averaged by the resolve into half its colour; memory counts every sample.
// A mask of all samples gives the whole colour (the test can fail both ways).
TEST(DeviceContract, MultisampledPassResolvesTheSampleMask) {
  const ShaderCode frag = shader("tests/contract_mask.frag", R"(
layout(std430, binding = 1) readonly buffer Mask { int mask; };
layout(location = 0) out vec4 outColor;
void main() {
  outColor = vec4(1.0, 0.5, 0.25, 1.0);
  gl_SampleMask[0] = mask;
}
)");
  const float tri[] = {-1, -1, 0.5f, 1, 3, -1, 0.5f, 1, -1, 3, 0.5f, 1};
  int ran = 0;
  for (auto& [backend, dev] : availableDevices()) {
    if (!dev->supportsSamples(4)) {
      ADD_FAILURE() << backend << " has no 4-sample targets (" << dev->sampleCountsText() << ")";
      continue;
    }
    ++ran;
    const Buffer pos =
        dev->createBuffer({"pos", Owner::Test, BufferUsage::Storage, sizeof tri}, tri);
    const Texture ms = dev->createTexture({"ms", Owner::Test, Format::RGBA32F, 8, 8, false, 1, 4});
    const Texture msDepth =
        dev->createTexture({"msd", Owner::Test, Format::Depth32F, 8, 8, false, 1, 4});
    const Texture out = dev->createTexture({"out", Owner::Test, Format::RGBA32F, 8, 8, false});
    PipelineDesc d;
    d.name = "contract.mask";
    d.technique = "tests";
    d.vertex = &kVert;
    d.fragment = &frag;
    d.colorFormats = {Format::RGBA32F};
    d.hasDepth = d.depthTest = d.depthWrite = true;
    d.samples = 4;
    d.bindings = {{0, BindingKind::StorageBuffer}, {1, BindingKind::StorageBuffer}};
    const Pipeline p = dev->createPipeline(d);
    for (const int mask : {0x3, 0xf}) {
      const Buffer m = dev->createBuffer({"mask", Owner::Test, BufferUsage::Storage, 4}, &mask);
      PassDesc pass;
      pass.name = "contract.ms";
      pass.color = {{ms, LoadOp::Clear, {0, 0, 0, 0}, {}, 0, out}};
      pass.depth = {msDepth, LoadOp::Clear, 1.0f};
      dev->beginFrame();
      dev->beginPass(pass);
      dev->draw(p, {Binding::buf(0, pos), Binding::buf(1, m)}, 3);
      dev->endPass();
      dev->endFrame();
      const auto bytes = dev->readTexture(out);
      const float k = mask == 0xf ? 1.0f : 0.5f;
      for (std::size_t i = 0; i < bytes.size(); i += 16) {
        float px[4];
        std::memcpy(px, bytes.data() + i, 16);
        EXPECT_NEAR(px[0], 1.0f * k, 1e-5) << backend << " mask " << mask << " byte " << i;
        EXPECT_NEAR(px[1], 0.5f * k, 1e-5) << backend << " mask " << mask;
        EXPECT_NEAR(px[3], 1.0f * k, 1e-5) << backend << " mask " << mask;
      }
    }
    bool counted = false;
    for (const ResourceBytes& r : dev->allocations())
      if (r.name == "ms") counted = r.bytes == 8u * 8 * 16 * 4;
    EXPECT_TRUE(counted) << backend << ": memory counts 4 samples of 16 bytes per pixel";
  }
  if (ran == 0) GTEST_SKIP() << "no backend available";
}

// Fresh resources read back as zero (colour, buffers) and 1 (depth) on both APIs.
TEST(DeviceContract, FreshResourcesHaveDefinedContents) {
  for (auto& [backend, dev] : availableDevices()) {
    const Texture c = dev->createTexture({"c", Owner::Test, Format::RGBA32F, 4, 4, false});
    const Texture d = dev->createTexture({"d", Owner::Test, Format::Depth32F, 4, 4, false});
    const Buffer b = dev->createBuffer({"b", Owner::Test, BufferUsage::Storage, 40});
    for (uint8_t byte : dev->readTexture(c)) EXPECT_EQ(byte, 0) << backend;
    for (uint8_t byte : dev->readBuffer(b)) EXPECT_EQ(byte, 0) << backend;
    const auto depth = dev->readTexture(d);
    for (std::size_t i = 0; i < depth.size(); i += 4) {
      float v = 0;
      std::memcpy(&v, depth.data() + i, 4);
      EXPECT_EQ(v, 1.0f) << backend;
    }
  }
}

// writeTexture is readTexture's inverse (every layer), on both APIs; a wrong
// size and a headless present are refused.
TEST(DeviceContract, WriteTextureRoundTripsAndPresentNeedsAWindow) {
  for (auto& [backend, dev] : availableDevices()) {
    for (const TextureDesc& desc :
         {TextureDesc{"one", Owner::Test, Format::RGBA8, 5, 3, false},
          TextureDesc{"array", Owner::Test, Format::RGBA32F, 4, 2, false, 3}}) {
      const Texture t = dev->createTexture(desc);
      std::vector<uint8_t> bytes(dev->readTexture(t).size());
      for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = uint8_t(i * 7 + 1);
      if (desc.format == Format::RGBA32F)  // finite floats: NaN bytes need not survive
        for (std::size_t i = 0; i < bytes.size(); i += 4) {
          const float v = float(i) * 0.25f;
          std::memcpy(bytes.data() + i, &v, 4);
        }
      dev->writeTexture(t, bytes);
      EXPECT_EQ(dev->readTexture(t), bytes) << backend << " " << desc.name;
      EXPECT_THROW(dev->writeTexture(t, std::vector<uint8_t>(bytes.size() - 1)), DeviceError);
    }
    EXPECT_EQ(dev->window(), nullptr) << backend;
    const Texture c = dev->createTexture({"c", Owner::Test, Format::RGBA32F, 4, 4, false});
    EXPECT_THROW(dev->present(c), DeviceError) << backend;
  }
}

}  // namespace
}  // namespace sb
