// Cull before building: the renderer declares every technique's passes,
// culls the frame graph, and only then compiles the pipelines and runs the
// preparations of the techniques it kept. A visibility-only run (--no-image)
// keeps no transparency pass, so no transparency technique compiles a
// pipeline or runs its preparation there: every technique in the registry,
// on both APIs.
#include <gtest/gtest.h>

#include <algorithm>

#include "harness/render.h"
#include "render_request.h"
#include "render/common/technique.h"
#include "render/common/unit.h"

namespace sb {
namespace {

RenderRequest tiny(const std::string& backend, const std::string& shadow, const std::string& oit) {
  return sbtest::smallRender(backend, "straight:strands=20,points=4,head=1,alpha=0.5", shadow, oit,
                             16);
}

bool preparedFor(const RenderResult& r, const std::string& technique) {
  return std::find(r.preparations.begin(), r.preparations.end(), technique + ".prepare") !=
         r.preparations.end();
}

class CullBeforeBuild : public ::testing::TestWithParam<std::string> {};

RenderResult visibilityOnly(const std::string& backend, const std::string& shadow,
                            const std::string& oit) {
  RenderRequest req = tiny(backend, shadow, oit);
  req.image = false;
  req.reference = true;
  return runRender(req);
}

// Culled, a transparency technique leaves the build exactly as no
// transparency technique does: the same pipelines, the same preparations.
TEST_P(CullBeforeBuild, ACulledTransparencyTechniqueCompilesAndPreparesNothing) {
  const RenderResult without = visibilityOnly(GetParam(), "shadowmap", "none");
  const RenderResult colourWithout = runRender(tiny(GetParam(), "shadowmap", "none"));
  EXPECT_FALSE(without.pipelines.empty());
  for (const TechniqueDescriptor* info : techniques(Family::Transparency)) {
    SCOPED_TRACE(GetParam() + " oit " + info->name);
    const RenderResult culled = visibilityOnly(GetParam(), "shadowmap", info->name);
    EXPECT_EQ(culled.pipelines, without.pipelines);
    EXPECT_EQ(culled.preparations, without.preparations);
    EXPECT_FALSE(preparedFor(culled, makeOitTechnique(Spec::parse(info->name))->name()));
    // Kept (a colour run), it is built: the check above is not vacuous.
    if (info->name == "none") continue;
    const RenderResult kept = runRender(tiny(GetParam(), "shadowmap", info->name));
    EXPECT_GT(kept.pipelines.size(), colourWithout.pipelines.size());
  }
}

TEST_P(CullBeforeBuild, EveryShadowTechniqueIsBuiltAndTheCulledTransparencyIsNot) {
  for (const TechniqueDescriptor* info : techniques(Family::Shadow)) {
    SCOPED_TRACE(GetParam() + " shadow " + info->name);
    const std::string name = makeShadowTechnique(Spec::parse(info->name))->name();
    const RenderResult r = visibilityOnly(GetParam(), info->name, "abuffer");
    const RenderResult without = visibilityOnly(GetParam(), info->name, "none");
    EXPECT_EQ(r.pipelines, without.pipelines);
    EXPECT_EQ(r.preparations, without.preparations);
    // Kept (prepared) exactly when it adds a pass (shadow none adds none).
    const bool passes = std::any_of(r.graph.begin(), r.graph.end(), [&](const std::string& p) {
      return p.rfind(name + ".", 0) == 0 || p == name;
    });
    EXPECT_EQ(preparedFor(r, name), passes);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, CullBeforeBuild, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

}  // namespace
}  // namespace sb
