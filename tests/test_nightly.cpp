// Nightly sweeps: shards from a scheduler's environment, merge naming missing shards, the
// statistics that make timings hold on a noisy machine (bootstrap intervals, outliers, change
// points) and `history` on synthetic runs with a known step and with pure noise.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <random>

#include "base/errors.h"
#include "harness/measure.h"
#include "harness/sweep.h"
#include "reports/stats.h"
#include "test_util.h"

namespace {

using namespace sbtest;
namespace fs = std::filesystem;
using json = nlohmann::json;

// ---- --shard auto ----

sb::AutoShard autoShard(const std::map<std::string, std::string>& vars,
                        const std::string& text = "auto") {
  return sb::shardFromEnvironment(text, [&](const char* name) -> const char* {
    auto it = vars.find(name);
    return it == vars.end() ? nullptr : it->second.c_str();
  });
}

std::string autoShardError(const std::map<std::string, std::string>& vars,
                           const std::string& text = "auto") {
  try {
    autoShard(vars, text);
  } catch (const sb::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ShardAuto, ReadsEachScheduler) {
  // Slurm: --array=0-3 (task 2 is the third shard), --array=1-4, --array=0-6:2.
  auto s = autoShard({{"SLURM_ARRAY_TASK_ID", "2"},
                      {"SLURM_ARRAY_TASK_COUNT", "4"},
                      {"SLURM_ARRAY_TASK_MIN", "0"}});
  EXPECT_EQ(s.index, 3);
  EXPECT_EQ(s.count, 4);
  EXPECT_EQ(s.source, "SLURM_ARRAY_TASK_ID");
  s = autoShard({{"SLURM_ARRAY_TASK_ID", "1"},
                 {"SLURM_ARRAY_TASK_COUNT", "4"},
                 {"SLURM_ARRAY_TASK_MIN", "1"}});
  EXPECT_EQ(s.index, 1);
  s = autoShard({{"SLURM_ARRAY_TASK_ID", "6"},
                 {"SLURM_ARRAY_TASK_COUNT", "4"},
                 {"SLURM_ARRAY_TASK_MIN", "0"},
                 {"SLURM_ARRAY_TASK_STEP", "2"}});
  EXPECT_EQ(s.index, 4);
  // Kubernetes indexed job: 0-based, the count given.
  s = autoShard({{"JOB_COMPLETION_INDEX", "0"}}, "auto/3");
  EXPECT_EQ(s.index, 1);
  EXPECT_EQ(s.count, 3);
  // GitLab: 1-based.
  s = autoShard({{"CI_NODE_INDEX", "2"}, {"CI_NODE_TOTAL", "2"}});
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 2);
  // GoogleTest: 0-based.
  s = autoShard({{"GTEST_SHARD_INDEX", "0"}, {"GTEST_TOTAL_SHARDS", "5"}});
  EXPECT_EQ(s.index, 1);
  EXPECT_EQ(s.count, 5);
}

TEST(ShardAuto, BadOrMissingVariablesNameThem) {
  const std::string none = autoShardError({});
  for (const char* v :
       {"SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX", "CI_NODE_INDEX", "GTEST_SHARD_INDEX"})
    EXPECT_NE(none.find(v), std::string::npos) << none;
  EXPECT_NE(autoShardError({{"JOB_COMPLETION_INDEX", "1"}}).find("auto/N"), std::string::npos);
  EXPECT_NE(
      autoShardError({{"CI_NODE_INDEX", "x"}, {"CI_NODE_TOTAL", "2"}}).find("CI_NODE_INDEX=x"),
      std::string::npos);
  EXPECT_NE(autoShardError({{"CI_NODE_INDEX", "3"}, {"CI_NODE_TOTAL", "2"}}).find("outside"),
            std::string::npos);
  EXPECT_NE(autoShardError({{"SLURM_ARRAY_TASK_ID", "3"},
                            {"SLURM_ARRAY_TASK_COUNT", "4"},
                            {"SLURM_ARRAY_TASK_MIN", "0"},
                            {"SLURM_ARRAY_TASK_STEP", "2"}})
                .find("steps"),
            std::string::npos);
  EXPECT_NE(autoShardError({}, "auto/x").find("auto/N"), std::string::npos);
}

TEST(ShardAuto, CliWithoutASchedulerIsAnInputError) {
  const fs::path dir = tempDir("shard-auto");
  const CliResult r = runCli("sweep suites/quick.json --shard auto --out " + (dir / "o").string());
  // The environment of the test may hold a scheduler's variables (a CI job): only judge a clean
  // one.
  if (!std::getenv("SLURM_ARRAY_TASK_ID") && !std::getenv("CI_NODE_INDEX") &&
      !std::getenv("GTEST_SHARD_INDEX") && !std::getenv("JOB_COMPLETION_INDEX")) {
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("SLURM_ARRAY_TASK_ID"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "o"));
  }
  fs::remove_all(dir);
}

// ---- merge with a missing shard ----

TEST(MergeMissing, NamesTheMissingShardAndExitsOne) {
  const fs::path dir = tempDir("merge-missing");
  const fs::path suite = dir / "s.json";
  std::ofstream(suite) << R"({"name": "m",
    "defaults": {"scene": "straight:strands=20,points=4,head=0", "size": "12x12", "repeat": 1,
                 "warmup": 0, "backends": ["gl"]},
    "groups": [{"name": "g", "axes": {"shadow": ["none", "dom:layers=3", "occupancy"]}}]})";
  for (const char* shard : {"1/3", "3/3"})
    ASSERT_EQ(runCli("sweep " + suite.string() + " --shard " + shard + " --out " +
                     (dir / (std::string("s") + shard[0])).string())
                  .status,
              0);
  const std::string inputs = (dir / "s1").string() + " " + (dir / "s3").string();
  CliResult r = runCli("merge --out " + (dir / "m").string() + " " + inputs);
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("missing shard 2/3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("g/shadow=dom:layers=3,backend=gl"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "m"));
  // --allow-missing merges what is there and records what is not.
  r = runCli("merge --allow-missing --out " + (dir / "m").string() + " " + inputs);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("missing shard 2/3"), std::string::npos) << r.out;
  const json merged = json::parse(readFile(dir / "m" / "results.json"));
  EXPECT_EQ(merged["results"].size(), 2u);
  EXPECT_EQ(merged["context"]["missing"]["shards"], json::array({2}));
  // Each shard's context is kept (host, devices, drivers).
  ASSERT_EQ(merged["context"]["shards"].size(), 2u);
  for (const auto& s : merged["context"]["shards"]) {
    EXPECT_TRUE(s["context"].contains("cpu"));
    EXPECT_FALSE(s["context"]["devices"].empty());
    EXPECT_TRUE(s["context"].contains("load_before"));
  }
  // All three: nothing missing.
  ASSERT_EQ(
      runCli("sweep " + suite.string() + " --shard 2/3 --out " + (dir / "s2").string()).status, 0);
  r = runCli("merge --out " + (dir / "all").string() + " " + inputs + " " + (dir / "s2").string());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json::parse(readFile(dir / "all" / "results.json"))["results"].size(), 3u);
  fs::remove_all(dir);
}

// ---- bootstrap intervals, outliers ----

TEST(Bootstrap, MedianIntervalCoversTheTrueMedianAtAbout95Percent) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(100.0, 5.0);
  int covered = 0;
  const int trials = 200;
  for (int t = 0; t < trials; ++t) {
    std::vector<double> x(15);
    for (double& v : x) v = noise(rng);
    const sb::Interval i = sb::bootstrapMedian(x, 0.95, 1000, std::uint64_t(t + 1));
    covered += i.low <= 100.0 && 100.0 <= i.high;
    EXPECT_LE(i.low, i.estimate);
    EXPECT_GE(i.high, i.estimate);
  }
  // The percentile interval of a median is a little conservative at n = 15.
  EXPECT_GE(covered, int(0.90 * trials));
  EXPECT_LE(covered, trials);
}

TEST(Bootstrap, PairedRatioCancelsASharedDrift) {
  // Two cases measured in rounds while the machine slows down 2x over the rounds: the ratio is
  // 1.5 in every round. Paired resampling keeps rounds together: a tight interval around 1.5;
  // resampling each alone sees the drift and gives a wide one.
  std::vector<double> a, b;
  for (int r = 0; r < 12; ++r) {
    const double drift = 1.0 + r / 11.0;
    b.push_back(10 * drift);
    a.push_back(15 * drift);
  }
  const sb::Interval paired = sb::bootstrapRatio(a, b, true);
  const sb::Interval alone = sb::bootstrapRatio(a, b, false);
  EXPECT_NEAR(paired.low, 1.5, 1e-9);
  EXPECT_NEAR(paired.high, 1.5, 1e-9);
  EXPECT_GT(alone.high - alone.low, 0.3);
  EXPECT_EQ(sb::orderingVerdict(paired, 1.0, false), "holds");
  EXPECT_EQ(sb::orderingVerdict(paired, 1.0, true), "fails");
  EXPECT_EQ(sb::orderingVerdict({1.0, 0.9, 1.1}, 1.0, true), "undecided");
}

TEST(Outliers, TukeyFencesMarkOnlyTheFarValues) {
  const std::vector<double> x = {10, 10.2, 9.9, 10.1, 10.0, 30.0, 10.3, 9.8};
  const auto o = sb::tukeyOutliers(x);
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_EQ(o[i], x[i] == 30.0) << i;
}

TEST(Measure, RoundsInterleaveTheCasesAndAdaptToTheTarget) {
  std::vector<int> order;
  std::vector<std::function<double()>> cases;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 1);
  for (int i = 0; i < 3; ++i)
    cases.push_back([&, i] {
      order.push_back(i);
      return 100.0 + (i == 2 ? 20 : 1) * noise(rng);  // case 2 is noisy
    });
  sb::RepetitionOptions o;
  o.minReps = 3;
  o.maxReps = 40;
  o.targetCiPct = 2;
  const auto m = sb::measureInterleaved(cases, o);
  // Round-robin with a rotating start: 0 1 2, 1 2 0, 2 0 1, ...
  ASSERT_GE(order.size(), 9u);
  EXPECT_EQ((std::vector<int>(order.begin(), order.begin() + 9)),
            (std::vector<int>{0, 1, 2, 1, 2, 0, 2, 0, 1}));
  // Every case got the same rounds; the noisy case made the group take more than the minimum
  // until its interval met the target (or the maximum).
  EXPECT_EQ(m[0].samples.size(), m[2].samples.size());
  EXPECT_GT(m[2].samples.size(), 3u);
  EXPECT_TRUE(m[2].median.relativeHalfWidth() * 100 <= 2 || m[2].samples.size() == 40u);
  // Without a target, exactly --min-reps rounds.
  o.targetCiPct = 0;
  EXPECT_EQ(sb::measureInterleaved(cases, o)[0].samples.size(), 3u);
  o.maxReps = 2;
  EXPECT_THROW(sb::measureInterleaved(cases, o), sb::InputError);
}

// ---- change points and history ----

// 30 runs: per-run medians with 5% noise, a step of `step` from run `at` (0: none).
std::vector<double> series(std::mt19937_64& rng, double step, int at, int n = 30) {
  std::normal_distribution<double> noise(0, 0.05);
  std::vector<double> x;
  for (int i = 0; i < n; ++i)
    x.push_back(100.0 * (1 + (i >= at && at > 0 ? step : 0)) * (1 + noise(rng)));
  return x;
}

TEST(ChangePoints, FindsATenPercentStepInFivePercentNoise) {
  std::mt19937_64 rng(11);
  int found = 0;
  const int trials = 20;
  for (int t = 0; t < trials; ++t) {
    const auto cps = sb::findChangePoints(series(rng, 0.10, 15));
    ASSERT_LE(cps.size(), 2u);
    if (cps.empty()) continue;
    ++found;
    EXPECT_NEAR(cps[0].index, 15, 3);
    EXPECT_NEAR(cps[0].size, 0.10, 0.06);
    EXPECT_LT(cps[0].p, 0.01);
  }
  // A 10% step is two noise sd: found nearly always with 15 runs a side.
  EXPECT_GE(found, 18);
}

TEST(ChangePoints, PureNoiseRaisesAlarmsAtMostAtTheStatedRate) {
  std::mt19937_64 rng(5);
  const int trials = 300;
  int alarms = 0;
  for (int t = 0; t < trials; ++t) alarms += !sb::findChangePoints(series(rng, 0, 0)).empty();
  // alpha = 0.01: expected 3 of 300; 9 or more has probability < 0.5% (binomial).
  EXPECT_LE(alarms, 8) << alarms << " false alarms in " << trials;
}

// A run folder (results.json) with one case per entry of `medians`, 5 repetitions around each.
void writeRun(const fs::path& dir, const std::string& date,
              const std::map<std::string, double>& medians, std::mt19937_64& rng) {
  fs::create_directories(dir);
  std::normal_distribution<double> within(0, 0.01);
  json results = json::array();
  int index = 0;
  for (const auto& [id, m] : medians) {
    std::vector<double> samples;
    for (int i = 0; i < 5; ++i) samples.push_back(m * (1 + within(rng)));
    results.push_back({{"case", {{"id", id}, {"group", "g"}, {"index", index++}}},
                       {"scene", {{"spec", "s"}}},
                       {"shadow", "none"},
                       {"oit", "none"},
                       {"size", {8, 8}},
                       {"frame_ms", {{"median", sb::median(samples)}, {"samples", samples}}},
                       {"passes", json::array()}});
  }
  std::ofstream(dir / "results.json")
      << json{{"context", {{"date", date}}}, {"results", results}}.dump();
}

TEST(HistoryCli, FindsARecentStepAndRaisesTheAlarm) {
  const fs::path dir = tempDir("history-step");
  std::mt19937_64 rng(21);
  const auto step = series(rng, 0.10, 22);  // the newest 8 runs slower by 10%
  const auto noise = series(rng, 0, 0);
  const auto old = series(rng, -0.15, 10);  // faster from run 10: information, no alarm
  for (int i = 0; i < 30; ++i) {
    char date[32];
    std::snprintf(date, sizeof date, "2026-11-%02dT02:00:00Z", i + 1);
    // Named so that folder order is not date order: history sorts by context.date.
    std::string name = "run-";
    name += std::to_string(29 - i);
    writeRun(dir / "runs" / name, date,
             {{"g/step", step[i]}, {"g/noise", noise[i]}, {"g/faster", old[i]}}, rng);
  }
  const CliResult r = runCli("history " + (dir / "runs").string() + " --out " +
                             (dir / "h").string() + " --threshold 5");
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  const json h = json::parse(readFile(dir / "h" / "history.json"));
  EXPECT_EQ(h["alarms"], 1);
  std::map<std::string, json> byId;
  for (const auto& c : h["cases"]) byId[c["id"]] = c;
  ASSERT_EQ(byId["g/step"]["changes"].size(), 1u) << byId["g/step"].dump();
  EXPECT_NEAR(byId["g/step"]["changes"][0]["index"].get<int>(), 22, 2);
  EXPECT_EQ(byId["g/step"]["changes"][0]["date"].get<std::string>().substr(0, 8), "2026-11-");
  EXPECT_TRUE(byId["g/step"]["alarm"].get<bool>());
  EXPECT_TRUE(byId["g/noise"]["changes"].empty());
  EXPECT_FALSE(byId["g/faster"]["alarm"].get<bool>());
  EXPECT_FALSE(byId["g/faster"]["changes"].empty());
  // Sorted by the size of the latest change, largest first; the unchanged case last.
  auto latest = [](const json& c) {
    return c["changes"].empty() ? 0.0 : std::abs(c["changes"].back()["size"].get<double>());
  };
  for (std::size_t i = 1; i < h["cases"].size(); ++i)
    EXPECT_GE(latest(h["cases"][i - 1]), latest(h["cases"][i])) << h["cases"][i]["verdict"];
  EXPECT_EQ(h["cases"][2]["id"], "g/noise");
  for (const auto& c : h["cases"]) std::cout << c["id"] << ": " << c["verdict"] << "\n";
  EXPECT_EQ(h["cases"][0]["points"].size(), 30u);
  EXPECT_LE(h["cases"][0]["points"][0]["ci95"][0].get<double>(),
            h["cases"][0]["points"][0]["median"].get<double>());
  const std::string html = readFile(dir / "h" / "history.html");
  EXPECT_NE(html.find("class=\"change\""), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos);  // offline: no external resources
  // A higher threshold than the step: the change is still reported, no alarm.
  EXPECT_EQ(runCli("history " + (dir / "runs").string() + " --out " + (dir / "h2").string() +
                   " --threshold 20")
                .status,
            0);
  fs::remove_all(dir);
}

TEST(HistoryCli, PureNoiseGivesNoAlarm) {
  const fs::path dir = tempDir("history-noise");
  std::mt19937_64 rng(99);
  std::vector<std::vector<double>> cases;
  for (int c = 0; c < 4; ++c) cases.push_back(series(rng, 0, 0));
  std::vector<std::string> runs;
  for (int i = 0; i < 30; ++i) {
    char date[32];
    std::snprintf(date, sizeof date, "2026-10-%02dT02:00:00Z", i + 1);
    std::string name = "r";  // (not "r" + to_string: GCC 12's -Wrestrict false positive)
    name += std::to_string(i);
    const fs::path run = dir / name;
    writeRun(run, date,
             {{"a", cases[0][i]}, {"b", cases[1][i]}, {"c", cases[2][i]}, {"d", cases[3][i]}}, rng);
    runs.push_back(run.string());
  }
  std::string args;
  for (const auto& r : runs) args += " " + r;
  const CliResult r = runCli("history" + args + " --out " + (dir / "h").string());
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  const json h = json::parse(readFile(dir / "h" / "history.json"));
  EXPECT_EQ(h["alarms"], 0);
  for (const auto& c : h["cases"]) EXPECT_TRUE(c["changes"].empty()) << c["id"];
  fs::remove_all(dir);
}

// Work counters over five runs: one case draws more from run 4 on, one case counts no work.
// The work change is listed with its run, pass and counter, first in the summary and the page;
// it raises no alarm.
TEST(HistoryCli, ListsTheRunWhereWorkChanged) {
  const fs::path dir = tempDir("history-work");
  std::mt19937_64 rng(3);
  std::vector<std::string> runs;
  for (int i = 0; i < 5; ++i) {
    char date[32];
    std::snprintf(date, sizeof date, "2026-09-%02dT02:00:00Z", i + 1);
    const fs::path run = dir / ("r" + std::to_string(i));
    writeRun(run, date, {{"g/counted", 10.0}, {"g/old", 10.0}}, rng);
    json doc = json::parse(readFile(run / "results.json"));
    for (auto& r : doc["results"]) {
      if (r["case"]["id"] != "g/counted") continue;  // g/old: a run from before the counters
      const json work = {{"vertices", 1000}, {"draws", i >= 3 ? 2 : 1}, {"samples_passed", 50}};
      r["passes"] = {{{"name", "color"}, {"ms", r["frame_ms"]}, {"work", work}}};
      r["frame_work"] = work;
    }
    std::ofstream(run / "results.json") << doc.dump();
    runs.push_back(run.string());
  }
  std::string args;
  for (const auto& r : runs) args += " " + r;
  const CliResult r = runCli("history" + args + " --out " + (dir / "h").string());
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(r.out.rfind("work changed: 1 case\n  g/counted: run 4 of 5 (2026-09-04T02:00:00Z): "
                        "pass color: draws 1 -> 2 (x2.00, +100.0%)\ntime changed: ",
                        0),
            0u)
      << r.out;
  const json h = json::parse(readFile(dir / "h" / "history.json"));
  EXPECT_EQ(h["work_changed"], 1);
  std::map<std::string, json> byId;
  for (const auto& c : h["cases"]) byId[c["id"]] = c;
  ASSERT_EQ(byId["g/counted"]["work_changes"].size(), 1u) << byId["g/counted"].dump();
  const json& w = byId["g/counted"]["work_changes"][0];
  EXPECT_EQ(w["index"], 3);
  EXPECT_EQ(w["date"], "2026-09-04T02:00:00Z");
  EXPECT_EQ(w["passes"][0]["pass"], "color");
  EXPECT_EQ(w["passes"][0]["counters"][0]["counter"], "draws");
  EXPECT_EQ(w["passes"][0]["counters"][0]["old"], 1);
  EXPECT_EQ(w["passes"][0]["counters"][0]["new"], 2);
  EXPECT_TRUE(byId["g/old"]["work_changes"].empty());
  const std::string html = readFile(dir / "h" / "history.html");
  const std::size_t work = html.find("<h2>Work changed</h2>"), time = html.find("Time changed");
  ASSERT_NE(work, std::string::npos);
  EXPECT_LT(work, time);
  EXPECT_LT(html.find("draws 1 -&gt; 2"), time) << html.substr(0, 2000);
  EXPECT_NE(html.find("class=\"work\""), std::string::npos);
  fs::remove_all(dir);
}

TEST(HistoryCli, BadInputExitsTwo) {
  const fs::path dir = tempDir("history-bad");
  std::mt19937_64 rng(1);
  writeRun(dir / "a", "2026-01-01T00:00:00Z", {{"x", 1.0}}, rng);
  CliResult r = runCli("history " + (dir / "a").string() + " --out " + (dir / "h").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("at least two runs"), std::string::npos) << r.err;
  std::ofstream(dir / "b.json") << R"({"results": []})";
  r = runCli("history " + (dir / "a").string() + " " + (dir / "b.json").string() + " --out " +
             (dir / "h").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("context.date"), std::string::npos) << r.err;
  r = runCli("history " + (dir / "a").string() + " " + (dir / "a").string() + " --alpha 2 --out " +
             (dir / "h").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--alpha"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "h"));
  fs::remove_all(dir);
}

}  // namespace
