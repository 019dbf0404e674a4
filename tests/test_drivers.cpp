// --driver: a named driver (drivers/mesa-25.0, from scripts/drivers.sh) is what renders
// and what the result JSON names; a driver that is not there is bad input (exit 2).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/test_util.h"

namespace {

namespace fs = std::filesystem;
using sbtest::runCli;

constexpr const char* kTiny = "--scene straight:strands=20,points=4 --size 16x16 --repeat 1";

nlohmann::json renderJson(const std::string& args) {
  const sbtest::CliResult r = runCli(std::string("render ") + kTiny + " --json " + args);
  EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
  if (r.status != 0) return {};
  return nlohmann::json::parse(r.out);
}

TEST(Drivers, UnknownNameIsBadInputNamingTheScript) {
  const sbtest::CliResult r = runCli(std::string("render ") + kTiny + " --driver no-such-driver");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unknown driver 'no-such-driver'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("scripts/drivers.sh"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(Drivers, MissingFolderIsBadInput) {
  const auto dir = sbtest::tempDir("driver");  // a folder, but no driver in it
  for (const std::string& args :
       {"check --driver=" + dir.string(), "render --driver " + (dir / "absent").string()}) {
    const sbtest::CliResult r = runCli(args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_NE(r.err.find("scripts/drivers.sh"), std::string::npos) << args << "\n" << r.err;
  }
  fs::remove_all(dir);
}

TEST(Drivers, SystemIsMesa22) {
  for (const std::string backend : {"gl", "vulkan"}) {
    const auto j = renderJson("--backend " + backend);
    if (j.is_null()) continue;
    EXPECT_EQ(j["driver_name"], "system") << backend;
    EXPECT_NE(j["driver"].get<std::string>().find("Mesa 22.3.6"), std::string::npos) << j["driver"];
  }
}

TEST(Drivers, Mesa25RendersAndIsNamed) {
  if (const std::string why = sbtest::mesa25Missing(); !why.empty()) GTEST_SKIP() << why;
  for (const std::string backend : {"gl --platform egl", "gl --platform osmesa", "vulkan"}) {
    const auto j = renderJson("--driver mesa-25.0 --backend " + backend);
    if (j.is_null()) continue;
    EXPECT_EQ(j["driver_name"], "mesa-25.0") << backend;
    EXPECT_NE(j["driver"].get<std::string>().find("Mesa 25.0.7"), std::string::npos)
        << backend << ": " << j["driver"];
    EXPECT_NE(j["device"].get<std::string>().find("llvmpipe"), std::string::npos) << j["device"];
  }
  // By path, too: the same driver, named as given.
  const std::string path = (fs::path(SB_SOURCE_DIR) / "drivers/mesa-25.0").string();
  const auto j = renderJson("--driver " + path + " --backend vulkan");
  if (!j.is_null()) {
    EXPECT_EQ(j["driver_name"], path);
    EXPECT_NE(j["driver"].get<std::string>().find("Mesa 25.0.7"), std::string::npos);
  }
}

// A suite's "drivers": one case per driver, each driver's cases swept in a process of its
// own (the sweep's own driver here, Mesa 25.0.7 in a child), joined in one results.json; an
// unknown driver is refused before anything runs.
TEST(Drivers, ASuiteSweepsEachDriverInAProcessOfItsOwn) {
  if (const std::string why = sbtest::mesa25Missing(); !why.empty()) GTEST_SKIP() << why;
  const auto dir = sbtest::tempDir("driver-suite");
  nlohmann::json suite = {{"name", "t"},
                          {"defaults",
                           {{"backends", {"gl", "vulkan"}},
                            {"scene", "straight:strands=20,points=4"},
                            {"size", "16x16"},
                            {"repeat", 2}}},
                          {"groups", {{{"name", "g"}, {"drivers", {"system", "mesa-25.0"}}}}}};
  std::ofstream(dir / "suite.json") << suite.dump(2);
  const sbtest::CliResult r =
      runCli("sweep " + (dir / "suite.json").string() + " --out " + (dir / "o").string());
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("the cases on driver mesa-25.0 in a process of its own"), std::string::npos)
      << r.out;
  const auto results = nlohmann::json::parse(sbtest::readFile(dir / "o" / "results.json"));
  std::map<std::string, std::string> drivers;  // case id -> the driver string it ran on
  for (const auto& x : results["results"])
    drivers[x["case"]["id"].get<std::string>()] = x["driver"].get<std::string>();
  ASSERT_EQ(drivers.size(), 4u) << r.out;
  for (const char* backend : {"gl", "vulkan"}) {
    const std::string b = backend;
    EXPECT_NE(drivers["g/driver=system,backend=" + b].find("Mesa 22.3"), std::string::npos);
    EXPECT_NE(drivers["g/driver=mesa-25.0,backend=" + b].find("Mesa 25.0.7"), std::string::npos);
  }

  suite["groups"][0]["drivers"] = {"system", "no-such-driver"};
  std::ofstream(dir / "bad.json") << suite.dump(2);
  const sbtest::CliResult bad =
      runCli("sweep " + (dir / "bad.json").string() + " --out " + (dir / "o2").string());
  EXPECT_EQ(bad.status, 2) << bad.err;
  EXPECT_NE(bad.err.find("no-such-driver"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "o2"));
  fs::remove_all(dir);
}

TEST(Drivers, VersionProbesEachDriver) {
  if (const std::string why = sbtest::mesa25Missing(); !why.empty()) GTEST_SKIP() << why;
  const sbtest::CliResult r = runCli("--version");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::size_t system = r.out.find("\nsystem");
  const std::size_t mesa25 = r.out.find("\nmesa-25.0:");
  ASSERT_NE(system, std::string::npos) << r.out;
  ASSERT_NE(mesa25, std::string::npos) << r.out;
  ASSERT_LT(system, mesa25) << r.out;
  const std::string systemPart = r.out.substr(system, mesa25 - system);
  const std::string mesa25Part = r.out.substr(mesa25);
  EXPECT_NE(systemPart.find("Mesa 22.3.6"), std::string::npos) << r.out;
  EXPECT_EQ(systemPart.find("25.0.7"), std::string::npos) << r.out;
  EXPECT_NE(mesa25Part.find("Mesa 25.0.7"), std::string::npos) << r.out;
  EXPECT_EQ(mesa25Part.find("22.3.6"), std::string::npos) << r.out;
  for (const char* cap : {"ray query: ", "mesh shaders: ", "fragment shader interlock: ",
                          "pipeline statistics: ", "timestamps: "})
    EXPECT_NE(mesa25Part.find(cap), std::string::npos) << cap << "\n" << r.out;
}

}  // namespace
