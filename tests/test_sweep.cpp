// Suites and sweeps: expansion, resume after a kill, shards and merge, the
// reference computed once (and not at all when no case needs it), bad input.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <regex>

#include "browser_util.h"
#include "harness/suite.h"
#include "imaging/image.h"
#include "imaging/metrics.h"
#include "test_util.h"

namespace {

using namespace sbtest;
namespace fs = std::filesystem;
using json = nlohmann::json;

// Two groups, both backends, a reference and a probe: small enough for seconds.
const char* kTinySuite = R"({
  "name": "tiny",
  "defaults": {"scene": "straight:strands=60,points=6,head=0", "size": "24x24", "repeat": 2,
               "warmup": 0, "reference": true},
  "presets": {"clumps": {"scene": "clustered:strands=60,points=6,head=0,alpha=0.4,clusters=6"}},
  "groups": [
    {"name": "shadows", "axes": {"shadow": ["none", "dom:layers=3", "occupancy"]}},
    {"name": "oit", "preset": "clumps", "backends": ["gl"], "oit": "wavg",
     "axes": {"shadow.maps": [2, 4]}, "shadow": "osm",
     "probe": {"texel": [12, 12], "map_size": 24, "samples": 8}}
  ]
})";

fs::path writeSuite(const fs::path& dir, const std::string& text, const std::string& name) {
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p;
}

// results.json without what differs run to run: timings, the context, devices.
json withoutTimings(json doc) {
  doc.erase("context");
  for (auto& r : doc["results"]) {
    r.erase("frame_ms");
    r.erase("measurement");
    for (auto& p : r["passes"]) p.erase("ms");
  }
  return doc;
}

json results(const fs::path& dir) { return json::parse(readFile(dir / "results.json")); }

TEST(Suite, ExpandsAxesInOrderWithBackendInnermost) {
  const sb::Suite s = sb::parseSuite(kTinySuite, "tiny.json");
  ASSERT_EQ(s.cases.size(), 8u);
  EXPECT_EQ(s.cases[0].id, "shadows/shadow=none,backend=gl");
  EXPECT_EQ(s.cases[1].id, "shadows/shadow=none,backend=vulkan");
  EXPECT_EQ(s.cases[6].id, "oit/shadow.maps=2,backend=gl");
  // The axis sets one option in the group's spec; the preset's scene applies.
  EXPECT_EQ(s.cases[7].request.shadow, "osm:maps=4");
  EXPECT_EQ(s.cases[7].request.scene, "clustered:strands=60,points=6,head=0,alpha=0.4,clusters=6");
  EXPECT_EQ(s.cases[7].request.oit, "wavg");
  EXPECT_TRUE(s.cases[7].request.probe.has_value());
  EXPECT_EQ(s.cases[0].request.width, 24u);
  EXPECT_EQ(s.cases[0].request.repeat, 2);
  // Stems are file-system safe and distinct.
  std::set<std::string> stems;
  for (const auto& c : s.cases) {
    EXPECT_TRUE(std::regex_match(c.stem, std::regex("[A-Za-z0-9._=-]+"))) << c.stem;
    stems.insert(c.stem);
  }
  EXPECT_EQ(stems.size(), s.cases.size());
}

TEST(Suite, BadSuitesNameTheProblem) {
  expectInputError([] { sb::parseSuite("{\n  \"name\": \"x\",\n  \"groups\": [,]\n}", "s.json"); },
                   {"s.json", "not valid JSON", "line 3"});
  expectInputError([] { sb::parseSuite(R"({"name": "x", "grups": []})", "s.json"); },
                   {"grups", "groups"});
  expectInputError(
      [] {
        sb::parseSuite(R"({"name": "x", "groups": [{"name": "g", "shadw": "dom"}]})", "s.json");
      },
      {"group 'g'", "shadw", "shadow"});
  expectInputError(
      [] {
        sb::parseSuite(R"({"name": "x", "groups": [{"name": "g", "shadow": "dmo"}]})", "s.json");
      },
      {"dmo", "dom"});
  expectInputError(
      [] {
        sb::parseSuite(R"({"name": "x", "groups": [{"name": "g", "axes": {"shadow.layers": []}}]})",
                       "s.json");
      },
      {"shadow.layers", "non-empty"});
  expectInputError(
      [] {
        sb::parseSuite(
            R"({"name": "x", "groups": [{"name": "g", "shadow": "dom", "axes": {"shadow.layers": [0]}}]})",
            "s.json");
      },
      {"layers"});
  expectInputError(
      [] {
        sb::parseSuite(R"({"name": "x", "groups": [{"name": "g", "scene": "curlly"}]})", "s.json");
      },
      {"curlly", "curly"});
  expectInputError(
      [] {
        sb::parseSuite(R"({"name": "x", "groups": [{"name": "g", "size": "0x0"}]})", "s.json");
      },
      {"0x0"});
}

TEST(Sweep, ResumedAfterAKillGivesTheSameResults) {
  const fs::path dir = tempDir("sweep-resume");
  const fs::path suite = writeSuite(dir, kTinySuite, "tiny.json");
  ASSERT_EQ(runCli("sweep " + suite.string() + " --out " + (dir / "full").string()).status, 0);

  // Killed (SIGKILL, no chance to clean up) once two cases are written.
  const std::string part = (dir / "part").string();
  const std::string script =
      "( " + std::string(SB_CLI) + " sweep " + suite.string() + " --out " + part +
      " >/dev/null 2>&1 & pid=$!; " + "while [ $(ls " + part +
      "/cases 2>/dev/null | grep -c 'json$') -lt 2 ]; do sleep 0.02; done; " +
      "kill -9 $pid; wait $pid 2>/dev/null )";
  ASSERT_EQ(std::system(("bash -c '" + script + "'").c_str()) >= 0, true);
  ASSERT_FALSE(fs::exists(fs::path(part) / "results.json")) << "the kill came too late";
  int written = 0;
  for (const auto& e : fs::directory_iterator(fs::path(part) / "cases"))
    written += e.path().extension() == ".json";
  ASSERT_GE(written, 2);
  ASSERT_LT(written, 8);

  // Without --resume the folder is refused, and left as it is.
  const CliResult again = runCli("sweep " + suite.string() + " --out " + part);
  EXPECT_EQ(again.status, 2);
  EXPECT_NE(again.err.find("--resume"), std::string::npos) << again.err;

  const CliResult resumed = runCli("sweep " + suite.string() + " --out " + part + " --resume");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("already done"), std::string::npos) << resumed.out;
  EXPECT_EQ(withoutTimings(results(part)), withoutTimings(results(dir / "full")));
  fs::remove_all(dir);
}

TEST(Sweep, ShardsMergeIntoTheUnshardedResults) {
  const fs::path dir = tempDir("sweep-shards");
  const fs::path suite = writeSuite(dir, kTinySuite, "tiny.json");
  ASSERT_EQ(runCli("sweep " + suite.string() + " --out " + (dir / "full").string()).status, 0);
  for (const char* shard : {"1/2", "2/2"})
    ASSERT_EQ(runCli("sweep " + suite.string() + " --shard " + shard + " --out " +
                     (dir / (std::string("s") + shard[0])).string())
                  .status,
              0);
  EXPECT_EQ(results(dir / "s1")["results"].size() + results(dir / "s2")["results"].size(), 8u);
  const CliResult merged = runCli("merge --out " + (dir / "merged").string() + " " +
                                  (dir / "s1").string() + " " + (dir / "s2").string());
  ASSERT_EQ(merged.status, 0) << merged.err;
  EXPECT_EQ(withoutTimings(results(dir / "merged")), withoutTimings(results(dir / "full")));
  // A shard given twice is refused, and nothing is created.
  const CliResult twice = runCli("merge --out " + (dir / "twice").string() + " " +
                                 (dir / "s1").string() + " " + (dir / "s1").string());
  EXPECT_EQ(twice.status, 2);
  EXPECT_NE(twice.err.find("in both"), std::string::npos) << twice.err;
  EXPECT_FALSE(fs::exists(dir / "twice"));
  fs::remove_all(dir);
}

TEST(Sweep, ReferenceComputedOncePerSceneAndViewAndNotWhenUnneeded) {
  const fs::path dir = tempDir("sweep-ref");
  // Three shadow techniques on one backend share one reference.
  const fs::path once = writeSuite(dir, R"({"name": "once",
    "defaults": {"scene": "straight:strands=40,points=5,head=0", "size": "16x16", "repeat": 1,
                 "warmup": 0, "reference": true, "backends": ["gl"]},
    "groups": [{"name": "g", "axes": {"shadow": ["none", "dom", "osm:maps=4"]}}]})",
                                   "once.json");
  CliResult r = runCli("sweep " + once.string() + " --out " + (dir / "once").string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("references rendered: 1\n"), std::string::npos) << r.out;

  const fs::path none = writeSuite(dir, R"({"name": "none",
    "defaults": {"scene": "straight:strands=40,points=5,head=0", "size": "16x16", "repeat": 1,
                 "warmup": 0, "backends": ["gl"]},
    "groups": [{"name": "g", "axes": {"shadow": ["none", "dom"]}}]})",
                                   "none.json");
  r = runCli("sweep " + none.string() + " --out " + (dir / "none").string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("references rendered: 0\n"), std::string::npos) << r.out;
  // Named: a range-for over results(...)["results"] reads a destroyed temporary.
  const json noneRun = results(dir / "none");
  for (const auto& res : noneRun.at("results")) {
    EXPECT_FALSE(res.contains("error"));
    EXPECT_FALSE(res.contains("reference"));
    EXPECT_FALSE(res.contains("measurement_graph"));
  }
  fs::remove_all(dir);
}

TEST(Sweep, EachShadingModelGetsItsOwnReference) {
  // The reference's image is shaded with the case's model: the exact techniques score zero under
  // every model, where a reference shared across models would score Kajiya-Kay against Marschner
  // (the control: the two models' images differ).
  const fs::path dir = tempDir("sweep-ref-shading");
  const fs::path suite = writeSuite(dir, R"({"name": "shading",
    "defaults": {"scene": "straight:strands=40,points=5,head=0", "size": "24x24", "repeat": 1,
                 "warmup": 0, "reference": true, "backends": ["gl"], "shadow": "exact",
                 "oit": "abuffer"},
    "groups": [{"name": "g", "axes": {"shading": ["kajiya-kay", "marschner", "sadeghi"]}}]})",
                                    "shading.json");
  const CliResult r = runCli("sweep " + suite.string() + " --out " + (dir / "o").string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("references rendered: 3\n"), std::string::npos) << r.out;
  const json run = results(dir / "o");
  ASSERT_EQ(run.at("results").size(), 3u);
  for (const auto& res : run.at("results"))
    EXPECT_LT(res.at("error").at("image").at("rmse").get<double>(), 1e-6) << res.at("shading");
  const fs::path a = dir / "o" / run["results"][0]["images"]["image"].get<std::string>();
  const fs::path b = dir / "o" / run["results"][1]["images"]["image"].get<std::string>();
  EXPECT_GT(sb::compareImages(sb::readImage(a.string()), sb::readImage(b.string())).rmse, 0.01)
      << "the models' images differ";
  fs::remove_all(dir);
}

TEST(Sweep, FilterSelectsCasesById) {
  const fs::path dir = tempDir("sweep-filter");
  const fs::path suite = writeSuite(dir, kTinySuite, "tiny.json");
  const CliResult r =
      runCli("sweep " + suite.string() + " --filter 'dom.*gl' --out " + (dir / "f").string());
  ASSERT_EQ(r.status, 0) << r.err;
  const json doc = results(dir / "f");
  ASSERT_EQ(doc["results"].size(), 1u);
  EXPECT_EQ(doc["results"][0]["case"]["id"], "shadows/shadow=dom:layers=3,backend=gl");
  EXPECT_EQ(doc["schema_version"], 1);
  EXPECT_TRUE(doc["context"].contains("commit"));
  EXPECT_TRUE(doc["context"].contains("cpu"));
  fs::remove_all(dir);
}

// The acceptance check on a real sweep's report: it loads offline in headless
// Chromium with no console message, shows the tables and the error-against-time
// chart, and its screenshot is not blank.
TEST(Sweep, RealReportLoadsInChromium) {
  if (!fs::exists(sbtest::kChromium))
    GTEST_SKIP() << sbtest::kChromium << " is not installed (apt-get install chromium)";
  const fs::path dir = tempDir("sweep-browser");
  const fs::path suite = writeSuite(dir, kTinySuite, "tiny.json");
  ASSERT_EQ(runCli("sweep " + suite.string() + " --out " + (dir / "run").string()).status, 0);
  for (const char* f : {"results.json", "results.csv", "report.md", "report.html"})
    EXPECT_TRUE(fs::is_regular_file(dir / "run" / f)) << f;
  const sbtest::PageLoad page = sbtest::loadPage(dir / "run" / "report.html", dir / "chromium");
  ASSERT_EQ(page.status, 0) << page.log;
  EXPECT_TRUE(page.console.empty()) << ::testing::PrintToString(page.console);
  EXPECT_NE(page.dom.find("<table>"), std::string::npos);
  EXPECT_NE(page.dom.find("class=\"chart-error-time\""), std::string::npos);
  EXPECT_NE(page.dom.find("data:image/png;base64,"), std::string::npos);
  const sbtest::ScreenshotVerdict shot = sbtest::inspectScreenshot(page.screenshot);
  EXPECT_FALSE(shot.blank) << shot.distinct << " colours, " << shot.inked << " inked";
  fs::remove_all(dir);
}

// A group's cases are timed in interleaved rounds: every case's first round starts before any
// case's second (a slow drift hits them alike); the rounds adapt to --target-ci within
// --min-reps..--max-reps; --no-interleave takes a case's frames back to back.
TEST(Sweep, RoundsInterleaveAGroupsCasesAndAdaptToTheTarget) {
  const fs::path dir = tempDir("sweep-rounds");
  const fs::path suite = writeSuite(dir, kTinySuite, "tiny.json");
  auto caseFiles = [](const fs::path& out) {
    std::vector<json> r;
    for (const auto& e : fs::directory_iterator(out / "cases"))
      r.push_back(json::parse(readFile(e.path())));
    std::sort(r.begin(), r.end(), [](const json& a, const json& b) {
      return a["case"]["index"].get<int>() < b["case"]["index"].get<int>();
    });
    return r;
  };
  const std::string base = "sweep " + suite.string() + " --filter '^shadows/' --out ";
  CliResult r = runCli(base + (dir / "a").string());
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<json> cases = caseFiles(dir / "a");
  ASSERT_EQ(cases.size(), 6u);
  double lastFirstRound = 0, firstSecondRound = 1e9;
  for (const json& c : cases) {
    const json& m = c["measurement"];
    EXPECT_EQ(m["mode"], "interleaved");
    ASSERT_EQ(m["samples"], 2) << "repeat 2: two rounds";
    ASSERT_EQ(c["frame_ms"]["samples"].size(), 2u);
    EXPECT_EQ(c["repeat"], 2);
    for (const json& p : c["passes"]) EXPECT_EQ(p["ms"]["samples"].size(), 2u) << p["name"];
    const auto ci = m["median_ci95_ms"].get<std::vector<double>>();
    EXPECT_LE(ci[0], m["median_ms"].get<double>());
    EXPECT_GE(ci[1], m["median_ms"].get<double>());
    const auto start = m["round_start_s"].get<std::vector<double>>();
    ASSERT_EQ(start.size(), 2u);
    lastFirstRound = std::max(lastFirstRound, start[0]);
    firstSecondRound = std::min(firstSecondRound, start[1]);
  }
  EXPECT_LT(lastFirstRound, firstSecondRound) << "every case's first round before any second";
  EXPECT_NE(r.out.find("2 interleaved rounds each"), std::string::npos) << r.out;

  // A target no frame time meets: --max-reps rounds.
  r = runCli(base + (dir / "b").string() + " --min-reps 3 --max-reps 4 --target-ci 0.0001");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const json& c : caseFiles(dir / "b")) EXPECT_EQ(c["measurement"]["samples"], 4);
  // A target every median meets at once: --min-reps rounds.
  r = runCli(base + (dir / "c").string() + " --min-reps 3 --max-reps 6 --target-ci 100");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const json& c : caseFiles(dir / "c")) EXPECT_EQ(c["measurement"]["samples"], 3);

  r = runCli(base + (dir / "d").string() + " --no-interleave");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const json& c : caseFiles(dir / "d")) {
    EXPECT_EQ(c["measurement"]["mode"], "back-to-back");
    EXPECT_EQ(c["frame_ms"]["samples"].size(), 2u);
    EXPECT_FALSE(c["measurement"].contains("round_start_s"));
  }
  // The report shows the interval.
  EXPECT_NE(readFile(dir / "a" / "report.md").find("95% CI"), std::string::npos);

  for (const std::string bad : {"--no-interleave --min-reps 3", "--min-reps 3 --max-reps 2",
                                "--target-ci 101", "--min-reps -1"}) {
    r = runCli(base + (dir / "e").string() + " " + bad);
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_FALSE(fs::exists(dir / "e")) << bad;
  }
  fs::remove_all(dir);
}

// The line a sweep prints per case shows the statistic the report uses: the
// median over all its rounds (frame_ms.median of its result), not its first
// round's time.
TEST(Sweep, CaseLineShowsTheReportsMedian) {
  const fs::path dir = tempDir("sweep-line");
  const fs::path suite = writeSuite(dir, kTinySuite, "tiny.json");
  const CliResult r = runCli("sweep " + suite.string() + " --filter '^shadows/' --min-reps 5 " +
                             "--out " + (dir / "a").string());
  ASSERT_EQ(r.status, 0) << r.err;
  int cases = 0;
  for (const auto& e : fs::directory_iterator(dir / "a" / "cases")) {
    const json c = json::parse(readFile(e.path()));
    ASSERT_EQ(c["frame_ms"]["samples"].size(), 5u);
    char median[32];
    std::snprintf(median, sizeof median, "%.2f", c["frame_ms"]["median"].get<double>());
    const std::string id = c["case"]["id"].get<std::string>();
    const std::string line = "] " + id + "  frame " + median + " ms";
    EXPECT_NE(r.out.find(line), std::string::npos) << "no '" << line << "' in:\n" << r.out;
    ++cases;
  }
  EXPECT_EQ(cases, 6);
  fs::remove_all(dir);
}

// A suite whose scene axis names a file: SCENE is the second scene's spec.
std::string fileSuite(const std::string& scene) {
  return R"({
  "name": "files",
  "defaults": {"size": "16x16", "repeat": 1, "warmup": 0, "backends": ["gl"]},
  "groups": [{"name": "g", "axes": {"scene": ["straight:strands=20,points=4,head=0", ")" +
         scene + R"(", "curly:strands=20,points=4,head=0"]}}]
})";
}

// Every file a suite names is read before anything runs: a missing or truncated one refuses
// the sweep (exit 2, the case and the file named, no folder, no case run).
TEST(Sweep, AMissingOrBrokenFileIsRefusedBeforeAnythingRuns) {
  const fs::path dir = tempDir("sweep-files");
  std::ofstream(dir / "cut.hair", std::ios::binary) << std::string("HAIR\x05\x00", 6);
  for (const std::string& scene :
       {"file:path=" + (dir / "missing.hair").string(), "file:path=" + (dir / "cut.hair").string(),
        "straight:strands=20,points=4,mesh=" + (dir / "missing.obj").string()}) {
    const fs::path suite = writeSuite(dir, fileSuite(scene), "files.json");
    const CliResult r = runCli("sweep " + suite.string() + " --out " + (dir / "o").string());
    EXPECT_EQ(r.status, 2) << scene << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find("case g/scene=" + scene), std::string::npos) << r.err;
    const std::string file = scene.substr(scene.rfind('=') + 1);
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_EQ(r.out.find("[1/"), std::string::npos) << "a case ran:\n" << r.out;
    EXPECT_FALSE(fs::exists(dir / "o")) << scene;
  }
  fs::remove_all(dir);
}

// A case that fails only when it runs (points=1 is refused by the scene's generator) is recorded
// with its message; the other cases run, results.json and the reports list the failure, exit 1.
TEST(Sweep, ACaseThatFailsAtRunTimeIsRecordedAndTheOthersFinish) {
  const fs::path dir = tempDir("sweep-runfail");
  const fs::path suite =
      writeSuite(dir, fileSuite("straight:strands=20,points=1,head=0"), "files.json");
  const fs::path out = dir / "o";
  const CliResult r = runCli("sweep " + suite.string() + " --out " + out.string());
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  const std::string bad = "g/scene=straight:strands=20,points=1,head=0,backend=gl";
  EXPECT_NE(r.out.find("case " + bad + " failed: "), std::string::npos) << r.out;
  const json doc = results(out);
  ASSERT_EQ(doc["results"].size(), 3u);
  int failed = 0;
  for (const auto& res : doc["results"]) {
    if (res["case"]["id"] == bad) {
      ASSERT_TRUE(res.contains("failed")) << res.dump();
      EXPECT_NE(res["failed"]["reason"].get<std::string>().find("points"), std::string::npos)
          << res["failed"].dump();
      ++failed;
    } else {
      EXPECT_FALSE(res.contains("failed")) << res.dump();
      EXPECT_TRUE(res["frame_ms"]["median"].is_number());
    }
  }
  EXPECT_EQ(failed, 1);
  for (const char* report : {"report.md", "report.html"}) {
    const std::string text = readFile(out / report);
    EXPECT_NE(text.find("Failed cases"), std::string::npos) << report;
    EXPECT_NE(text.find("points=1"), std::string::npos) << report;
  }
  fs::remove_all(dir);
}

// A case on a driver this machine lacks (drivers/ empty here) is not run: listed with the reason
// and scripts/drivers.sh, the others run, exit 0; --require-drivers or CI=true make it exit 1.
// Control: a name scripts/drivers.sh does not fetch is a mistake, refused before anything runs.
TEST(Sweep, CasesOnAMissingDriverAreListedAndFailOnlyWhenRequired) {
  const fs::path dir = tempDir("sweep-nodriver");
  fs::create_directories(dir / "drivers");
  const std::string env = "-u CI SB_DRIVERS_DIR=" + (dir / "drivers").string();
  const std::string suiteText = R"({
    "name": "drivers",
    "defaults": {"scene": "straight:strands=20,points=4,head=0", "size": "16x16", "repeat": 1,
                 "warmup": 0, "backends": ["gl"]},
    "groups": [{"name": "g", "drivers": ["system", "DRIVER"]},
               {"name": "rq", "backends": ["vulkan"], "shadow": "rt:tier=ray_query"}]
  })";
  auto withDriver = [&](const std::string& d) {
    return std::regex_replace(suiteText, std::regex("DRIVER"), d);
  };
  const fs::path suite = writeSuite(dir, withDriver("mesa-25.0"), "d.json");
  const std::string missing = "g/driver=mesa-25.0,backend=gl";

  const CliResult r = runCli("sweep " + suite.string() + " --out " + (dir / "a").string(), env);
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  const json doc = results(dir / "a");
  ASSERT_EQ(doc["results"].size(), 3u);
  // Ray queries: not run where the device lacks them (the system's Mesa 22.3 lavapipe), else run.
  bool noRayQueries = false;
  for (const auto& res : doc["results"]) {
    if (res["case"]["group"] != "rq" || !res.contains("failed")) continue;
    noRayQueries = true;
    EXPECT_EQ(res["failed"]["unavailable"], true) << res.dump();
    EXPECT_NE(res["failed"]["enable"].get<std::string>().find("VK_KHR_ray_query"),
              std::string::npos);
  }
  EXPECT_NE(r.out.find(noRayQueries ? "2 cases not run" : "1 case not run"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("  " + missing + ": not run: unknown driver 'mesa-25.0'"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("to run them: scripts/drivers.sh"), std::string::npos) << r.out;
  for (const auto& res : doc["results"]) {
    if (res["case"]["group"] != "g") continue;
    const bool isMissing = res["case"]["id"] == missing;
    EXPECT_EQ(res.contains("failed"), isMissing) << res.dump();
    if (isMissing) {
      EXPECT_EQ(res["failed"]["unavailable"], true);
    }
  }
  EXPECT_NE(readFile(dir / "a" / "report.md").find("scripts/drivers.sh"), std::string::npos);

  const CliResult required =
      runCli("sweep " + suite.string() + " --require-drivers --out " + (dir / "b").string(), env);
  EXPECT_EQ(required.status, 1) << required.out << required.err;
  EXPECT_EQ(results(dir / "b")["results"].size(), 3u);
  const CliResult ci = runCli("sweep " + suite.string() + " --out " + (dir / "c").string(),
                              "CI=true SB_DRIVERS_DIR=" + (dir / "drivers").string());
  EXPECT_EQ(ci.status, 1) << ci.out << ci.err;
  EXPECT_NE(ci.out.find("the cases not run fail the sweep"), std::string::npos) << ci.out;

  const fs::path typo = writeSuite(dir, withDriver("mesa-25.O"), "typo.json");
  const CliResult t = runCli("sweep " + typo.string() + " --out " + (dir / "t").string(), env);
  EXPECT_EQ(t.status, 2) << t.out;
  EXPECT_NE(t.err.find("unknown driver 'mesa-25.O'"), std::string::npos) << t.err;
  EXPECT_FALSE(fs::exists(dir / "t"));
  fs::remove_all(dir);
}

TEST(Sweep, BadInputExitsTwoAndWritesNothing) {
  const fs::path dir = tempDir("sweep-bad");
  const fs::path bad =
      writeSuite(dir, "{\"name\": \"b\",\n\"groups\": [\n  {\"name\": 1}\n", "b.json");
  CliResult r = runCli("sweep " + bad.string() + " --out " + (dir / "o").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("line"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "o"));

  const fs::path suite = writeSuite(dir, kTinySuite, "tiny.json");
  r = runCli("sweep " + suite.string() + " --out " + (dir / "tiny.json" / "o").string());
  EXPECT_EQ(r.status, 2);
  r = runCli("sweep " + suite.string() + " --shard 3/2 --out " + (dir / "o").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--shard"), std::string::npos) << r.err;
  r = runCli("sweep " + suite.string() + " --filter '(' --out " + (dir / "o").string());
  EXPECT_EQ(r.status, 2);
  r = runCli("sweep " + (dir / "missing.json").string() + " --out " + (dir / "o").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("missing.json"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "o"));
  r = runCli("report " + dir.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("sweep.json"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

}  // namespace
