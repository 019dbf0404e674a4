// CPU tests of technique code: the Kajiya-Kay math shared with GLSL, the
// shader loader's #include/#line handling, the technique
// registry's validation, and a broken shader named in the CLI's message.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "backends/shader_source.h"
#include "render/common/shader_library.h"
#include "render/common/technique.h"
#include "techniques/kajiya_kay/kajiya_kay.h"
#include "test_util.h"

namespace sb {
namespace {

TEST(KajiyaKay, DiffuseIsSineOfTangentAndLight) {
  const glm::vec3 T(0, 1, 0), V(0, 0, 1);
  EXPECT_NEAR(glsl::kajiyaKay(T, glm::vec3(1, 0, 0), V, 10).x, 1.0f, 1e-6f);  // perpendicular
  EXPECT_NEAR(glsl::kajiyaKay(T, glm::vec3(0, 1, 0), V, 10).x, 0.0f, 1e-6f);  // along the strand
  const glm::vec3 L45 = glm::normalize(glm::vec3(1, 1, 0));
  EXPECT_NEAR(glsl::kajiyaKay(T, L45, V, 10).x, std::sqrt(0.5f), 1e-6f);
}

TEST(KajiyaKay, SpecularPeaksOnTheReflectionCone) {
  const glm::vec3 T(0, 1, 0);
  const glm::vec3 L = glm::normalize(glm::vec3(1, 1, 0));         // 45 deg from T
  const glm::vec3 Vmirror = glm::normalize(glm::vec3(0, -1, 1));  // 135 deg from T: on the cone
  const glm::vec3 Vsame = glm::normalize(glm::vec3(0, 1, 1));     // 45 deg: off the cone
  EXPECT_NEAR(glsl::kajiyaKay(T, L, Vmirror, 50).y, 1.0f, 1e-5f);
  EXPECT_NEAR(glsl::kajiyaKay(T, L, Vsame, 50).y, 0.0f, 1e-6f);
  // Degenerate: light along the tangent gives no diffuse and no NaN.
  const glm::vec2 d = glsl::kajiyaKay(T, T, T, 50);
  EXPECT_TRUE(std::isfinite(d.x) && std::isfinite(d.y));
}

TEST(ShaderLibrary, ResolvesIncludesAndAliasesWithLineDirectives) {
  ShaderDefines defs;
  defs.aliases["shadow"] = "techniques/shadowmap/lookup.glsl";
  defs.aliases["shading"] = "techniques/kajiya_kay/shading.glsl";
  defs.defines.push_back({"SB_TEST", "1"});
  const ShaderCode code = loadShader("render/shading/hair.frag", defs);
  EXPECT_EQ(code.fileNames.front(), "render/shading/hair.frag");
  const std::vector<std::string> expected = {
      "render/common/shading.glsl", "techniques/kajiya_kay/shading.glsl",
      "techniques/kajiya_kay/kajiya_kay.glsl", "techniques/shadowmap/lookup.glsl"};
  for (const auto& f : expected)
    EXPECT_NE(std::find(code.fileNames.begin(), code.fileNames.end(), f), code.fileNames.end())
        << f;
  EXPECT_NE(code.text.find("#define SB_TEST 1"), std::string::npos);
  EXPECT_NE(code.text.find("float shadowVisibility"), std::string::npos);
  EXPECT_THROW(loadShader("render/shading/hair.frag"), DeviceError);  // <shadow> unbound
  defs.aliases.erase("shading");
  EXPECT_THROW(loadShader("render/shading/hair.frag", defs), DeviceError);  // <shading> too
  EXPECT_THROW(loadShader("techniques/nope.frag"), DeviceError);
}

TEST(ShaderLibrary, CompileLogLinesMapToFiles) {
  ShaderCode code;
  code.name = "techniques/x/main.frag";
  code.fileNames = {"techniques/x/main.frag", "techniques/x/inc.glsl"};
  const std::string msg = describeCompileError(code, "xtech", "ERROR: 1:7: 'foo' : undeclared");
  EXPECT_NE(msg.find("techniques/x/inc.glsl:7:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("xtech"), std::string::npos);
}

TEST(Registry, ValidatesTechniqueNamesAndOptions) {
  EXPECT_EQ(makeShadowTechnique(Spec::parse("none"))->name(), "none");
  EXPECT_EQ(makeShadowTechnique(Spec::parse("shadowmap:size=64,bias=0.01"))->name(), "shadowmap");
  try {
    makeShadowTechnique(Spec::parse("shadowmpa"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'shadowmap'"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(makeShadowTechnique(Spec::parse("shadowmap:size=0")), InputError);
  EXPECT_THROW(makeShadowTechnique(Spec::parse("shadowmap:bias=nan")), InputError);
  EXPECT_THROW(makeShadowTechnique(Spec::parse("shadowmap:sise=5")), InputError);
  EXPECT_THROW(makeShadowTechnique(Spec::parse("none:size=5")), InputError);
}

// A technique shader that fails to compile, through the CLI on both backends:
// BadInput.ShaderThatFailsToCompile (tests/test_bad_input.cpp).

}  // namespace
}  // namespace sb
