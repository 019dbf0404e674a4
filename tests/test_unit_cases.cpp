// A unit folder's cases (techniques/<folder>/cases.json, harness/unit_cases.h) join the
// manifest and the quick suite that ask for them ("unit_cases": true), and only those; a bad
// file or a name taken twice is refused naming the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "harness/baselines.h"
#include "harness/suite.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;

// A tree: baselines/manifest.json, suites/quick.json and techniques/x/cases.json.
fs::path tree(bool ask, const std::string& unitCases) {
  const fs::path root = sbtest::tempDir(ask ? "unit-cases" : "unit-cases-off");
  fs::create_directories(root / "baselines");
  fs::create_directories(root / "suites");
  fs::create_directories(root / "techniques" / "x");
  const std::string flag = ask ? "true" : "false";
  std::ofstream(root / "baselines" / "manifest.json")
      << R"({"format": 2, "unit_cases": )" << flag
      << R"(, "defaults": {"size": "16x16", "tolerance": {"max_abs": 0.002,
             "max_failing_fraction": 0.0005, "failing_threshold": 1e-4, "min_psnr": 80}},
            "cases": [{"name": "central", "scene": "curly:strands=5"}]})";
  std::ofstream(root / "suites" / "quick.json")
      << R"({"name": "quick", "unit_cases": )" << flag
      << R"(, "defaults": {"scene": "curly:strands=5", "size": "16x16"},
            "groups": [{"name": "central", "axes": {"shadow": ["none"]}}]})";
  std::ofstream(root / "techniques" / "x" / "cases.json") << unitCases;
  return root;
}

const char* kUnit = R"({"baselines": [{"name": "unit-case", "scene": "curly:strands=5"}],
                        "quick": [{"name": "unit-group", "axes": {"shadow": ["shadowmap"]}}]})";

TEST(UnitCases, JoinTheManifestAndTheQuickSuiteThatAskForThem) {
  const fs::path on = tree(true, kUnit);
  const sb::Manifest m = sb::loadManifest(on / "baselines" / "manifest.json");
  ASSERT_EQ(m.cases.size(), 2u);
  EXPECT_EQ(m.cases[1].name, "unit-case");
  EXPECT_EQ(m.cases[1].request.width, 16u);  // the manifest's defaults apply
  const sb::Suite s = sb::loadSuite((on / "suites" / "quick.json").string());
  bool unitGroup = false;
  for (const sb::SweepCase& c : s.cases) unitGroup |= c.group == "unit-group";
  EXPECT_TRUE(unitGroup);
  // The control: a manifest and a suite that do not ask get none.
  const fs::path off = tree(false, kUnit);
  EXPECT_EQ(sb::loadManifest(off / "baselines" / "manifest.json").cases.size(), 1u);
  for (const sb::SweepCase& c : sb::loadSuite((off / "suites" / "quick.json").string()).cases)
    EXPECT_NE(c.group, "unit-group");
}

TEST(UnitCases, ABadFileOrATakenNameIsRefusedNamingTheFile) {
  sbtest::expectInputError(
      [] { sb::loadManifest(tree(true, R"({"baseline": []})") / "baselines" / "manifest.json"); },
      {"cases.json", "baseline"});
  sbtest::expectInputError(
      [] {
        sb::loadManifest(
            tree(true, R"({"baselines": [{"name": "central", "scene": "curly:strands=5"}]})") /
            "baselines" / "manifest.json");
      },
      {"cases.json", "duplicate case name 'central'"});
}

}  // namespace
