// Leave out what a scene does not need: the report lists the passes that ran,
// and each kind of unneeded work is shown absent, beside a run that needs it.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace {

using namespace sbtest;
using json = nlohmann::json;

json render(const std::string& args) {
  const CliResult r = runCli("render --size 16x16 --json " + args);
  EXPECT_EQ(r.status, 0) << r.err;
  return json::parse(r.out);
}

bool ran(const json& report, const std::string& prefix) {
  for (const auto& p : report["passes"])
    if (p["name"].get<std::string>().rfind(prefix, 0) == 0) return true;
  return false;
}

const std::string kHair = "--scene straight:strands=50,points=5,head=";

TEST(PassCulling, TheReportListsThePassesThatRan) {
  const json r = render(kHair + "1 --shadow dom");
  std::vector<std::string> ranNames;
  for (const auto& p : r["passes"]) ranNames.push_back(p["name"]);
  EXPECT_EQ(ranNames, r["graph"].get<std::vector<std::string>>());
}

TEST(PassCulling, NoMeshNoOpaqueShadowOrBackgroundPass) {
  // (shadowmap draws the mesh and the hair into its one map: no separate pass.)
  for (const char* shadow : {"osm", "dom", "dc", "occupancy"}) {
    const json with = render(kHair + "1 --shadow " + shadow);
    EXPECT_TRUE(ran(with, std::string(shadow) + ".opaque")) << shadow;
    EXPECT_TRUE(ran(with, "shading.mesh")) << shadow;
    const json without = render(kHair + "0 --shadow " + shadow);
    EXPECT_FALSE(ran(without, std::string(shadow) + ".opaque")) << shadow;
    EXPECT_FALSE(ran(without, "shading.mesh")) << shadow;
  }
}

TEST(PassCulling, NoTransparencyTechniqueNoTransparencyPass) {
  const std::vector<std::string> oit = {"wsum",          "wavg", "wboit",
                                        "occupancy_oit", "peel", "abuffer"};
  auto anyOit = [&](const json& r) {
    for (const auto& o : oit)
      if (ran(r, o)) return true;
    return false;
  };
  EXPECT_FALSE(anyOit(render(kHair + "0 --shadow dom --oit none")));
  EXPECT_TRUE(anyOit(render(kHair + "0 --shadow dom --oit wavg")));
  EXPECT_TRUE(anyOit(render(kHair + "0 --shadow dom --oit occupancy")));
}

TEST(PassCulling, VisibilityErrorOnlyRunsNoFinalShading) {
  const json full = render(kHair + "1 --shadow occupancy --oit occupancy --reference");
  EXPECT_TRUE(ran(full, "shading."));
  EXPECT_TRUE(ran(full, "occupancy_oit."));
  ASSERT_TRUE(full["error"].contains("image"));

  const json vis = render(kHair + "1 --shadow occupancy --oit occupancy --reference --no-image");
  EXPECT_FALSE(ran(vis, "shading.")) << vis["graph"];
  EXPECT_FALSE(ran(vis, "occupancy_oit.")) << vis["graph"];
  EXPECT_TRUE(ran(vis, "occupancy.occupancy"));
  EXPECT_TRUE(ran(vis, "visibility"));
  EXPECT_FALSE(vis["error"].contains("image"));
  // The same visibility error as the full run: leaving shading out changed nothing measured.
  EXPECT_EQ(vis["error"]["visibility"], full["error"]["visibility"]);
}

TEST(PassCulling, NoReferenceNeededNoneComputed) {
  const json with = render(kHair + "0 --shadow dom --reference");
  EXPECT_TRUE(with.contains("reference"));
  EXPECT_TRUE(with.contains("measurement_graph"));
  std::size_t withResources = with["memory"]["resources"].size();
  const json without = render(kHair + "0 --shadow dom");
  EXPECT_FALSE(without.contains("reference"));
  EXPECT_FALSE(without.contains("error"));
  EXPECT_FALSE(without.contains("measurement_graph"));
  EXPECT_FALSE(ran(without, "visibility"));
  // Timed frames never include measurement passes, with or without a reference.
  EXPECT_FALSE(ran(with, "visibility"));
  EXPECT_EQ(with["graph"], without["graph"]);
  EXPECT_GT(withResources, 0u);
}

// Memory only for what runs: a resource is made on the device when a kept pass
// first uses it, so the report counts exactly what the run allocated.
std::map<std::string, std::size_t> resourceBytes(const json& report) {
  std::map<std::string, std::size_t> out;
  std::size_t sum = 0;
  for (const auto& r : report["memory"]["resources"]) {
    out[r["name"]] = r["bytes"];
    sum += r["bytes"].get<std::size_t>();
  }
  EXPECT_EQ(sum, report["memory"]["total_bytes"].get<std::size_t>());
  return out;
}

TEST(PassCulling, NoMeshNoOpaqueShadowMapAllocated) {
  for (const char* shadow : {"osm", "dom", "dc", "occupancy"}) {
    const auto with = resourceBytes(render(kHair + "1 --shadow " + shadow));
    const auto without = resourceBytes(render(kHair + "0 --shadow " + shadow));
    const std::string map = std::string(shadow) + ".opaque_depth";
    ASSERT_TRUE(with.count(map)) << shadow;
    EXPECT_FALSE(without.count(map)) << shadow;
    // Everything else the shadow technique holds is the same with and without the mesh.
    for (const auto& [name, bytes] : with)
      if (name != map && name.rfind("scene.", 0) != 0 && name.rfind("shading.", 0) != 0) {
        ASSERT_TRUE(without.count(name)) << name;
        EXPECT_EQ(without.at(name), bytes) << name;
      }
  }
}

TEST(PassCulling, VisibilityOnlyRunAllocatesNoShadingTargets) {
  const std::string args = kHair + "1 --shadow occupancy --oit occupancy --reference";
  const json fullReport = render(args);
  const json visReport = render(args + " --no-image");
  const auto full = resourceBytes(fullReport);
  const auto vis = resourceBytes(visReport);
  // The final shading targets and every transparency target are gone ...
  for (const auto& [name, bytes] : full) {
    const bool shadingOnly = name == "frame.color" || name == "frame.depth" ||
                             name.rfind("occupancy_oit.", 0) == 0;
    EXPECT_EQ(vis.count(name) == 0, shadingOnly) << name;
  }
  EXPECT_TRUE(full.count("frame.color"));
  EXPECT_TRUE(full.count("occupancy_oit.bits"));
  // ... and the bytes drop by exactly their sizes, plus the visibility pass's own targets,
  // which only the visibility-only run has in its timed frames.
  std::size_t dropped = 0, added = 0;
  for (const auto& [name, bytes] : full)
    if (!vis.count(name)) dropped += bytes;
  for (const auto& [name, bytes] : vis)
    if (!full.count(name)) {
      EXPECT_EQ(name.rfind("visibility.", 0), 0u) << name;
      added += bytes;
    }
  EXPECT_GT(dropped, added);
  EXPECT_EQ(fullReport["memory"]["total_bytes"].get<std::size_t>() - dropped + added,
            visReport["memory"]["total_bytes"].get<std::size_t>());
}

}  // namespace
