// render/common/uniform_block.h: a uniform block declared once yields the
// GLSL block and a C++ struct whose layout is checked against std140 at compile
// time. The std140 rules are checked here on layouts where C++ and std140
// disagree (a scalar or vec3 after a vec4, an array of scalars), and the check
// of a block is shown to fail on such a layout: std140Mismatch() names the
// member here, and SB_UNIFORM_BLOCK_END's static_assert stops the build
// (the UniformBlockStd140CheckFails test in CMakeLists.txt compiles
// tests/data/uniform_block_bad.cpp and expects that error).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "backends/vulkan/vk_shader.h"
#include "render/common/peel_uniforms.h"
#include "render/common/shader_library.h"
#include "render/common/uniform_block.h"
#include "render/common/view_uniforms.h"
#include "techniques/osm/uniforms.h"

// clang-format off
// A block C++ lays out as std140 does: a vec3 then a float fill one vec4.
SB_UNIFORM_BLOCK(TestGoodBlock, 0)
  SB_FIELD(vec3, a)
  SB_FIELD(float, b)
  SB_FIELD(vec2, c)
  SB_FIELD(uint, d)
  SB_FIELD(int, e)
  SB_ARRAY(ivec4, f, 2)
  SB_FIELD(mat4, g)
SB_UNIFORM_BLOCK_END(TestGoodBlock)

// Blocks C++ lays out otherwise, closed without the static_assert.
// std140 puts the vec3 at 32 (a vec3 aligns as a vec4), C++ at 20.
SB_UNIFORM_BLOCK(TestBadVec3, 0)
  SB_FIELD(vec4, a)
  SB_FIELD(float, b)
  SB_FIELD(vec3, c)
SB_UNIFORM_BLOCK_END_UNCHECKED(TestBadVec3)
// std140 steps a float array by 16 bytes, C++ by 4: the vec4 after it moves.
SB_UNIFORM_BLOCK(TestBadArray, 0)
  SB_ARRAY(float, a, 4)
  SB_FIELD(vec4, b)
SB_UNIFORM_BLOCK_END_UNCHECKED(TestBadArray)
// The same array last: only the size tells.
SB_UNIFORM_BLOCK(TestBadSize, 0)
  SB_FIELD(vec4, a)
  SB_ARRAY(float, b, 4)
SB_UNIFORM_BLOCK_END_UNCHECKED(TestBadSize)
// A vec2 after a float: std140 aligns it to 8, C++ (glm) to 4.
SB_UNIFORM_BLOCK(TestBadVec2, 0)
  SB_FIELD(float, a)
  SB_FIELD(vec2, b)
SB_UNIFORM_BLOCK_END_UNCHECKED(TestBadVec2)
// clang-format on

namespace {

namespace std140 = sb::std140;

constexpr std140::Rule kFloat = std140::RuleOf<float>::rule,
                       kVec2 = std140::RuleOf<glm::vec2>::rule,
                       kVec3 = std140::RuleOf<glm::vec3>::rule,
                       kVec4 = std140::RuleOf<glm::vec4>::rule,
                       kMat4 = std140::RuleOf<glm::mat4>::rule;

// The std140 offsets (OpenGL 4.6, 7.6.2.2), where C++ (glm) puts some elsewhere.
static_assert(std140::offsetAfter(16, kFloat, 0) == 16);  // vec4, float: 16 in both
static_assert(std140::offsetAfter(20, kVec3, 0) == 32);   // vec4, float, vec3: C++ 20
static_assert(std140::offsetAfter(12, kFloat, 0) == 12);  // vec3, float: packed in both
static_assert(std140::offsetAfter(4, kVec2, 0) == 8);     // float, vec2: C++ 4
static_assert(std140::memberEnd(0, kFloat, 4) == 64);     // float[4]: stride 16, C++ 4
static_assert(std140::offsetAfter(4, kFloat, 2) == 16);   // an array aligns as a vec4
static_assert(std140::memberEnd(0, kMat4, 0) == 64);
static_assert(std140::memberEnd(16, kVec4, 129) == 16 + 129 * 16);
static_assert(std140::blockSize(20) == 32);
static_assert(sizeof(glm::vec3) == 12 && alignof(glm::vec3) == 4);  // why C++ and std140 differ

TEST(UniformBlocks, TheCheckPassesALayoutCppSharesWithStd140) {
  EXPECT_EQ(sb::TestGoodBlock::std140Mismatch(), nullptr);
  EXPECT_EQ(offsetof(sb::TestGoodBlock, b), 12u);
  EXPECT_EQ(offsetof(sb::TestGoodBlock, c), 16u);
  EXPECT_EQ(offsetof(sb::TestGoodBlock, f), 32u);
  EXPECT_EQ(sizeof(sb::TestGoodBlock), 128u);
  EXPECT_EQ(sb::TestGoodBlock::kBinding, 0u);
}

TEST(UniformBlocks, TheCheckNamesTheFirstMemberCppPlacesElsewhere) {
  static_assert(sb::TestBadVec3::std140Mismatch() != nullptr);  // constexpr: what the assert reads
  EXPECT_STREQ(sb::TestBadVec3::std140Mismatch(), "c");
  EXPECT_EQ(offsetof(sb::TestBadVec3, c), 20u);  // std140: 32
  EXPECT_STREQ(sb::TestBadArray::std140Mismatch(), "b");
  EXPECT_STREQ(sb::TestBadSize::std140Mismatch(), "sizeof");
  EXPECT_STREQ(sb::TestBadVec2::std140Mismatch(), "b");
}

TEST(UniformBlocks, TheProjectsBlocksAreStd140) {
  // Every block's END asserts this; a few, to see the names and sizes.
  EXPECT_EQ(sb::ViewUniforms::std140Mismatch(), nullptr);
  EXPECT_EQ(sizeof(sb::ViewUniforms), 112u);
  EXPECT_EQ(sb::ViewUniforms::kBinding, uint32_t(SB_SLOT_VIEW));
  EXPECT_EQ(offsetof(sb::OsmParams, osmSlices), 96u);
  EXPECT_EQ(sizeof(sb::OsmParams), 96u + 129u * 16u);
  EXPECT_EQ(sb::PeelSize::kBinding, uint32_t(SB_SLOT_PEEL_ADVANCE_SIZE));
}

// The GLSL side: the loader drops the C++'s #include (std140.h is not a shader
// file), resolves "techniques/..." from the source root, and the block compiles.
TEST(UniformBlocks, TheGlslSideIsTheStd140BlockAndCompiles) {
  const sb::ShaderCode code = sb::loadShader("techniques/osm/map.frag");
  for (const auto& f : code.fileNames) EXPECT_EQ(f.find("std140.h"), std::string::npos) << f;
  EXPECT_NE(
      std::find(code.fileNames.begin(), code.fileNames.end(), "render/common/uniform_block.h"),
      code.fileNames.end());
  EXPECT_NE(code.text.find("SB_UNIFORM_BLOCK(OsmParams, SB_SLOT_OSM_PARAMS)"), std::string::npos);
  EXPECT_FALSE(sb::compileVulkanSpirv(code, sb::ShaderStage::Fragment, "uniform_blocks").empty());
  const sb::ShaderCode comp = sb::loadShader("render/common/peel_advance.comp",
                                             {{{"STATE_BINDING", "1"}, {"PEELED_BINDING", "2"}}});
  EXPECT_FALSE(sb::compileVulkanSpirv(comp, sb::ShaderStage::Compute, "uniform_blocks").empty());
}

// Variables of a storage class in a SPIR-V module (OpVariable's third operand).
int variablesOf(const std::vector<uint32_t>& spv, uint32_t storageClass) {
  int n = 0;
  for (std::size_t i = 5; i < spv.size() && (spv[i] >> 16) > 0; i += spv[i] >> 16) {
    if ((spv[i] & 0xffffu) == 59u && (spv[i] >> 16) >= 4 && spv[i + 3] == storageClass) ++n;
  }
  return n;
}

// On lavapipe the Vulkan backend reads uniform blocks through storage buffers
// (VulkanPlatform::uniformsAsStorage): the same block compiles to a
// StorageBuffer variable and no Uniform one.
TEST(UniformBlocks, AsStorageTheBlockIsAStorageBuffer) {
  constexpr uint32_t kUniform = 2, kStorageBuffer = 12;
  const sb::ShaderCode code = sb::loadShader("techniques/osm/map.frag");
  const std::vector<uint32_t> ubo =
      sb::compileVulkanSpirv(code, sb::ShaderStage::Fragment, "uniform_blocks");
  const std::vector<uint32_t> ssbo =
      sb::compileVulkanSpirv(code, sb::ShaderStage::Fragment, "uniform_blocks", true);
  EXPECT_GT(variablesOf(ubo, kUniform), 0);
  EXPECT_EQ(variablesOf(ssbo, kUniform), 0);
  EXPECT_GT(variablesOf(ssbo, kStorageBuffer), variablesOf(ubo, kStorageBuffer));
  // The driver binds that slot with a storage buffer descriptor, and only then.
  EXPECT_EQ(sb::storageBufferBindings(ssbo).count(SB_SLOT_OSM_PARAMS), 1u);
  EXPECT_EQ(sb::storageBufferBindings(ubo).count(SB_SLOT_OSM_PARAMS), 0u);
}

}  // namespace
