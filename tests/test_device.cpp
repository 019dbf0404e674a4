// Device contract tests, run on every backend that can be created here (a
// backend whose createDevice() throws DeviceError is skipped with its message).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "backends/device.h"

namespace sb {
namespace {

constexpr uint32_t kSize = 16;

ShaderCode shader(const std::string& name, const std::string& text) {
  return ShaderCode{name, text, {name}};
}

// Positions (vec4) pulled from a storage buffer; colour from a uniform block.
const ShaderCode kPosVert = shader("tests/inline.vert", R"(
layout(std430, binding = 0) readonly buffer Positions { vec4 pos[]; };
void main() { gl_Position = pos[gl_VertexIndex]; }
)");
const ShaderCode kColorFrag = shader("tests/inline.frag", R"(
layout(std140, binding = 1) uniform Params { vec4 color; };
layout(location = 0) out vec4 outColor;
void main() { outColor = color; }
)");
const ShaderCode kUintFrag = shader("tests/inline_uint.frag", R"(
layout(std140, binding = 1) uniform Params { uvec4 value; };
layout(location = 0) out uvec4 outValue;
void main() { outValue = value; }
)");
const ShaderCode kEmptyFrag = shader("tests/empty.frag", R"(
void main() {}
)");
const ShaderCode kSampleDepthFrag = shader("tests/sample_depth.frag", R"(
layout(binding = 2) uniform sampler2D depthTex;
layout(location = 0) out vec4 outColor;
void main() {
  vec2 uv = gl_FragCoord.xy / vec2(textureSize(depthTex, 0));
  outColor = vec4(texture(depthTex, uv).r, 0.0, 0.0, 1.0);
}
)");
const ShaderCode kAtomicComp = shader("tests/atomic.comp", R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Counter { uint count; uint values[]; };
void main() {
  atomicAdd(count, 1u);
  values[gl_GlobalInvocationID.x] = gl_GlobalInvocationID.x * 2u;
}
)");

// Two layers of one array in one pass: layer 2 gets the colour, layer 0 twice it.
const ShaderCode kTwoTargetsFrag = shader("tests/two_targets.frag", R"(
layout(std140, binding = 1) uniform Params { vec4 color; };
layout(location = 0) out vec4 outFirst;
layout(location = 1) out vec4 outSecond;
void main() {
  outFirst = color;
  outSecond = 2.0 * color;
}
)");
// Every layer of an array, sampled at once: L0 + 10 L2 + 100 L1, and the layer count.
const ShaderCode kSampleLayersFrag = shader("tests/sample_layers.frag", R"(
layout(binding = 2) uniform sampler2DArray layersTex;
layout(location = 0) out vec4 outColor;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 sum = vec4(0.0);
  const float scale[3] = float[3](1.0, 100.0, 10.0);
  for (int l = 0; l < textureSize(layersTex, 0).z; ++l)
    sum += scale[l] * texelFetch(layersTex, ivec3(p, l), 0);
  outColor = vec4(sum.rgb, float(textureSize(layersTex, 0).z));
}
)");
// A one-layer integer texture sampled as an array of one.
const ShaderCode kSampleUintArrayFrag = shader("tests/sample_uint_array.frag", R"(
layout(binding = 2) uniform usampler2DArray bitsTex;
layout(location = 0) out vec4 outColor;
void main() {
  outColor = vec4(texelFetch(bitsTex, ivec3(ivec2(gl_FragCoord.xy), 0), 0));
}
)");

using Quad = std::vector<float>;  // vec4 per vertex

// Two triangles covering x in [x0,x1], y in [y0,y1] (NDC) at depth z.
Quad quad(float x0, float y0, float x1, float y1, float z = 0.5f) {
  return {x0, y0, z, 1, x1, y0, z, 1, x1, y1, z, 1, x0, y0, z, 1, x1, y1, z, 1, x0, y1, z, 1};
}

template <class T>
T at(const std::vector<uint8_t>& data, std::size_t index) {
  T v;
  std::memcpy(&v, data.data() + index * sizeof(T), sizeof(T));
  return v;
}

class DeviceTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    messagesBefore_ = validationMessageCount();
    DeviceOptions opts;
    opts.backend = GetParam();
    opts.platform = GetParam() == "vulkan" ? "headless" : "egl";
    opts.validation = true;
    try {
      dev_ = createDevice(opts);
    } catch (const DeviceError& e) {
      GTEST_SKIP() << GetParam() << " backend unavailable: " << e.what();
    }
  }

  void TearDown() override {
    dev_.reset();
    // Covers device creation, the test's work and destruction.
    EXPECT_EQ(validationMessageCount(), messagesBefore_) << "validation messages (see stderr)";
  }

  Buffer makeBuffer(const std::string& name, BufferUsage usage, const void* data,
                    std::size_t bytes) {
    return dev_->createBuffer({name, Owner::Test, usage, bytes}, data);
  }
  Buffer positions(const Quad& q) {
    return makeBuffer("positions", BufferUsage::Storage, q.data(), q.size() * sizeof(float));
  }
  Buffer color(float r, float g, float b, float a) {
    const float c[4] = {r, g, b, a};
    return makeBuffer("color", BufferUsage::Uniform, c, sizeof(c));
  }
  Texture target(Format f, const std::string& name = "target") {
    return dev_->createTexture({name, Owner::Test, f, kSize, kSize, false});
  }
  PipelineDesc colorPipeline(Format f, const ShaderCode* frag = &kColorFrag) {
    PipelineDesc d;
    d.name = "test-pipeline";
    d.technique = "tests";
    d.vertex = &kPosVert;
    d.fragment = frag;
    d.colorFormats = {f};
    d.bindings = {{0, BindingKind::StorageBuffer}, {1, BindingKind::UniformBuffer}};
    return d;
  }
  static PassDesc pass(const std::string& name, Texture t, std::array<float, 4> clear) {
    PassDesc p;
    p.name = name;
    ColorAttachment a;
    a.texture = t;
    a.clear = clear;
    p.color = {a};
    return p;
  }

  std::unique_ptr<Device> dev_;
  std::size_t messagesBefore_ = 0;
};

TEST_P(DeviceTest, InfoNamesBackend) {
  const DeviceInfo info = dev_->info();
  EXPECT_EQ(info.backend, GetParam());
  EXPECT_FALSE(info.device.empty());
  EXPECT_FALSE(info.driver.empty());
}

TEST_P(DeviceTest, ClearAndLowerHalfQuadRGBA8) {
  Texture t = target(Format::RGBA8);
  Buffer pos = positions(quad(-1, -1, 1, 0));  // lower half of NDC: y in [-1, 0]
  Buffer col = color(1, 0, 0, 1);
  Pipeline p = dev_->createPipeline(colorPipeline(Format::RGBA8));
  dev_->beginFrame();
  dev_->beginPass(pass("main", t, {0, 0, 1, 1}));
  dev_->draw(p, {Binding::buf(0, pos), Binding::buf(1, col)}, 6);
  dev_->endPass();
  dev_->endFrame();
  const std::vector<uint8_t> px = dev_->readTexture(t);
  ASSERT_EQ(px.size(), kSize * kSize * 4);
  for (uint32_t y = 0; y < kSize; ++y) {
    for (uint32_t x = 0; x < kSize; ++x) {
      const uint8_t* p4 = &px[(y * kSize + x) * 4];
      const bool lower = y < kSize / 2;  // row 0 = NDC y=-1
      EXPECT_EQ(p4[0], lower ? 255 : 0) << "x=" << x << " y=" << y;
      EXPECT_EQ(p4[1], 0) << "x=" << x << " y=" << y;
      EXPECT_EQ(p4[2], lower ? 0 : 255) << "x=" << x << " y=" << y;
      EXPECT_EQ(p4[3], 255) << "x=" << x << " y=" << y;
    }
  }
}

TEST_P(DeviceTest, TriangleRGBA32F) {
  Texture t = target(Format::RGBA32F);
  // One triangle covering the left half of the lower half exactly (x <= 0, y <= 0)
  // would have a diagonal edge; use a quad in the upper-left quadrant instead.
  Buffer pos = positions(quad(-1, 0, 0, 1));
  Buffer col = color(0.25f, 0.5f, 2.0f, 1.0f);
  Pipeline p = dev_->createPipeline(colorPipeline(Format::RGBA32F));
  dev_->beginFrame();
  dev_->beginPass(pass("main", t, {-1, 0.125f, 0, 0}));
  dev_->draw(p, {Binding::buf(0, pos), Binding::buf(1, col)}, 6);
  dev_->endPass();
  dev_->endFrame();
  const std::vector<uint8_t> px = dev_->readTexture(t);
  ASSERT_EQ(px.size(), kSize * kSize * 16);
  for (uint32_t y = 0; y < kSize; ++y) {
    for (uint32_t x = 0; x < kSize; ++x) {
      const std::size_t i = (y * kSize + x) * 4;
      const bool inside = y >= kSize / 2 && x < kSize / 2;
      EXPECT_EQ(at<float>(px, i + 0), inside ? 0.25f : -1.0f) << x << "," << y;
      EXPECT_EQ(at<float>(px, i + 1), inside ? 0.5f : 0.125f) << x << "," << y;
      EXPECT_EQ(at<float>(px, i + 2), inside ? 2.0f : 0.0f) << x << "," << y;
      EXPECT_EQ(at<float>(px, i + 3), inside ? 1.0f : 0.0f) << x << "," << y;
    }
  }
}

TEST_P(DeviceTest, DepthTest) {
  Texture t = target(Format::RGBA8);
  Texture depth = target(Format::Depth32F, "depth");
  Buffer full = positions(quad(-1, -1, 1, 1, 0.5f));
  Buffer behind = positions(quad(-1, -1, 1, 1, 0.7f));
  Buffer leftFront = positions(quad(-1, -1, 0, 1, 0.25f));
  Buffer red = color(1, 0, 0, 1), green = color(0, 1, 0, 1), blue = color(0, 0, 1, 1);
  PipelineDesc d = colorPipeline(Format::RGBA8);
  d.hasDepth = true;
  d.depthTest = true;
  d.depthWrite = true;
  d.depthCompare = CompareOp::Less;
  Pipeline p = dev_->createPipeline(d);
  PassDesc pd = pass("depth", t, {0, 0, 0, 1});
  pd.depth.texture = depth;
  pd.depth.clear = 1.0f;
  dev_->beginFrame();
  dev_->beginPass(pd);
  dev_->draw(p, {Binding::buf(0, full), Binding::buf(1, red)}, 6);
  dev_->draw(p, {Binding::buf(0, behind), Binding::buf(1, green)}, 6);
  dev_->draw(p, {Binding::buf(0, leftFront), Binding::buf(1, blue)}, 6);
  dev_->endPass();
  dev_->endFrame();
  const std::vector<uint8_t> px = dev_->readTexture(t);
  const std::vector<uint8_t> dz = dev_->readTexture(depth);
  ASSERT_EQ(dz.size(), kSize * kSize * 4);
  for (uint32_t y = 0; y < kSize; ++y) {
    for (uint32_t x = 0; x < kSize; ++x) {
      const std::size_t i = y * kSize + x;
      const bool left = x < kSize / 2;
      EXPECT_EQ(px[i * 4 + 0], left ? 0 : 255) << x << "," << y;
      EXPECT_EQ(px[i * 4 + 1], 0) << x << "," << y;
      EXPECT_EQ(px[i * 4 + 2], left ? 255 : 0) << x << "," << y;
      EXPECT_NEAR(at<float>(dz, i), left ? 0.25f : 0.5f, 1e-6f) << x << "," << y;
    }
  }
}

TEST_P(DeviceTest, BlendModes) {
  struct Case {
    const char* name;
    BlendState state;
    std::array<float, 4> expected;
  };
  // dst = 0.5 everywhere, src = (1, 0.25, 0, 0.5).
  const Case cases[] = {
      {"over", BlendState::over(), {0.75f, 0.375f, 0.25f, 0.75f}},
      {"additive", BlendState::additive(), {1.5f, 0.75f, 0.5f, 1.0f}},
      {"min", BlendState::min(), {0.5f, 0.25f, 0.0f, 0.5f}},
      {"max", BlendState::max(), {1.0f, 0.5f, 0.5f, 0.5f}},
  };
  Buffer pos = positions(quad(-1, -1, 1, 1));
  Buffer col = color(1, 0.25f, 0, 0.5f);
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    Texture t = target(Format::RGBA32F);
    PipelineDesc d = colorPipeline(Format::RGBA32F);
    d.blend = {c.state};
    Pipeline p = dev_->createPipeline(d);
    dev_->beginFrame();
    dev_->beginPass(pass(c.name, t, {0.5f, 0.5f, 0.5f, 0.5f}));
    dev_->draw(p, {Binding::buf(0, pos), Binding::buf(1, col)}, 6);
    dev_->endPass();
    dev_->endFrame();
    const std::vector<uint8_t> px = dev_->readTexture(t);
    for (std::size_t i : {std::size_t{0}, std::size_t{kSize * kSize - 1}}) {
      for (int ch = 0; ch < 4; ++ch) {
        EXPECT_FLOAT_EQ(at<float>(px, i * 4 + ch), c.expected[ch]) << "channel " << ch;
      }
    }
    dev_->destroy(t);
  }
}

TEST_P(DeviceTest, LogicOpOrOnRGBA32UI) {
  Texture t = target(Format::RGBA32UI);
  Buffer full = positions(quad(-1, -1, 1, 1));
  Buffer lower = positions(quad(-1, -1, 1, 0));
  const uint32_t bitsA[4] = {1, 2, 4, 8}, bitsB[4] = {16, 32, 64, 128};
  Buffer a = makeBuffer("a", BufferUsage::Uniform, bitsA, sizeof(bitsA));
  Buffer b = makeBuffer("b", BufferUsage::Uniform, bitsB, sizeof(bitsB));
  PipelineDesc d = colorPipeline(Format::RGBA32UI, &kUintFrag);
  d.logicOpOr = true;
  Pipeline p = dev_->createPipeline(d);
  PassDesc pd = pass("or", t, {});
  pd.color[0].clearUint = {0x100, 0, 0, 0};
  dev_->beginFrame();
  dev_->beginPass(pd);
  dev_->draw(p, {Binding::buf(0, full), Binding::buf(1, a)}, 6);
  dev_->draw(p, {Binding::buf(0, lower), Binding::buf(1, b)}, 6);
  dev_->endPass();
  dev_->endFrame();
  const std::vector<uint8_t> px = dev_->readTexture(t);
  for (uint32_t y = 0; y < kSize; ++y) {
    const std::size_t i = y * kSize + 3;
    const bool both = y < kSize / 2;
    EXPECT_EQ(at<uint32_t>(px, i * 4 + 0), both ? 0x111u : 0x101u) << "y=" << y;
    EXPECT_EQ(at<uint32_t>(px, i * 4 + 1), both ? 34u : 2u) << "y=" << y;
    EXPECT_EQ(at<uint32_t>(px, i * 4 + 2), both ? 68u : 4u) << "y=" << y;
    EXPECT_EQ(at<uint32_t>(px, i * 4 + 3), both ? 136u : 8u) << "y=" << y;
  }
}

TEST_P(DeviceTest, SampledDepthFromPreviousPass) {
  Texture depth = target(Format::Depth32F, "shadow-depth");
  Texture out = target(Format::R32F, "out");
  Buffer lower = positions(quad(-1, -1, 1, 0, 0.25f));
  Buffer full = positions(quad(-1, -1, 1, 1));
  PipelineDesc dd = colorPipeline(Format::R32F, &kEmptyFrag);
  dd.colorFormats = {};
  dd.hasDepth = true;
  dd.depthTest = true;
  dd.depthWrite = true;
  dd.bindings = {{0, BindingKind::StorageBuffer}};
  Pipeline depthOnly = dev_->createPipeline(dd);
  PipelineDesc sd = colorPipeline(Format::R32F, &kSampleDepthFrag);
  sd.bindings = {{0, BindingKind::StorageBuffer}, {2, BindingKind::SampledTexture}};
  Pipeline sample = dev_->createPipeline(sd);

  dev_->beginFrame();
  PassDesc p1;
  p1.name = "shadow";
  p1.depth.texture = depth;
  dev_->beginPass(p1);
  dev_->draw(depthOnly, {Binding::buf(0, lower)}, 6);
  dev_->endPass();
  PassDesc p2 = pass("resolve", out, {-1, 0, 0, 0});
  p2.sampledTextures = {depth};
  dev_->beginPass(p2);
  dev_->draw(sample, {Binding::buf(0, full), Binding::tex(2, depth)}, 6);
  dev_->endPass();
  dev_->endFrame();
  const std::vector<uint8_t> px = dev_->readTexture(out);
  for (uint32_t y = 0; y < kSize; ++y) {
    EXPECT_FLOAT_EQ(at<float>(px, y * kSize + 5), y < kSize / 2 ? 0.25f : 1.0f) << "y=" << y;
  }
}

TEST_P(DeviceTest, UndeclaredSampledTextureThrows) {
  Texture depth = target(Format::Depth32F, "depth");
  Texture out = target(Format::R32F, "out");
  Buffer full = positions(quad(-1, -1, 1, 1));
  PipelineDesc sd = colorPipeline(Format::R32F, &kSampleDepthFrag);
  sd.bindings = {{0, BindingKind::StorageBuffer}, {2, BindingKind::SampledTexture}};
  Pipeline sample = dev_->createPipeline(sd);
  dev_->beginFrame();
  dev_->beginPass(pass("resolve", out, {0, 0, 0, 0}));  // depth not in sampledTextures
  EXPECT_THROW(dev_->draw(sample, {Binding::buf(0, full), Binding::tex(2, depth)}, 6), DeviceError);
  dev_->endPass();
  dev_->endFrame();
}

TEST_P(DeviceTest, UpdateUniformBufferBetweenPasses) {
  Texture t1 = target(Format::RGBA32F, "first");
  Texture t2 = target(Format::RGBA32F, "second");
  Buffer pos = positions(quad(-1, -1, 1, 1));
  Buffer col = color(1, 2, 3, 4);
  Pipeline p = dev_->createPipeline(colorPipeline(Format::RGBA32F));
  const float second[4] = {5, 6, 7, 8};
  dev_->beginFrame();
  dev_->beginPass(pass("first", t1, {0, 0, 0, 0}));
  dev_->draw(p, {Binding::buf(0, pos), Binding::buf(1, col)}, 6);
  EXPECT_THROW(dev_->updateBuffer(col, second, sizeof(second)), DeviceError);  // inside a pass
  dev_->endPass();
  dev_->updateBuffer(col, second, sizeof(second));
  dev_->beginPass(pass("second", t2, {0, 0, 0, 0}));
  dev_->draw(p, {Binding::buf(0, pos), Binding::buf(1, col)}, 6);
  dev_->endPass();
  dev_->endFrame();
  const std::vector<uint8_t> a = dev_->readTexture(t1), b = dev_->readTexture(t2);
  for (int ch = 0; ch < 4; ++ch) {
    EXPECT_EQ(at<float>(a, 17 * 4 + ch), float(ch + 1));
    EXPECT_EQ(at<float>(b, 17 * 4 + ch), float(ch + 5));
  }
}

TEST_P(DeviceTest, UpdateBufferUnalignedAndLarge) {
  std::vector<uint8_t> initial(70000);
  for (std::size_t i = 0; i < initial.size(); ++i) initial[i] = uint8_t(i * 7);
  Buffer b = makeBuffer("big", BufferUsage::Storage, initial.data(), initial.size());
  EXPECT_EQ(dev_->readBuffer(b), initial);
  // Outside a frame.
  const uint8_t three[3] = {1, 2, 3};
  dev_->updateBuffer(b, three, 3, 5);
  std::copy(three, three + 3, initial.begin() + 5);
  // Inside a frame, between passes: unaligned (staged) and large (staged).
  std::vector<uint8_t> large(68000, 0xAB);
  dev_->beginFrame();
  dev_->updateBuffer(b, three, 3, 101);
  dev_->updateBuffer(b, large.data(), large.size(), 1000);
  dev_->endFrame();
  std::copy(three, three + 3, initial.begin() + 101);
  std::copy(large.begin(), large.end(), initial.begin() + 1000);
  EXPECT_EQ(dev_->readBuffer(b), initial);
  EXPECT_THROW(dev_->updateBuffer(b, three, 3, initial.size() - 1), DeviceError);
}

TEST_P(DeviceTest, ComputeAtomics) {
  const uint32_t invocations = 256;
  Buffer b = makeBuffer("counter", BufferUsage::Storage, nullptr, (1 + invocations) * 4);
  PipelineDesc d;
  d.name = "atomic";
  d.technique = "tests";
  d.compute = &kAtomicComp;
  d.bindings = {{0, BindingKind::StorageBuffer}};
  Pipeline p = dev_->createPipeline(d);
  dev_->beginFrame();
  dev_->fillBuffer(b, 5);
  dev_->dispatch("atomics", p, {Binding::buf(0, b)}, invocations / 64);
  dev_->dispatch("atomics-again", p, {Binding::buf(0, b)}, invocations / 64);
  dev_->endFrame();
  const std::vector<uint8_t> data = dev_->readBuffer(b);
  EXPECT_EQ(at<uint32_t>(data, 0), 5u + 2 * invocations);
  for (uint32_t i = 0; i < invocations; ++i) EXPECT_EQ(at<uint32_t>(data, 1 + i), 2 * i);
  const std::vector<PassTiming> timings = dev_->lastFrameTimings();
  ASSERT_EQ(timings.size(), 2u);
  EXPECT_EQ(timings[0].name, "atomics");
  EXPECT_EQ(timings[1].name, "atomics-again");
}

TEST_P(DeviceTest, LinesTopology) {
  Texture t = target(Format::R32F);
  // Horizontal line through the centres of row 4, from the centre of column 0 to
  // the centre of column 15; a vertical one through column 12, rows 8..15.
  const float rowY = (4.5f / kSize) * 2 - 1, c0 = (0.5f / kSize) * 2 - 1;
  const float c15 = (15.5f / kSize) * 2 - 1, colX = (12.5f / kSize) * 2 - 1;
  const float r8 = (8.5f / kSize) * 2 - 1, r15 = (15.5f / kSize) * 2 - 1;
  Buffer pos = positions({c0, rowY, 0, 1, c15, rowY, 0, 1, colX, r8, 0, 1, colX, r15, 0, 1});
  Buffer col = color(1, 0, 0, 0);
  PipelineDesc d = colorPipeline(Format::R32F);
  d.topology = Topology::Lines;
  Pipeline p = dev_->createPipeline(d);
  dev_->beginFrame();
  dev_->beginPass(pass("lines", t, {0, 0, 0, 0}));
  dev_->draw(p, {Binding::buf(0, pos), Binding::buf(1, col)}, 4);
  dev_->endPass();
  dev_->endFrame();
  const std::vector<uint8_t> px = dev_->readTexture(t);
  int rowLit = 0, colLit = 0;
  for (uint32_t y = 0; y < kSize; ++y) {
    for (uint32_t x = 0; x < kSize; ++x) {
      const bool lit = at<float>(px, y * kSize + x) > 0.5f;
      if (y == 4) {
        rowLit += lit;
        if (x >= 1 && x <= 14) {
          EXPECT_TRUE(lit) << x << "," << y;
        }
      } else if (x == 12) {
        colLit += lit;
        if (y >= 9 && y <= 14) {
          EXPECT_TRUE(lit) << x << "," << y;
        }
        if (y < 8) {
          EXPECT_FALSE(lit) << x << "," << y;
        }
      } else {
        EXPECT_FALSE(lit) << x << "," << y;
      }
    }
  }
  EXPECT_GE(rowLit, 14);
  EXPECT_LE(rowLit, 16);
  EXPECT_GE(colLit, 6);
  EXPECT_LE(colLit, 8);
}

// While making is deferred, a buffer created with contents is declared, not
// made: the renderer puts its whole plan to the memory guard first. It is made
// with those contents when first used or by makeDeferredBuffers.
TEST_P(DeviceTest, DeferredMakingKeepsContentsUntilTheBufferIsMade) {
  const std::vector<uint32_t> words = {1, 2, 3, 4};
  dev_->setDeferMaking(true);
  const Buffer a = dev_->createBuffer({"a", Owner::Scene, BufferUsage::Storage, 16}, words.data());
  const Buffer b = dev_->createBuffer({"b", Owner::Scene, BufferUsage::Storage, 16}, words.data());
  dev_->setDeferMaking(false);
  EXPECT_TRUE(dev_->allocations().empty());
  EXPECT_EQ(dev_->declared().size(), 2u);
  std::vector<uint8_t> expected(16);
  std::memcpy(expected.data(), words.data(), 16);
  EXPECT_EQ(dev_->readBuffer(a), expected);  // its contents, still not made
  EXPECT_TRUE(dev_->allocations().empty());
  dev_->fillBuffer(a, 7);  // made when first used
  EXPECT_EQ(dev_->allocations().size(), 1u);
  dev_->makeDeferredBuffers();
  EXPECT_EQ(dev_->allocations().size(), 2u);
  EXPECT_EQ(dev_->readBuffer(b), expected);
  // Control: not deferred, it is made at once.
  dev_->createBuffer({"c", Owner::Scene, BufferUsage::Storage, 16}, words.data());
  EXPECT_EQ(dev_->allocations().size(), 3u);
}

TEST_P(DeviceTest, MemoryAccounting) {
  EXPECT_TRUE(dev_->allocations().empty());
  Buffer a = dev_->createBuffer({"hair-vertices", Owner::Scene, BufferUsage::Storage, 1000});
  Buffer u = dev_->createBuffer({"params", Owner::Frame, BufferUsage::Uniform, 64});
  Texture t = dev_->createTexture({"occupancy", Owner::Shadow, Format::RGBA32UI, 16, 8, false});
  Texture d = dev_->createTexture({"depth", Owner::Shadow, Format::Depth32F, 7, 3, false});
  Texture c = dev_->createTexture({"accum", Owner::Oit, Format::RGBA16F, 5, 5, true});
  // Declared, not yet made: nothing has used them.
  EXPECT_TRUE(dev_->allocations().empty());
  EXPECT_EQ(dev_->declared().size(), 5u);
  dev_->readBuffer(a);
  dev_->readBuffer(u);
  for (Texture x : {t, d, c}) dev_->readTexture(x);
  std::vector<ResourceBytes> all = dev_->allocations();
  ASSERT_EQ(all.size(), 5u);
  EXPECT_EQ(dev_->declared().size(), 5u);
  auto find = [&](const std::string& name) {
    for (const ResourceBytes& r : all) {
      if (r.name == name) return r;
    }
    ADD_FAILURE() << name << " missing";
    return ResourceBytes{};
  };
  EXPECT_EQ(find("hair-vertices").bytes, 1000u);
  EXPECT_EQ(find("hair-vertices").owner, Owner::Scene);
  EXPECT_EQ(find("params").bytes, 64u);
  EXPECT_EQ(find("params").owner, Owner::Frame);
  EXPECT_EQ(find("occupancy").bytes, 16u * 8 * 16);
  EXPECT_EQ(find("occupancy").owner, Owner::Shadow);
  EXPECT_EQ(find("depth").bytes, 7u * 3 * 4);
  EXPECT_EQ(find("accum").bytes, 5u * 5 * 8);
  EXPECT_EQ(find("accum").owner, Owner::Oit);
  dev_->destroy(a);
  dev_->destroy(t);
  all = dev_->allocations();
  ASSERT_EQ(all.size(), 3u);
  for (const ResourceBytes& r : all) {
    EXPECT_NE(r.name, "hair-vertices");
    EXPECT_NE(r.name, "occupancy");
  }
  dev_->destroy(u);
  dev_->destroy(d);
  dev_->destroy(c);
  EXPECT_TRUE(dev_->allocations().empty());
}

TEST_P(DeviceTest, CompileErrorNamesFileLineAndTechnique) {
  const ShaderCode broken{"techniques/broken/broken.frag",
                          "layout(location = 0) out vec4 outColor;\n"
                          "void main() {\n"
                          "  outColor = vec4(1.0) this is wrong;\n"
                          "}\n",
                          {"techniques/broken/broken.frag"}};
  PipelineDesc d = colorPipeline(Format::RGBA8, &broken);
  d.technique = "broken-technique";
  try {
    dev_->createPipeline(d);
    FAIL() << "expected DeviceError";
  } catch (const DeviceError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("techniques/broken/broken.frag:3"), std::string::npos) << msg;
    EXPECT_NE(msg.find("broken-technique"), std::string::npos) << msg;
  }
}

TEST_P(DeviceTest, TimingsPerPassInOrder) {
  Texture t = target(Format::RGBA8);
  Buffer pos = positions(quad(-1, -1, 1, 1));
  Buffer col = color(1, 1, 1, 1);
  Buffer counter = makeBuffer("counter", BufferUsage::Storage, nullptr, 257 * 4);
  Pipeline p = dev_->createPipeline(colorPipeline(Format::RGBA8));
  PipelineDesc cd;
  cd.name = "atomic";
  cd.technique = "tests";
  cd.compute = &kAtomicComp;
  cd.bindings = {{0, BindingKind::StorageBuffer}};
  Pipeline c = dev_->createPipeline(cd);
  for (int frame = 0; frame < 2; ++frame) {
    dev_->beginFrame();
    dev_->beginPass(pass("alpha", t, {0, 0, 0, 0}));
    dev_->draw(p, {Binding::buf(0, pos), Binding::buf(1, col)}, 6);
    dev_->endPass();
    dev_->dispatch("beta", c, {Binding::buf(0, counter)}, 4);
    PassDesc g = pass("gamma", t, {0, 0, 0, 0});
    g.color[0].load = LoadOp::Load;
    dev_->beginPass(g);
    dev_->draw(p, {Binding::buf(0, pos), Binding::buf(1, col)}, 6);
    dev_->endPass();
    dev_->endFrame();
    const std::vector<PassTiming> timings = dev_->lastFrameTimings();
    ASSERT_EQ(timings.size(), 3u);
    EXPECT_EQ(timings[0].name, "alpha");
    EXPECT_EQ(timings[1].name, "beta");
    EXPECT_EQ(timings[2].name, "gamma");
    for (const PassTiming& pt : timings) {
      EXPECT_TRUE(std::isfinite(pt.ms)) << pt.name;
      EXPECT_GE(pt.ms, 0.0) << pt.name;
      EXPECT_LT(pt.ms, 10000.0) << pt.name;
    }
    // The work, by arithmetic: a full-screen quad (6 vertices, 2 triangles) covers
    // every pixel once; RGBA8 writes 4 bytes a pixel; the colour is a 16-byte
    // uniform, the quad's 6 vec4 a storage buffer. gamma also loads its target.
    const uint64_t pixels = kSize * kSize, quadBytes = 6 * 4 * sizeof(float);
    const PassWork& alpha = timings[0].work;
    ASSERT_TRUE(alpha.statistics) << "no pipeline statistics: " << dev_->info().counters;
    EXPECT_EQ(alpha.vertices, 6u);
    EXPECT_EQ(alpha.primitives, 2u);
    EXPECT_EQ(alpha.vertexInvocations, 6u);
    EXPECT_EQ(alpha.clipInvocations, 2u);
    EXPECT_EQ(alpha.clipPrimitives, 2u);
    // Fragment invocations may count helper invocations (the API leaves it to the
    // implementation): llvmpipe counts whole 2x2 quads, so the quads along the
    // diagonal, shaded once per triangle, count twice (320 for these 256 pixels).
    EXPECT_GE(alpha.fragmentInvocations, pixels);
    EXPECT_EQ(alpha.samplesPassed, pixels);
    EXPECT_EQ(alpha.computeInvocations, 0u);
    EXPECT_EQ(alpha.draws, 1u);
    EXPECT_EQ(alpha.dispatches, 0u);
    EXPECT_EQ(alpha.bytesWritten, pixels * 4);
    EXPECT_EQ(alpha.bytesRead, 16u);
    EXPECT_EQ(alpha.bytesStorage, quadBytes);
    const PassWork& beta = timings[1].work;
    EXPECT_EQ(beta.computeInvocations, 4u * 64u);  // 4 groups of 64
    EXPECT_EQ(beta.fragmentInvocations + beta.vertices + beta.samplesPassed, 0u);
    EXPECT_EQ(beta.dispatches, 1u);
    EXPECT_EQ(beta.bytesStorage, 257u * 4u);
    PassWork gammaExpected = alpha;
    gammaExpected.bytesRead += pixels * 4;
    gammaExpected.resources.insert(gammaExpected.resources.begin() + 1,
                                   {"target", "RGBA8", kSize, kSize, 1, 1, pixels * 4, "read"});
    EXPECT_EQ(timings[2].work, gammaExpected);
  }
}

TEST_P(DeviceTest, ManyDrawsAndPassesInOneFrame) {
  // More descriptor sets and timestamp queries than one pool holds.
  Texture t = target(Format::RGBA32F);
  Buffer pos = positions(quad(-1, -1, 1, 1));
  Buffer col = color(1.0f / 1024, 0, 0, 0);
  PipelineDesc d = colorPipeline(Format::RGBA32F);
  d.blend = {BlendState::additive()};
  Pipeline p = dev_->createPipeline(d);
  dev_->beginFrame();
  for (int i = 0; i < 130; ++i) {  // more passes than a pool of 128 work queries
    PassDesc pd = pass("pass" + std::to_string(i), t, {0, 0, 0, 0});
    if (i > 0) pd.color[0].load = LoadOp::Load;
    dev_->beginPass(pd);
    for (int j = 0; j < 10; ++j) dev_->draw(p, {Binding::buf(0, pos), Binding::buf(1, col)}, 6);
    dev_->endPass();
  }
  dev_->endFrame();
  const std::vector<PassTiming> timings = dev_->lastFrameTimings();
  ASSERT_EQ(timings.size(), 130u);
  EXPECT_EQ(timings.back().name, "pass129");
  EXPECT_EQ(timings.back().work.draws, 10u);
  EXPECT_EQ(timings.back().work.vertices, 60u);
  EXPECT_EQ(timings.back().work.samplesPassed, 10u * kSize * kSize);
  const std::vector<uint8_t> px = dev_->readTexture(t);
  EXPECT_FLOAT_EQ(at<float>(px, 0), 1300.0f / 1024);
}

// Two layers of one array as the two attachments of one pass (out of order,
// one layer left alone), then the whole array sampled by a later pass, and
// read back layer after layer.
TEST_P(DeviceTest, RenderIntoTwoLayersOfOneArrayAndSampleThem) {
  const Texture arr =
      dev_->createTexture({"layers", Owner::Test, Format::RGBA32F, kSize, kSize, false, 3});
  const Texture out = target(Format::RGBA32F, "out");
  Buffer lower = positions(quad(-1, -1, 1, 0));
  Buffer full = positions(quad(-1, -1, 1, 1));
  Buffer col = color(0.25f, 0.5f, 0.75f, 1.0f);
  PipelineDesc wd = colorPipeline(Format::RGBA32F, &kTwoTargetsFrag);
  wd.colorFormats = {Format::RGBA32F, Format::RGBA32F};
  Pipeline write = dev_->createPipeline(wd);
  PipelineDesc sd = colorPipeline(Format::RGBA32F, &kSampleLayersFrag);
  sd.bindings = {{0, BindingKind::StorageBuffer}, {2, BindingKind::SampledTextureArray}};
  Pipeline sample = dev_->createPipeline(sd);

  dev_->beginFrame();
  PassDesc p1;
  p1.name = "layers";
  p1.color = {{arr, LoadOp::Clear, {0.5f, 0.5f, 0.5f, 0.5f}, {}, 2},
              {arr, LoadOp::Clear, {0, 0, 0, 0}, {}, 0}};
  dev_->beginPass(p1);
  dev_->draw(write, {Binding::buf(0, lower), Binding::buf(1, col)}, 6);
  dev_->endPass();
  PassDesc p2 = pass("sample", out, {-1, -1, -1, -1});
  p2.sampledTextures = {arr};
  dev_->beginPass(p2);
  dev_->draw(sample, {Binding::buf(0, full), Binding::tex(2, arr)}, 6);
  dev_->endPass();
  dev_->endFrame();

  const std::vector<uint8_t> px = dev_->readTexture(out);
  for (uint32_t y = 0; y < kSize; ++y) {
    const std::size_t i = (y * kSize + 7) * 4;
    const bool lowerHalf = y < kSize / 2;
    // Lower: 2c + 10c = 12c; upper: 0 + 10 * 0.5; layer 1 is still zero.
    EXPECT_FLOAT_EQ(at<float>(px, i + 0), lowerHalf ? 3.0f : 5.0f) << "y=" << y;
    EXPECT_FLOAT_EQ(at<float>(px, i + 1), lowerHalf ? 6.0f : 5.0f) << "y=" << y;
    EXPECT_FLOAT_EQ(at<float>(px, i + 2), lowerHalf ? 9.0f : 5.0f) << "y=" << y;
    EXPECT_FLOAT_EQ(at<float>(px, i + 3), 3.0f) << "y=" << y;  // textureSize().z
  }

  const std::vector<uint8_t> layers = dev_->readTexture(arr);
  ASSERT_EQ(layers.size(), std::size_t{3} * kSize * kSize * 16);
  const std::size_t perLayer = std::size_t{kSize} * kSize * 4;  // floats
  for (uint32_t y = 0; y < kSize; ++y) {
    const std::size_t i = (y * kSize + 3) * 4;
    const bool lowerHalf = y < kSize / 2;
    EXPECT_FLOAT_EQ(at<float>(layers, i + 1), lowerHalf ? 1.0f : 0.0f) << "layer 0 y=" << y;
    EXPECT_FLOAT_EQ(at<float>(layers, perLayer + i + 1), 0.0f) << "layer 1 y=" << y;
    EXPECT_FLOAT_EQ(at<float>(layers, 2 * perLayer + i + 0), lowerHalf ? 0.25f : 0.5f)
        << "layer 2 y=" << y;
    EXPECT_FLOAT_EQ(at<float>(layers, 2 * perLayer + i + 2), lowerHalf ? 0.75f : 0.5f)
        << "layer 2 y=" << y;
  }
  // The accounting counts every layer.
  for (const ResourceBytes& r : dev_->allocations()) {
    if (r.name == "layers") {
      EXPECT_EQ(r.bytes, std::size_t{3} * kSize * kSize * 16);
    }
  }
}

// A one-layer texture is also an array of one (sampler2DArray), here an
// integer one written by logic-op OR, as the occupancy maps are.
TEST_P(DeviceTest, OneLayerTextureSampledAsAnArray) {
  const Texture bits = target(Format::RGBA32UI, "bits");
  const Texture out = target(Format::RGBA32F, "out");
  Buffer full = positions(quad(-1, -1, 1, 1));
  const uint32_t value[4] = {1, 2, 4, 8};
  Buffer v = makeBuffer("value", BufferUsage::Uniform, value, sizeof value);
  PipelineDesc wd = colorPipeline(Format::RGBA32UI, &kUintFrag);
  wd.logicOpOr = true;
  Pipeline write = dev_->createPipeline(wd);
  PipelineDesc sd = colorPipeline(Format::RGBA32F, &kSampleUintArrayFrag);
  sd.bindings = {{0, BindingKind::StorageBuffer}, {2, BindingKind::SampledTextureArray}};
  Pipeline sample = dev_->createPipeline(sd);
  dev_->beginFrame();
  PassDesc p1 = pass("bits", bits, {});
  p1.color[0].clearUint = {16, 0, 0, 0};
  dev_->beginPass(p1);
  dev_->draw(write, {Binding::buf(0, full), Binding::buf(1, v)}, 6);
  dev_->endPass();
  PassDesc p2 = pass("sample", out, {});
  p2.sampledTextures = {bits};
  dev_->beginPass(p2);
  dev_->draw(sample, {Binding::buf(0, full), Binding::tex(2, bits)}, 6);
  dev_->endPass();
  dev_->endFrame();
  const std::vector<uint8_t> px = dev_->readTexture(out);
  const std::size_t i = (5 * kSize + 9) * 4;
  EXPECT_FLOAT_EQ(at<float>(px, i + 0), 17.0f);
  EXPECT_FLOAT_EQ(at<float>(px, i + 1), 2.0f);
  EXPECT_FLOAT_EQ(at<float>(px, i + 2), 4.0f);
  EXPECT_FLOAT_EQ(at<float>(px, i + 3), 8.0f);
}

INSTANTIATE_TEST_SUITE_P(Backends, DeviceTest, ::testing::Values("gl", "vulkan"),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           return param.param;
                         });

// After everything above in this process: no validation message at all.
class NoValidationMessages : public ::testing::Environment {
 public:
  void TearDown() override { EXPECT_EQ(validationMessageCount(), 0u); }
};
const auto* const kNoValidationEnv = ::testing::AddGlobalTestEnvironment(new NoValidationMessages);

}  // namespace
}  // namespace sb
