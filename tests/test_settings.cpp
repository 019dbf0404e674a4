// The settings table (harness/settings.h) and its three front ends: every setting
// given as a CLI flag, a suite key (a group's key and an axis) and a baselines
// manifest key resolves to the same request; a bad value is refused by each with
// exit status 2 and a message naming the setting; a baseline case's camera and
// light keys change its image; the docs hold the table as it is.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "harness/baselines.h"
#include "harness/settings.h"
#include "harness/suite.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;
using sb::RenderRequest;
using sb::Setting;
using sb::SettingType;

const char* kScene = "straight:strands=30,points=6,seed=3";

// Settings that are valid only with another one set: given with it everywhere.
const std::map<std::string, std::pair<std::string, std::string>> kNeeds = {
    {"image", {"reference", "true"}},
    {"invariants", {"reference", "true"}},
    {"animate", {"reference", "true"}}};

std::vector<std::string> splitCommas(const std::string& t) {
  std::vector<std::string> parts;
  std::stringstream in(t);
  for (std::string p; std::getline(in, p, ',');) parts.push_back(p);
  return parts;
}

// A text-form value as a suite or manifest writes it: the JSON form where the
// type has one (numbers, booleans, [x, y, z], the probe object), else the text.
ojson jsonValue(const Setting& s, const std::string& text) {
  switch (s.type) {
    case SettingType::Int:
      return std::stoll(text);
    case SettingType::Float:
      return std::stod(text);
    case SettingType::Flag:
      if (text == "true" || text == "false") return text == "true";
      return text;  // a bad value: not a boolean
    case SettingType::Vec3: {
      const auto p = splitCommas(text);
      try {
        if (p.size() == 3) return ojson::array({std::stod(p[0]), std::stod(p[1]), std::stod(p[2])});
      } catch (const std::invalid_argument&) {
      }
      return text;  // a bad value: as written
    }
    case SettingType::Probe: {
      const auto p = splitCommas(text);
      if (p.size() != 4) return text;
      return {{"texel", {std::stoi(p[0]), std::stoi(p[1])}},
              {"map_size", std::stoi(p[2])},
              {"samples", std::stoi(p[3])}};
    }
    default:
      return text;
  }
}

// The CLI arguments that give a setting a text value.
std::vector<std::string> cliArgs(const Setting& s, const std::string& text) {
  if (s.type == SettingType::Flag && (text == "true" || text == "false")) return {s.flag};
  if (s.type == SettingType::Flag) return {s.flag + "=" + text};
  return {s.flag, text};
}

// `render`'s settings options, parsed in process.
RenderRequest fromCli(std::vector<std::string> args) {
  CLI::App app;
  RenderRequest req;
  sb::CliSettings settings(app, {}, req);
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  app.parse(args);
  settings.apply(req);
  return req;
}

// One group of one case on gl, with `settings` as the group's keys (or its axes).
RenderRequest fromSuite(const ojson& settings, bool asAxes) {
  ojson group = {{"name", "g"}};
  for (const auto& [k, v] : settings.items()) {
    if (asAxes)
      group["axes"][k] = ojson::array({v});
    else
      group[k] = v;
  }
  const ojson suite = {
      {"name", "t"}, {"defaults", {{"backends", {"gl"}}, {"scene", kScene}}}, {"groups", {group}}};
  const sb::Suite s = sb::parseSuite(suite.dump(), "t.json");
  EXPECT_EQ(s.cases.size(), 1u);
  return s.cases.at(0).request;
}

ojson manifest(const ojson& cases) {
  return {{"format", 2},
          {"tolerances",
           {{"t",
             {{"max_abs", 0.002},
              {"max_failing_fraction", 0.0005},
              {"failing_threshold", 0.0001},
              {"min_psnr", 80}}}}},
          {"defaults", {{"size", "24x24"}, {"tolerance", "t"}, {"backends", {"gl"}}}},
          {"cases", cases}};
}

// One case named "c" with `settings` as its keys, read back as a request on its first backend.
RenderRequest fromManifest(const ojson& settings) {
  const fs::path dir = sbtest::tempDir("settings-manifest");
  ojson c = {{"name", "c"}, {"scene", kScene}};
  for (const auto& [k, v] : settings.items()) c[k] = v;
  std::ofstream(dir / "manifest.json") << manifest(ojson::array({c})).dump(2);
  const sb::Manifest m = sb::loadManifest(dir / "manifest.json");
  fs::remove_all(dir);
  return sb::caseRequest(m.cases.at(0), m.cases.at(0).backends.at(0));
}

TEST(Settings, TableIsComplete) {
  std::set<std::string> keys, flags;
  for (const Setting& s : sb::settingsTable()) {
    EXPECT_TRUE(keys.insert(s.key).second) << s.key;
    EXPECT_TRUE(flags.insert(s.flag).second) << s.flag;
    EXPECT_EQ(s.flag.rfind("--", 0), 0u) << s.flag;
    EXPECT_FALSE(s.help.empty()) << s.key;
    EXPECT_FALSE(s.defaultText.empty()) << s.key;
    EXPECT_FALSE(s.example.empty()) << s.key;
    EXPECT_FALSE(s.badExample.empty()) << s.key;
    // Set and read back, the example differs from the default request's value.
    RenderRequest r;
    sb::setFromText(r, s, s.example);
    EXPECT_NE(s.get(r), s.get(RenderRequest{})) << s.key;
  }
  // Camera and light among them, and every other field of RenderRequest.
  for (const char* k : {"scene",
                        "shadow",
                        "oit",
                        "backend",
                        "platform",
                        "size",
                        "primitive",
                        "geometry",
                        "ribbon_width",
                        "repeat",
                        "warmup",
                        "reference",
                        "image",
                        "probe",
                        "animate",
                        "invariants",
                        "run_to_run",
                        "validation",
                        "memory_limit",
                        "camera_eye",
                        "camera_target",
                        "camera_up",
                        "fov",
                        "near",
                        "far",
                        "light",
                        "light_position",
                        "light_direction",
                        "light_color",
                        "light_intensity",
                        "extra_lights"})
    EXPECT_EQ(keys.count(k), 1u) << k;
  EXPECT_EQ(keys.size(), 34u);
}

// Every setting through the three front ends: the same value lands in the same
// field, and nothing else changes from what each front end gives without it.
TEST(Settings, EveryFrontEndGivesTheSameRequest) {
  for (const Setting& s : sb::settingsTable()) {
    SCOPED_TRACE(s.key + " = " + s.example);
    std::vector<std::string> args = cliArgs(s, s.example);
    ojson keys = {{s.key, jsonValue(s, s.example)}};
    std::vector<std::string> baseArgs;
    ojson baseKeys = ojson::object();
    if (kNeeds.count(s.key)) {
      const auto& [key, value] = kNeeds.at(s.key);
      const Setting& need = *sb::findSetting(key);
      for (const auto& a : cliArgs(need, value)) {
        args.push_back(a);
        baseArgs.push_back(a);
      }
      keys[key] = baseKeys[key] = jsonValue(need, value);
    }
    // What each front end gives without the setting, with it set as the table says.
    auto expected = [&](RenderRequest base) {
      sb::setFromText(base, s, s.example);
      return base;
    };
    const RenderRequest cli = fromCli(args);
    EXPECT_EQ(cli, expected(fromCli(baseArgs)));
    const RenderRequest suite = fromSuite(keys, false);
    EXPECT_EQ(suite, expected(fromSuite(baseKeys, false)));
    EXPECT_EQ(fromSuite(keys, true), suite) << "as an axis";
    EXPECT_EQ(s.get(cli), s.get(suite));
    // A baseline case compares its image: "image": false is refused there (below).
    if (s.key == "image") continue;
    const RenderRequest baseline = fromManifest(keys);
    EXPECT_EQ(baseline, expected(fromManifest(baseKeys)));
    EXPECT_EQ(s.get(cli), s.get(baseline));
  }
  sbtest::expectInputError(
      [] {
        fromManifest({{"image", false}, {"reference", true}});
      },
      {"cases[0] ('c')", "\"image\": false", "compares its image"});
  // Equal in effect, also in the JSON spellings the table allows.
  EXPECT_EQ(fromSuite({{"size", 32}}, false).width, 32u);
  EXPECT_EQ(fromSuite({{"camera_eye", "1,2,3"}}, false),
            fromSuite({{"camera_eye", {1, 2, 3}}}, false));
  EXPECT_EQ(fromManifest({{"probe", "12,10,24,8"}}),
            fromManifest({{"probe", {{"texel", {12, 10}}, {"map_size", 24}, {"samples", 8}}}}));
  EXPECT_EQ(fromManifest({{"backend", "vulkan"}}).backend, "vulkan");
}

// The strandbench command line run in this process: main()'s parse and exit
// status (cli/main.cpp) over the commands it registers, stdout and stderr
// captured. The same code as the binary without the start of a process that
// loads some 260 shared libraries (0.5-1 s each, the most of this test's time
// when each refusal below spawned the binary).
sbtest::CliResult runInProcess(std::vector<std::string> args) {
  CLI::App app{"strandbench"};
  app.require_subcommand(1);
  sb::registerCommands(app);
  sb::runGuarded("reset", [] { return 0; });  // no status left from an earlier command
  std::ostringstream out, err;
  struct Capture {
    std::ostream& stream;
    std::streambuf* old;
    ~Capture() { stream.rdbuf(old); }
  } captureOut{std::cout, std::cout.rdbuf(out.rdbuf())},
      captureErr{std::cerr, std::cerr.rdbuf(err.rdbuf())};
  sbtest::CliResult r;
  const std::vector<std::string> given = args;
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  try {
    app.parse(args);
    r.status = sb::lastCommandStatus();
  } catch (const CLI::ParseError& e) {  // as main() handles it
    std::cerr << sb::parseErrorMessage(app, e, given) << "\n";
    r.status = 2;
  }
  r.out = out.str();
  r.err = err.str();
  return r;
}

// The binary's result for the same arguments (each quoted for the shell).
sbtest::CliResult runBinary(const std::vector<std::string>& args) {
  std::string line;
  for (const auto& a : args) line += (line.empty() ? "'" : " '") + a + "'";
  return sbtest::runCli(line);
}

// A bad value of every setting through the three front ends: render (CLI flags),
// sweep (suite keys) and check (manifest keys) each give exit status 2 naming the
// setting, before they render or write anything. In process (runInProcess); the
// binary gives the same for the first setting.
TEST(Settings, EveryFrontEndRefusesABadValue) {
  const fs::path dir = sbtest::tempDir("settings-bad");
  bool first = true;
  for (const Setting& s : sb::settingsTable()) {
    SCOPED_TRACE(s.key + " = " + s.badExample);
    std::vector<std::string> extra;
    ojson keys = {{s.key, jsonValue(s, s.badExample)}};
    if (kNeeds.count(s.key)) {
      const auto& [key, value] = kNeeds.at(s.key);
      extra = {"--" + std::string(key)};
      keys[key] = true;
    }
    // Each front end in process, and for the first setting also as the binary.
    auto run = [&](const std::vector<std::string>& args) {
      const sbtest::CliResult r = runInProcess(args);
      if (first) {
        const sbtest::CliResult binary = runBinary(args);
        EXPECT_EQ(binary.status, r.status) << binary.err;
        EXPECT_EQ(binary.err, r.err);
      }
      return r;
    };

    std::vector<std::string> render = {"render", "--scene", kScene, "--size", "16x16"};
    render.insert(render.end(), extra.begin(), extra.end());
    for (const auto& a : cliArgs(s, s.badExample)) render.push_back(a);
    const sbtest::CliResult cli = run(render);
    EXPECT_EQ(cli.status, 2) << cli.err;
    EXPECT_NE(cli.err.find(s.flag), std::string::npos) << cli.err;

    const std::string quoted = "\"" + s.key + "\"";
    ojson group = {{"name", "g"}};
    for (const auto& [k, v] : keys.items()) group[k] = v;
    const ojson suite = {{"name", "t"},
                         {"defaults", {{"backends", {"gl"}}, {"scene", kScene}, {"size", "16x16"}}},
                         {"groups", {group}}};
    std::ofstream(dir / "suite.json") << suite.dump(2);
    const sbtest::CliResult sweep =
        run({"sweep", (dir / "suite.json").string(), "--out", (dir / "o").string()});
    EXPECT_EQ(sweep.status, 2) << sweep.err;
    EXPECT_NE(sweep.err.find(quoted), std::string::npos) << sweep.err;
    EXPECT_FALSE(fs::exists(dir / "o"));

    fs::create_directories(dir / "b");
    ojson c = {{"name", "c"}, {"scene", kScene}};
    for (const auto& [k, v] : keys.items()) c[k] = v;
    std::ofstream(dir / "b" / "manifest.json") << manifest(ojson::array({c})).dump(2);
    const sbtest::CliResult check =
        run({"check", "--baselines", (dir / "b").string(), "--out", (dir / "out").string()});
    EXPECT_EQ(check.status, 2) << check.err;
    EXPECT_NE(check.err.find(quoted), std::string::npos) << check.err;
    EXPECT_NE(check.err.find("manifest.json"), std::string::npos) << check.err;
    EXPECT_FALSE(fs::exists(dir / "out"));
    fs::remove_all(dir / "o");  // what a front end that took the value wrote: one failure each
    fs::remove_all(dir / "out");
    first = false;
  }
  fs::remove_all(dir);
}

// Format 1 manifests load unchanged, and as format 2 give the same cases.
// The committed manifest's cases that format 1 can express (its settings only), read as format
// 1 and as format 2, give the same requests.
TEST(Settings, Format1ManifestIsFormat2WithTheSameCases) {
  const fs::path committed = fs::path(SB_SOURCE_DIR) / "baselines" / "manifest.json";
  ojson doc = ojson::parse(sbtest::readFile(committed));
  ASSERT_EQ(doc["format"], 2);
  const std::set<std::string> format1 = {"name", "comment",   "scene",        "shadow",  "oit",
                                         "size", "primitive", "ribbon_width", "backends"};
  ojson cases = ojson::array();
  for (const auto& c : doc["cases"]) {
    bool fits = true;
    for (const auto& [k, v] : c.items()) fits = fits && format1.count(k);
    if (fits) cases.push_back(c);
  }
  ASSERT_GT(cases.size(), 20u);
  doc["cases"] = cases;
  const fs::path dir = sbtest::tempDir("settings-format");
  std::ofstream(dir / "two.json") << doc.dump(2);
  doc["format"] = 1;
  std::ofstream(dir / "one.json") << doc.dump(2);
  const sb::Manifest one = sb::loadManifest(dir / "one.json");
  const sb::Manifest two = sb::loadManifest(dir / "two.json");
  fs::remove_all(dir);
  ASSERT_EQ(one.cases.size(), two.cases.size());
  for (std::size_t i = 0; i < one.cases.size(); ++i) {
    EXPECT_EQ(one.cases[i].name, two.cases[i].name);
    EXPECT_EQ(one.cases[i].request, two.cases[i].request) << one.cases[i].name;
    EXPECT_EQ(one.cases[i].backends, two.cases[i].backends) << one.cases[i].name;
    // What format 1 always rendered: one frame, no warm-up, a fitted view.
    EXPECT_EQ(one.cases[i].request.repeat, 1);
    EXPECT_EQ(one.cases[i].request.warmup, 0);
    EXPECT_EQ(one.cases[i].request.view, sb::ViewOverrides{});
  }
}

// Each camera and light key of a baseline case changes its image, and so do all
// together; `bless` and `check` take them end to end.
TEST(Settings, BaselineCameraAndLightChangeTheImage) {
  const std::string scene = "curly:strands=60,points=16,seed=7";
  // Near and far halfway into the fitted range clip the hair.
  const sb::Scene built = sb::makeScene(sb::Spec::parse(scene));
  RenderRequest fitted;
  fitted.scene = scene;
  fitted.width = fitted.height = 24;
  const sb::RenderSettings f = sb::makeRenderSettings(fitted, built);
  const float middle = glm::length(f.camera.target - f.camera.eye);
  const ojson view = {{"camera_eye", "0.3,1.2,4"},
                      {"camera_target", "0.2,0.3,-0.1"},
                      {"camera_up", "1,1,0"},
                      {"fov", 60},
                      {"near", middle},
                      {"far", middle},
                      {"light", "point"},
                      {"light_position", "2,3,4"},
                      {"light_direction", "-1,-0.5,0"},
                      {"light_color", "1,0.5,0.25"},
                      {"light_intensity", 2}};
  ojson cases = ojson::array({{{"name", "plain"}, {"scene", scene}, {"shadow", "shadowmap"}}});
  ojson posed = cases[0];
  posed["name"] = "posed";
  for (const auto& [k, v] : view.items()) {
    ojson one = cases[0];
    one["name"] = "only-" + k;
    one[k] = v;
    cases.push_back(one);
    if (k != "near" && k != "far") posed[k] = v;  // together, the planes fitted to the new eye
  }
  cases.push_back(posed);

  const fs::path dir = sbtest::tempDir("settings-view");
  std::ofstream(dir / "manifest.json") << manifest(cases).dump(2);
  const sb::Manifest m = sb::loadManifest(dir / "manifest.json");
  ASSERT_EQ(m.cases.size(), cases.size());
  const sb::Image plain = sb::runRender(sb::caseRequest(m.cases[0], "gl")).image;
  for (std::size_t i = 1; i < m.cases.size(); ++i) {
    const sb::Image img = sb::runRender(sb::caseRequest(m.cases[i], "gl")).image;
    EXPECT_NE(img.pixels, plain.pixels) << m.cases[i].name << " renders as if the key were ignored";
  }

  const sbtest::CliResult bless =
      sbtest::runCli("bless --baselines " + dir.string() + " --filter '^(plain|posed)$'");
  ASSERT_EQ(bless.status, 0) << bless.out << bless.err;
  EXPECT_NE(sbtest::readFile(dir / "plain.gl.png"), sbtest::readFile(dir / "posed.gl.png"));
  const sbtest::CliResult check =
      sbtest::runCli("check --baselines " + dir.string() + " --filter '^(plain|posed)$' --out " +
                     (dir / "out").string());
  EXPECT_EQ(check.status, 0) << check.out << check.err;
  fs::remove_all(dir);
}

// The docs' settings table is the table's (regenerate: `strandbench list --settings-markdown`).
TEST(Settings, DocsHoldTheTable) {
  const std::string table = sb::settingsMarkdown();
  for (const char* doc : {"docs/suites-and-results.md", "docs/usage.md"}) {
    const std::string text = sbtest::readFile(fs::path(SB_SOURCE_DIR) / doc);
    EXPECT_NE(text.find(table), std::string::npos)
        << doc << " lacks the settings table; paste `strandbench list --settings-markdown`:\n"
        << table;
  }
  const sbtest::CliResult list = sbtest::runCli("list --settings-markdown");
  EXPECT_EQ(list.status, 0);
  EXPECT_EQ(list.out, table);
}

}  // namespace
