// `strandbench compare-runs`: the Mann-Whitney U test against known values, and the command on
// synthetic results.json files (unchanged, deliberately slowed, noise only, too few
// repetitions, no samples, added/removed/definition changed, sweep folders, bad input).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "reports/compare_runs.h"
#include "reports/stats.h"
#include "test_util.h"

using nlohmann::json;
using sbtest::runCli;
using sbtest::tempDir;

namespace {

// ---- statistics ----

TEST(MannWhitney, FullySeparatedFiveVsFiveIsOneIn252) {
  const sb::RankTest t = sb::mannWhitneyGreater({1, 2, 3, 4, 5}, {6, 7, 8, 9, 10});
  EXPECT_TRUE(t.exact);
  EXPECT_DOUBLE_EQ(t.u, 25.0);
  EXPECT_NEAR(t.p, 1.0 / 252.0, 1e-12);
  // The other direction: every ordering has U >= 0.
  const sb::RankTest back = sb::mannWhitneyGreater({6, 7, 8, 9, 10}, {1, 2, 3, 4, 5});
  EXPECT_DOUBLE_EQ(back.u, 0.0);
  EXPECT_NEAR(back.p, 1.0, 1e-12);
}

// The tables' critical value for m = n = 5, one-sided 0.05: P(U <= 4) = 12/252 = 0.0476, so by
// symmetry P(U >= 21) = 12/252 and P(U >= 20) = 19/252 (> 0.05).
TEST(MannWhitney, ExactTailMatchesTheTable) {
  EXPECT_NEAR(sb::mannWhitneyExactUpperTail(5, 5, 21), 12.0 / 252.0, 1e-12);
  EXPECT_NEAR(sb::mannWhitneyExactUpperTail(5, 5, 20), 19.0 / 252.0, 1e-12);
  EXPECT_NEAR(sb::mannWhitneyExactUpperTail(5, 5, 0), 1.0, 1e-12);
}

// U = m*n/2 (interleaved samples): for m = n = 4 the counts of U = 0..16 are the coefficients of
// the Gaussian binomial [8 choose 4]: 1 1 2 3 5 5 7 7 8 7 7 5 5 3 2 1 1 (70 in all), so
// P(U >= 8) = 39/70, a little over one half.
TEST(MannWhitney, InterleavedSamplesGiveAboutOneHalf) {
  const sb::RankTest t = sb::mannWhitneyGreater({1, 4, 5, 8}, {2, 3, 6, 7});
  EXPECT_TRUE(t.exact);
  EXPECT_DOUBLE_EQ(t.u, 8.0);
  EXPECT_NEAR(t.p, 39.0 / 70.0, 1e-12);
  EXPECT_GT(t.p, 0.5);
}

// The recurrence against brute force: every choice of which m of the m+n ranks are x.
TEST(MannWhitney, ExactDistributionMatchesEnumeration) {
  for (auto [m, n] : {std::pair{1, 1}, {1, 4}, {2, 3}, {3, 3}, {4, 4}, {3, 6}, {6, 2}, {5, 5}}) {
    const int total = m + n;
    std::vector<int> atLeast(m * n + 2, 0);
    int orderings = 0;
    for (int mask = 0; mask < (1 << total); ++mask) {
      if (__builtin_popcount(mask) != m) continue;
      ++orderings;
      int u = 0, xsBelow = 0;  // ranks ascending; bit set = an x
      for (int r = 0; r < total; ++r) {
        if (mask & (1 << r))
          ++xsBelow;
        else
          u += xsBelow;
      }
      for (int k = 0; k <= u; ++k) ++atLeast[k];
    }
    for (int k = 0; k <= m * n + 1; ++k)
      EXPECT_NEAR(sb::mannWhitneyExactUpperTail(m, n, k),
                  static_cast<double>(atLeast[k]) / orderings, 1e-12)
          << m << " vs " << n << ", U >= " << k;
    EXPECT_NEAR(sb::mannWhitneyMinP(m, n), 1.0 / orderings, 1e-12);
  }
}

// With ties: the normal approximation with tie and continuity correction. x = 1 2 2 3 3,
// y = 3 3 4 4 5: U = 15 + 2 * (3 + 2 * 0.5) = 23; tie groups 2, 4, 2 give sum(t^3 - t) = 72;
// var = 25/12 * (11 - 72/90) = 21.25; z = (23 - 12.5 - 0.5) / sqrt(21.25) = 2.1693;
// p = 1 - Phi(z) = 0.015030 (scipy.stats.mannwhitneyu(y, x, alternative="greater")).
TEST(MannWhitney, NormalApproximationWithTies) {
  const sb::RankTest t = sb::mannWhitneyGreater({1, 2, 2, 3, 3}, {3, 3, 4, 4, 5});
  EXPECT_FALSE(t.exact);
  EXPECT_DOUBLE_EQ(t.u, 23.0);
  EXPECT_NEAR(t.p, 0.0150298, 1e-6);
  // Every value equal: no evidence either way.
  EXPECT_DOUBLE_EQ(sb::mannWhitneyGreater({2, 2, 2}, {2, 2, 2}).p, 1.0);
  EXPECT_DOUBLE_EQ(sb::mannWhitneyGreater({}, {1, 2}).p, 1.0);
}

// Large samples without ties use the normal approximation, which is then close to exact.
TEST(MannWhitney, LargeSamplesAgreeWithTheExactTail) {
  std::vector<double> x, y;
  for (int i = 0; i < 60; ++i) {
    x.push_back(i * 2.0);
    y.push_back(i * 2.0 + 9.0);  // shifted by 4.5 ranks
  }
  const sb::RankTest t = sb::mannWhitneyGreater(x, y);
  EXPECT_FALSE(t.exact);
  EXPECT_NEAR(t.p, sb::mannWhitneyExactUpperTail(60, 60, t.u), 2e-3);
  // At the exact limit (50 x 50) the exact distribution is still used.
  x.resize(50);
  y.resize(50);
  const sb::RankTest e = sb::mannWhitneyGreater(x, y);
  EXPECT_TRUE(e.exact);
  EXPECT_GT(e.p, 0.0);
  EXPECT_LT(e.p, 1.0);
}

TEST(MannWhitney, SmallestPossiblePValue) {
  EXPECT_NEAR(sb::mannWhitneyMinP(2, 2), 1.0 / 6.0, 1e-12);
  EXPECT_NEAR(sb::mannWhitneyMinP(3, 3), 0.05, 1e-12);  // cannot be < 0.05
  EXPECT_NEAR(sb::mannWhitneyMinP(4, 4), 1.0 / 70.0, 1e-12);
  EXPECT_NEAR(sb::mannWhitneyMinP(5, 5), 1.0 / 252.0, 1e-12);
}

// ---- synthetic runs ----

// One case: frame samples; two passes split each frame 40/60.
json makeResult(const std::string& id, int index, const std::vector<double>& frame,
                const std::string& shadow = "none") {
  auto timing = [](const std::vector<double>& v) {
    const sb::Stats s = sb::summarize(v);
    return json{{"median", s.median}, {"min", s.min},       {"max", s.max},
                {"mean", s.mean},     {"stddev", s.stddev}, {"samples", v}};
  };
  std::vector<double> shadowMs, colorMs;
  for (double f : frame) {
    shadowMs.push_back(0.4 * f);
    colorMs.push_back(0.6 * f);
  }
  const std::string backend = id.substr(id.rfind('=') + 1);
  return {
      {"backend", backend},
      {"scene", {{"spec", "straight:strands=500,points=16"}, {"strands", 500}}},
      {"shadow", shadow},
      {"oit", "none"},
      {"primitive", "lines"},
      {"size", {128, 128}},
      {"repeat", frame.size()},
      {"warmup", 1},
      {"passes",
       {{{"name", "shadow.depth"}, {"executions", 1}, {"ms", timing(shadowMs)}},
        {{"name", "color"}, {"executions", 1}, {"ms", timing(colorMs)}}}},
      {"frame_ms", timing(frame)},
      {"case", {{"id", id}, {"group", "g"}, {"index", index}, {"params", {{"backend", backend}}}}}};
}

// n samples around base ms with a relative spread of +-noise (fixed seed).
std::vector<double> samplesAround(double base, int n, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(base * (1.0 + noise * u(rng)));
  return v;
}

const std::vector<std::string> kIds = {"shadows/shadow=none,backend=gl",
                                       "shadows/shadow=none,backend=vulkan",
                                       "shadows/shadow=osm,backend=gl"};

// Three cases of `reps` repetitions each, optionally transformed per case.
json makeRun(int reps = 10,
             const std::function<std::vector<double>(int, std::vector<double>)>& change = {}) {
  json results = json::array();
  for (int i = 0; i < static_cast<int>(kIds.size()); ++i) {
    std::vector<double> s = samplesAround(10.0 * (i + 1), reps, 0.03, 100 + i);
    if (change) s = change(i, s);
    results.push_back(makeResult(kIds[i], i, s));
  }
  return {{"schema_version", 1},
          {"suite", {{"name", "synthetic"}}},
          {"context", {{"commit", "0123456789abcdef"}, {"date", "2026-11-22T22:10:00Z"}}},
          {"groups", json::array()},
          {"results", results}};
}

std::string write(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
  return file.string();
}
std::string write(const std::filesystem::path& file, const json& j) {
  return write(file, j.dump(1));
}

// The output line of one case (the table row starting with its id).
std::string lineOf(const std::string& out, const std::string& id) {
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(id + " ", 0) == 0) return line;
  return "";
}

std::string compareRuns(const std::string& a, const std::string& b) {
  return "compare-runs '" + a + "' '" + b + "'";
}

TEST(CompareRunsCli, UnchangedRunPasses) {
  const auto dir = tempDir("cmpruns");
  const std::string file = write(dir / "results.json", makeRun());
  const auto r = runCli(compareRuns(file, file));
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  for (const auto& id : kIds) {
    const std::string line = lineOf(r.out, id);
    EXPECT_NE(line.find("+0.0%"), std::string::npos) << line;
    EXPECT_NE(line.find(" ok"), std::string::npos) << line;
  }
  EXPECT_NE(r.out.find("3 cases: 0 slower, 0 faster, 3 ok"), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}

TEST(CompareRunsCli, FlagsADeliberatelySlowedCase) {
  const auto dir = tempDir("cmpruns");
  const std::string before = write(dir / "old.json", makeRun());
  const std::string after = write(dir / "new.json", makeRun(10, [](int i, std::vector<double> s) {
                                    if (i == 1)
                                      for (double& x : s) x *= 1.5;
                                    return s;
                                  }));
  const auto r = runCli(compareRuns(before, after));
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  const std::string slowed = lineOf(r.out, kIds[1]);
  EXPECT_NE(slowed.find("SLOWER"), std::string::npos) << r.out;
  EXPECT_NE(slowed.find("+5"), std::string::npos) << slowed;  // about +50%
  EXPECT_NE(lineOf(r.out, kIds[0]).find(" ok"), std::string::npos) << r.out;
  EXPECT_NE(lineOf(r.out, kIds[2]).find(" ok"), std::string::npos) << r.out;
  // Its passes are listed under it, in lower case (they never fail the comparison).
  const std::string pass = lineOf(r.out, "  pass shadow.depth");
  EXPECT_NE(pass.find("+50.0%"), std::string::npos) << r.out;
  EXPECT_NE(pass.find("slower"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 slower"), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}

TEST(CompareRunsCli, NoiseOnlyChangePasses) {
  const auto dir = tempDir("cmpruns");
  const std::string before = write(dir / "old.json", makeRun());
  const std::string after = write(dir / "new.json", makeRun(10, [](int i, std::vector<double> s) {
                                    std::mt19937 rng(7 + i);
                                    std::shuffle(s.begin(), s.end(), rng);
                                    std::uniform_real_distribution<double> jitter(-0.01, 0.01);
                                    for (double& x : s) x *= 1.0 + jitter(rng);
                                    return s;
                                  }));
  const auto r = runCli(compareRuns(before, after));
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(r.out.find("SLOWER"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0 slower"), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}

TEST(CompareRunsCli, TwoRepetitionsAreNotJudged) {
  const auto dir = tempDir("cmpruns");
  const std::string before = write(dir / "old.json", makeRun(2));
  const std::string after = write(dir / "new.json", makeRun(2, [](int, std::vector<double> s) {
                                    for (double& x : s) x *= 3.0;
                                    return s;
                                  }));
  const auto r = runCli(compareRuns(before, after));
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  for (const auto& id : kIds) {
    const std::string line = lineOf(r.out, id);
    EXPECT_NE(line.find("+200.0%"), std::string::npos) << line;
    EXPECT_NE(line.find("not judged (too few repetitions: 2 vs 2"), std::string::npos) << line;
  }
  EXPECT_NE(r.out.find("3 not judged"), std::string::npos) << r.out;
  // 4 vs 4 is enough at alpha 0.05 (best possible p = 1/70).
  write(dir / "old4.json", makeRun(4));
  write(dir / "new4.json", makeRun(4, [](int, std::vector<double> s) {
          for (double& x : s) x *= 3.0;
          return s;
        }));
  const auto four = runCli(compareRuns((dir / "old4.json").string(), (dir / "new4.json").string()));
  EXPECT_EQ(four.status, 1) << four.out;
  EXPECT_NE(four.out.find("3 slower"), std::string::npos) << four.out;
  std::filesystem::remove_all(dir);
}

TEST(CompareRunsCli, MissingSamplesAreNotJudged) {
  const auto dir = tempDir("cmpruns");
  json slowed = makeRun(10, [](int, std::vector<double> s) {
    for (double& x : s) x *= 2.0;
    return s;
  });
  for (auto& res : slowed["results"]) {
    res["frame_ms"].erase("samples");
    for (auto& p : res["passes"]) p["ms"].erase("samples");
  }
  const std::string before = write(dir / "old.json", makeRun());
  const std::string after = write(dir / "new.json", slowed);
  const auto r = runCli(compareRuns(before, after));
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  const std::string line = lineOf(r.out, kIds[0]);
  EXPECT_NE(line.find("not judged (no samples)"), std::string::npos) << r.out;
  EXPECT_NE(line.find("+100.0%"), std::string::npos) << line;
  std::filesystem::remove_all(dir);
}

TEST(CompareRunsCli, FasterIsInformationOnly) {
  const auto dir = tempDir("cmpruns");
  const std::string before = write(dir / "old.json", makeRun());
  const std::string after = write(dir / "new.json", makeRun(10, [](int i, std::vector<double> s) {
                                    if (i == 2)
                                      for (double& x : s) x *= 0.6;
                                    return s;
                                  }));
  const auto r = runCli(compareRuns(before, after));
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(lineOf(r.out, kIds[2]).find("faster"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0 slower, 1 faster"), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}

// A 4% slowdown (samples spread +-0.5%) is within the default 5% but not within --threshold 2.
TEST(CompareRunsCli, ThresholdOption) {
  const auto dir = tempDir("cmpruns");
  auto tight = [](int i, std::vector<double> s) {
    return samplesAround(10.0 * (i + 1), static_cast<int>(s.size()), 0.005, 200 + i);
  };
  const std::string before = write(dir / "old.json", makeRun(10, tight));
  const std::string after = write(dir / "new.json", makeRun(10, [&](int i, std::vector<double> s) {
                                    s = tight(i, s);
                                    if (i == 0)
                                      for (double& x : s) x *= 1.04;
                                    return s;
                                  }));
  const auto loose = runCli(compareRuns(before, after));
  EXPECT_EQ(loose.status, 0) << loose.out << loose.err;
  const auto strict = runCli(compareRuns(before, after) + " --threshold 2%");
  EXPECT_EQ(strict.status, 1) << strict.out << strict.err;
  EXPECT_NE(lineOf(strict.out, kIds[0]).find("SLOWER"), std::string::npos) << strict.out;
  EXPECT_NE(strict.out.find("threshold 2%"), std::string::npos) << strict.out;
  for (const char* bad : {"--threshold abc", "--threshold -1", "--alpha 0", "--alpha 1.5"}) {
    const auto r = runCli(compareRuns(before, after) + " " + bad);
    EXPECT_EQ(r.status, 2) << bad << "\n" << r.out;
    EXPECT_NE(r.err.find("strandbench compare-runs:"), std::string::npos) << bad << r.err;
  }
  std::filesystem::remove_all(dir);
}

// Runs of different suites, or with few cases in common, say so (exit status unchanged); runs
// with no case in common are refused (exit 2). Control: two runs of one suite get no warning.
TEST(CompareRunsCli, UnrelatedRunsWarnOrAreRefused) {
  const auto dir = tempDir("cmpruns");
  const std::string base = write(dir / "old.json", makeRun());
  const auto same = runCli(compareRuns(base, base));
  EXPECT_EQ(same.status, 0) << same.out << same.err;
  EXPECT_EQ(same.out.find("warning:"), std::string::npos) << same.out;

  // Another suite with one of the three cases and two of its own: 1 of 3 shared.
  json other = makeRun();
  other["suite"]["name"] = "elsewhere";
  other["results"][1]["case"]["id"] = "g/shadow=none,backend=gl";
  other["results"][2]["case"]["id"] = "g/shadow=osm,backend=gl";
  const std::string few = write(dir / "few.json", other);
  const auto r = runCli(compareRuns(base, few));
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("warning: the runs are of different suites (old synthetic, new elsewhere)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("warning: the runs share only 1 of 3 cases"), std::string::npos) << r.out;
  const auto j = runCli(compareRuns(base, few) + " --json");
  EXPECT_EQ(j.status, 0) << j.err;
  const json doc = json::parse(j.out);
  EXPECT_EQ(doc["shared_cases"], 1);
  EXPECT_EQ(doc["warnings"].size(), 2u);

  // No case in common: nothing to compare.
  other["results"][0]["case"]["id"] = "g/shadow=dom,backend=gl";
  const std::string none = write(dir / "none.json", other);
  const auto refused = runCli(compareRuns(base, none));
  EXPECT_EQ(refused.status, 2) << refused.out;
  EXPECT_NE(refused.err.find("the runs share no case"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("suite elsewhere, 3 cases"), std::string::npos) << refused.err;
  std::filesystem::remove_all(dir);
}

TEST(CompareRunsCli, AddedRemovedAndDefinitionChanged) {
  const auto dir = tempDir("cmpruns");
  json changed = makeRun();
  auto& results = changed["results"];
  results.erase(results.begin());        // kIds[0] removed
  results[0]["shadow"] = "osm:maps=16";  // kIds[1]: another technique
  results.push_back(makeResult("shadows/shadow=dom,backend=gl", 3, samplesAround(5, 10, 0.03, 9)));
  const std::string before = write(dir / "old.json", makeRun());
  const std::string after = write(dir / "new.json", changed);
  const auto r = runCli(compareRuns(before, after));
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(lineOf(r.out, kIds[0]).find("removed"), std::string::npos) << r.out;
  const std::string def = lineOf(r.out, kIds[1]);
  EXPECT_NE(def.find("definition changed"), std::string::npos) << r.out;
  EXPECT_NE(def.find("osm:maps=16"), std::string::npos) << def;
  EXPECT_NE(lineOf(r.out, "shadows/shadow=dom,backend=gl").find("added"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("1 definition changed, 1 added, 1 removed"), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}

// A sweep folder: its results.json, or (before `report`) its cases/*.json.
TEST(CompareRunsCli, ReadsSweepFolders) {
  const auto dir = tempDir("cmpruns");
  const json before = makeRun();
  write(dir / "old" / "results.json", before);
  const json after = makeRun(10, [](int i, std::vector<double> s) {
    if (i == 0)
      for (double& x : s) x *= 1.5;
    return s;
  });
  // Case files named in an order other than the suite's.
  const std::vector<std::string> names = {"z.json", "m.json", "a.json"};
  for (std::size_t i = 0; i < names.size(); ++i)
    write(dir / "new" / "cases" / names[i], after["results"][i]);
  write(dir / "new" / "context.json", after["context"]);
  const auto r = runCli(compareRuns((dir / "old").string(), (dir / "new").string()));
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(lineOf(r.out, kIds[0]).find("SLOWER"), std::string::npos) << r.out;
  // Rows keep the suite's order (case.index).
  EXPECT_LT(r.out.find(kIds[0]), r.out.find(kIds[2]));
  EXPECT_NE(r.out.find("commit 0123456789"), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}

TEST(CompareRunsCli, JsonOutput) {
  const auto dir = tempDir("cmpruns");
  const std::string before = write(dir / "old.json", makeRun());
  const std::string after = write(dir / "new.json", makeRun(10, [](int i, std::vector<double> s) {
                                    if (i == 1)
                                      for (double& x : s) x *= 1.5;
                                    return s;
                                  }));
  const auto r = runCli(compareRuns(before, after) + " --json");
  EXPECT_EQ(r.status, 1) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["status"], 1);
  EXPECT_EQ(j["summary"]["SLOWER"], 1);
  ASSERT_EQ(j["cases"].size(), 3u);
  EXPECT_EQ(j["cases"][1]["id"], kIds[1]);
  EXPECT_EQ(j["cases"][1]["verdict"], "SLOWER");
  EXPECT_NEAR(j["cases"][1]["change_pct"].get<double>(), 50.0, 1e-6);
  EXPECT_NEAR(j["cases"][1]["p"].get<double>(), sb::mannWhitneyMinP(10, 10), 1e-12);
  EXPECT_TRUE(j["cases"][1]["exact"].get<bool>());
  EXPECT_EQ(j["cases"][1]["passes"].size(), 2u);
  EXPECT_EQ(j["cases"][0]["verdict"], "ok");
  std::filesystem::remove_all(dir);
}

TEST(CompareRunsCli, BadInputExitsTwo) {
  const auto dir = tempDir("cmpruns");
  const std::string good = write(dir / "good.json", makeRun());
  json badSamples = makeRun();
  badSamples["results"][1]["frame_ms"]["samples"] = "fast";
  json twice = makeRun();
  twice["results"].push_back(twice["results"][0]);
  json noId = makeRun();
  noId["results"][0]["case"].erase("id");
  std::filesystem::create_directories(dir / "empty");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {write(dir / "notjson.json", std::string("{\"results\": [")), "not valid JSON"},
      {write(dir / "noresults.json", json{{"schema_version", 1}}), "no \"results\" array"},
      {write(dir / "version.json", json{{"schema_version", 7}, {"results", json::array()}}),
       "schema_version"},
      {write(dir / "samples.json", badSamples), "frame_ms.samples must be an array of numbers"},
      {write(dir / "twice.json", twice), "appears more than once"},
      {write(dir / "noid.json", noId), "lacks case.id"},
      {(dir / "missing.json").string(), "no such file or folder"},
      {(dir / "empty").string(), "neither results.json nor cases"},
  };
  // Bad input as OLD and as NEW, alternately.
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& [path, message] = cases[i];
    const auto r = runCli(i % 2 ? compareRuns(good, path) : compareRuns(path, good));
    EXPECT_EQ(r.status, 2) << path << "\n" << r.out;
    EXPECT_NE(r.err.find("strandbench compare-runs: " + path), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  std::filesystem::remove_all(dir);
}

// The library call: loading and judging without the CLI.
TEST(CompareRuns, JudgesTimingsDirectly) {
  const sb::CompareRunsOptions opt;
  auto ms = [](std::vector<double> v) { return json{{"median", sb::median(v)}, {"samples", v}}; };
  const json base = ms({10, 10.1, 9.9, 10.2, 9.8});
  EXPECT_EQ(sb::compareTiming(base, ms({15, 15.1, 14.9, 15.2, 14.8}), opt).verdict,
            sb::Verdict::Slower);
  EXPECT_EQ(sb::compareTiming(base, ms({5, 5.1, 4.9, 5.2, 4.8}), opt).verdict, sb::Verdict::Faster);
  // Beyond the threshold in the median but not significant: overlapping samples.
  const sb::TimingChange overlap = sb::compareTiming(base, ms({9, 10.7, 10.8, 20, 8}), opt);
  EXPECT_EQ(overlap.verdict, sb::Verdict::Ok);
  EXPECT_EQ(overlap.note, "not significant");
  // Significant but within the threshold.
  EXPECT_EQ(sb::compareTiming(base, ms({10.3, 10.4, 10.35, 10.45, 10.5}), opt).verdict,
            sb::Verdict::Ok);
  // 3 vs 3 fully separated gives p = 1/20 at best: too few at alpha 0.05, enough at 0.1.
  const json three = ms({10, 10.1, 9.9}), slowThree = ms({15, 15.1, 14.9});
  const sb::TimingChange few = sb::compareTiming(three, slowThree, opt);
  EXPECT_EQ(few.verdict, sb::Verdict::NotJudged);
  EXPECT_EQ(few.note, "too few repetitions: 3 vs 3, best possible p 0.05");
  sb::CompareRunsOptions loose;
  loose.alpha = 0.1;
  const sb::TimingChange judged = sb::compareTiming(three, slowThree, loose);
  EXPECT_EQ(judged.verdict, sb::Verdict::Slower);
  EXPECT_NEAR(*judged.p, 0.05, 1e-12);
  const sb::TimingChange none =
      sb::compareTiming(json{{"median", 10.0}}, json{{"median", 20.0}}, opt);
  EXPECT_EQ(none.verdict, sb::Verdict::NotJudged);
  EXPECT_EQ(none.note, "no samples");
  EXPECT_NEAR(*none.changePct, 100.0, 1e-12);
}

// ---- paired rounds ----

TEST(SignedRank, AllPositiveIsTwoToTheMinusN) {
  const sb::RankTest r = sb::signedRankGreater({0.1, 0.3, 0.2, 0.5, 0.4});
  EXPECT_TRUE(r.exact);
  EXPECT_NEAR(r.u, 15.0, 1e-12);
  EXPECT_NEAR(r.p, 1.0 / 32.0, 1e-12);
  EXPECT_NEAR(sb::signedRankGreater({-0.1, -0.3, -0.2}).p, 1.0, 1e-12);
  EXPECT_NEAR(sb::signedRankMinP(5), 1.0 / 32.0, 1e-12);
  EXPECT_NEAR(sb::signedRankMinP(4), 1.0 / 16.0, 1e-12);  // cannot be < 0.05
  // Symmetric differences: W = 3 of 0..6, P(W >= 3) = 5/8 over the 8 sign patterns.
  EXPECT_NEAR(sb::signedRankGreater({1.0, -1.0, 2.0, -2.0}).p, 10.0 / 16.0, 1e-12);
  EXPECT_NEAR(sb::signedRankGreater({0.0, 0.0}).p, 1.0, 1e-12);  // no non-zero difference
}

TEST(SignedRank, NormalApproximationAgreesWithTheExactTail) {
  // 20 pairs are counted exactly, 21 by the normal approximation: both near for mixed signs.
  std::vector<double> d;
  for (int i = 1; i <= 21; ++i) d.push_back((i % 3 == 0 ? -1.0 : 1.0) * i);
  const sb::RankTest approx = sb::signedRankGreater(d);
  EXPECT_FALSE(approx.exact);
  d.pop_back();
  const sb::RankTest exact = sb::signedRankGreater(d);
  EXPECT_TRUE(exact.exact);
  EXPECT_GT(approx.p, 0.0);
  EXPECT_LT(approx.p, 0.2);
  EXPECT_LT(exact.p, 0.2);
}

// Rounds on a machine whose speed drifts by up to 2x between rounds: each round's runs are
// taken together, so both builds see the same factor.
struct PairedRounds {
  std::vector<std::string> olds, news;
};
PairedRounds writeRounds(const std::filesystem::path& dir, int rounds, double slowCase1) {
  const double drift[] = {1.0, 1.6, 0.8, 1.3, 0.7, 2.0, 1.1, 0.9};
  PairedRounds p;
  for (int r = 0; r < rounds; ++r) {
    auto at = [&](double extra, unsigned seed) {
      return [=](int i, std::vector<double> s) {
        std::mt19937 rng(seed + 31 * i);
        std::uniform_real_distribution<double> jitter(-0.02, 0.02);
        for (double& x : s) x *= drift[r] * (i == 1 ? extra : 1.0) * (1.0 + jitter(rng));
        return s;
      };
    };
    p.olds.push_back(write(dir / ("old" + std::to_string(r) + ".json"), makeRun(5, at(1.0, r))));
    p.news.push_back(
        write(dir / ("new" + std::to_string(r) + ".json"), makeRun(5, at(slowCase1, 100 + r))));
  }
  return p;
}
std::string pairedCommand(const PairedRounds& p) {
  std::string cmd = compareRuns(p.olds[0], p.news[0]);
  for (std::size_t i = 1; i < p.olds.size(); ++i)
    cmd += " --pair '" + p.olds[i] + "' '" + p.news[i] + "'";
  return cmd;
}

TEST(CompareRunsCli, PairedRoundsFlagASlowerCaseThroughDrift) {
  const auto dir = tempDir("cmpruns");
  const PairedRounds p = writeRounds(dir, 6, 1.10);  // case 1: 10% slower in every round
  const auto r = runCli(pairedCommand(p));
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("paired: 6 pairs"), std::string::npos) << r.out;
  EXPECT_NE(lineOf(r.out, kIds[1]).find("SLOWER"), std::string::npos) << r.out;
  EXPECT_NE(lineOf(r.out, kIds[0]).find(" ok"), std::string::npos) << r.out;
  EXPECT_NE(lineOf(r.out, kIds[2]).find(" ok"), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}

TEST(CompareRunsCli, PairedRoundsPassDriftThatTwoSweepsCallSlower) {
  const auto dir = tempDir("cmpruns");
  const PairedRounds p = writeRounds(dir, 6, 1.0);  // no change, only the machine's drift
  const auto paired = runCli(pairedCommand(p));
  EXPECT_EQ(paired.status, 0) << paired.out << paired.err;
  EXPECT_NE(paired.out.find("0 slower"), std::string::npos) << paired.out;
  // The same runs compared unpaired, round 0's old against round 1's new (1.6x slower
  // machine): every case is called slower.
  const auto unpaired = runCli(compareRuns(p.olds[0], p.news[1]));
  EXPECT_EQ(unpaired.status, 1) << unpaired.out;
  EXPECT_NE(unpaired.out.find("3 slower"), std::string::npos) << unpaired.out;
  // Four pairs cannot reach p < 0.05 (2^-4): not judged.
  const PairedRounds four = writeRounds(dir / "four", 4, 1.10);
  const auto few = runCli(pairedCommand(four));
  EXPECT_EQ(few.status, 0) << few.out;
  EXPECT_NE(lineOf(few.out, kIds[1]).find("too few pairs: 4"), std::string::npos) << few.out;
  // A --pair needs both of its runs.
  const auto bad = runCli(compareRuns(p.olds[0], p.news[0]) + " --pair '" + p.olds[1] + "'");
  EXPECT_EQ(bad.status, 2) << bad.out << bad.err;
  std::filesystem::remove_all(dir);
}

}  // namespace

namespace {

// ---- Holm's correction over the cases ----

sb::CaseComparison judgedCase(const std::string& id, double changePct, double p,
                              const sb::CompareRunsOptions& opt) {
  sb::CaseComparison c;
  c.id = id;
  c.frame.name = id;
  c.frame.changePct = changePct;
  c.frame.p = p;
  const bool beyond = std::abs(changePct) > opt.thresholdPct;
  c.frame.verdict = beyond && p < opt.alpha
                        ? (changePct >= 0 ? sb::Verdict::Slower : sb::Verdict::Faster)
                        : sb::Verdict::Ok;
  c.verdict = c.frame.verdict;
  return c;
}

// The textbook example: p = 0.01, 0.04, 0.03 over three cases adjust to 0.03, 0.06, 0.06 (the
// second smallest is 2 x 0.03 = 0.06, and the largest may not fall below it).
TEST(CompareRunsHolm, AdjustedValuesAreTheStepDownOnes) {
  sb::CompareRunsOptions opt;
  std::vector<sb::CaseComparison> cases{judgedCase("a", 10, 0.01, opt),
                                        judgedCase("b", 10, 0.04, opt),
                                        judgedCase("c", 10, 0.03, opt)};
  sb::applyCorrection(cases, opt);
  EXPECT_NEAR(*cases[0].frame.pAdjusted, 0.03, 1e-12);
  EXPECT_NEAR(*cases[1].frame.pAdjusted, 0.06, 1e-12);
  EXPECT_NEAR(*cases[2].frame.pAdjusted, 0.06, 1e-12);
  EXPECT_EQ(cases[0].verdict, sb::Verdict::Slower);
  EXPECT_EQ(cases[1].verdict, sb::Verdict::Ok);
  EXPECT_EQ(cases[2].verdict, sb::Verdict::Ok);
  EXPECT_NE(cases[1].frame.note.find("not significant over 3 cases"), std::string::npos);
}

// 38 cases, two of them beyond the threshold with p 0.02 and 0.03, as chance gives in a suite:
// judged alone they are SLOWER, corrected they are not; a real regression (p 1e-5, as 16 rounds
// all slower give) stays SLOWER among them.
TEST(CompareRunsHolm, ChanceVerdictsAmongManyCasesAreNotRegressions) {
  sb::CompareRunsOptions opt;
  std::vector<sb::CaseComparison> cases;
  for (int i = 0; i < 36; ++i)
    cases.push_back(judgedCase("noise" + std::to_string(i), 2.0, 0.1 + 0.025 * i, opt));
  cases.push_back(judgedCase("chance1", 12.0, 0.02, opt));
  cases.push_back(judgedCase("chance2", 9.0, 0.03, opt));
  std::vector<sb::CaseComparison> alone = cases;
  opt.correction = sb::Correction::None;
  sb::applyCorrection(alone, opt);
  EXPECT_EQ(alone[36].verdict, sb::Verdict::Slower);
  EXPECT_EQ(alone[37].verdict, sb::Verdict::Slower);
  opt.correction = sb::Correction::Holm;
  std::vector<sb::CaseComparison> corrected = cases;
  sb::applyCorrection(corrected, opt);
  for (const auto& c : corrected) EXPECT_NE(c.verdict, sb::Verdict::Slower) << c.id;
  cases.push_back(judgedCase("real", 10.0, 1.0 / 65536.0, opt));
  sb::applyCorrection(cases, opt);
  EXPECT_EQ(cases.back().verdict, sb::Verdict::Slower);
  EXPECT_EQ(cases[36].verdict, sb::Verdict::Ok);
}

}  // namespace

namespace {

// ---- work: exact counters, judged apart from time ----

// The run of makeRun with work counters in every pass (as render --json writes them: counters,
// resources, and frame_work their sum), the same for every case and repetition.
json withWork(json run) {
  for (auto& r : run["results"]) {
    json frame = json::object();
    for (std::size_t i = 0; i < r["passes"].size(); ++i) {
      const double k = static_cast<double>(i + 1);
      json work = {{"vertices", 8000 * k},
                   {"primitives", 4000 * k},
                   {"vertex_invocations", 8000 * k},
                   {"clip_invocations", 4000 * k},
                   {"clip_primitives", 4000 * k},
                   {"fragment_invocations", 100000 * k},
                   {"compute_invocations", 0},
                   {"samples_passed", 5000 * k},
                   {"draws", 1},
                   {"dispatches", 0},
                   {"bytes_written", 65536 * k},
                   {"bytes_read", 256},
                   {"bytes_storage", 300000}};
      for (const auto& [key, v] : work.items())
        frame[key] = frame.value(key, 0.0) + v.get<double>();
      work["resources"] = json::array(
          {{{"access", "write"}, {"bytes", 65536 * k}, {"format", "Depth32F"}, {"name", "d"}}});
      r["passes"][i]["work"] = work;
    }
    r["frame_work"] = frame;
  }
  return run;
}

TEST(CompareRunsWork, IdenticalRunsChangeNeitherWorkNorTime) {
  const auto dir = tempDir("cmpwork");
  const std::string before = write(dir / "old.json", withWork(makeRun()));
  const std::string after = write(dir / "new.json", withWork(makeRun()));
  const auto r = runCli(compareRuns(before, after));
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  // The two summary lines open the output.
  EXPECT_EQ(r.out.rfind("work changed: none (3 cases compared)\ntime changed: none (", 0), 0u)
      << r.out;
  EXPECT_EQ(r.out.find("work changes"), std::string::npos) << r.out;
  const auto j = runCli(compareRuns(before, after) + " --json --fail-on-work-change");
  EXPECT_EQ(j.status, 0) << j.out << j.err;
  const json doc = json::parse(j.out);
  EXPECT_EQ(doc["work"]["changed_cases"], 0);
  EXPECT_EQ(doc["work"]["same_cases"], 3);
  EXPECT_TRUE(doc["work"]["cases"].empty());
  for (const auto& c : doc["cases"]) EXPECT_EQ(c["work"], "same") << c["id"];
  std::filesystem::remove_all(dir);
}

// A case with one more pass (a copy of one, renamed, with its work): a work change naming the
// pass with its counters; exit 0 unless --fail-on-work-change. The other way round, removed.
TEST(CompareRunsWork, ExtraPassIsAWorkChange) {
  const auto dir = tempDir("cmpwork");
  json extra = withWork(makeRun());
  json pass = extra["results"][1]["passes"][1];
  pass["name"] = "extra.pass";
  extra["results"][1]["passes"].push_back(pass);
  const std::string before = write(dir / "old.json", withWork(makeRun()));
  const std::string after = write(dir / "new.json", extra);
  const auto r = runCli(compareRuns(before, after));
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(r.out.rfind("work changed: 1 case (13 counters; 1 pass added) of 3 compared", 0), 0u)
      << r.out;
  const std::size_t at = r.out.find("    pass extra.pass added: ");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_LT(r.out.find("  " + kIds[1] + "\n"), at) << r.out;  // under its case
  const std::string line = r.out.substr(at, r.out.find('\n', at) - at);
  EXPECT_NE(line.find("fragment_invocations 200000"), std::string::npos) << line;
  EXPECT_NE(line.find("draws 1"), std::string::npos) << line;
  EXPECT_EQ(line.find("resources"), std::string::npos) << line;  // not a counter
  // Work apart from time: the frame timings are the same, so no time change.
  EXPECT_NE(r.out.find("\ntime changed: none"), std::string::npos) << r.out;
  EXPECT_EQ(runCli(compareRuns(before, after) + " --fail-on-work-change").status, 1);

  const auto j = runCli(compareRuns(before, after) + " --json");
  EXPECT_EQ(j.status, 0) << j.err;
  const json doc = json::parse(j.out);
  EXPECT_EQ(doc["work"]["changed_cases"], 1);
  EXPECT_EQ(doc["work"]["changed_counters"], 13);
  ASSERT_EQ(doc["work"]["cases"].size(), 1u);
  EXPECT_EQ(doc["work"]["cases"][0]["id"], kIds[1]);
  const json& p = doc["work"]["cases"][0]["passes"][0];
  EXPECT_EQ(p["pass"], "extra.pass");
  EXPECT_EQ(p["change"], "added");
  EXPECT_EQ(doc["cases"][1]["work"], "changed");
  EXPECT_EQ(doc["cases"][0]["work"], "same");

  const auto back = runCli(compareRuns(after, before));
  EXPECT_EQ(back.status, 0) << back.out;
  EXPECT_NE(back.out.find("    pass extra.pass removed: "), std::string::npos) << back.out;
  std::filesystem::remove_all(dir);
}

// One counter of one pass doubled: reported with the pass, the counter, old and new value and
// the ratio. A counter null in one run (samples_passed without device queries) is not compared.
TEST(CompareRunsWork, ChangedCounterShowsOldAndNewValues) {
  const auto dir = tempDir("cmpwork");
  json changed = withWork(makeRun());
  changed["results"][2]["passes"][1]["work"]["fragment_invocations"] = 400000;
  changed["results"][0]["passes"][0]["work"]["samples_passed"] = nullptr;
  const std::string before = write(dir / "old.json", withWork(makeRun()));
  const std::string after = write(dir / "new.json", changed);
  const auto r = runCli(compareRuns(before, after));
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(r.out.rfind("work changed: 1 case (1 counter; 1 pass changed) of 3 compared", 0), 0u)
      << r.out;
  EXPECT_NE(
      r.out.find("  " + kIds[2] +
                 "\n    pass color: fragment_invocations 200000 -> 400000 (x2.00, +100.0%)\n"),
      std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("samples_passed"), std::string::npos) << r.out;
  const json doc = json::parse(runCli(compareRuns(before, after) + " --json").out);
  const json& c = doc["work"]["cases"][0]["passes"][0]["counters"][0];
  EXPECT_EQ(c["counter"], "fragment_invocations");
  EXPECT_EQ(c["old"], 200000);
  EXPECT_EQ(c["new"], 400000);
  EXPECT_DOUBLE_EQ(c["ratio"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(c["change_pct"].get<double>(), 100.0);
  std::filesystem::remove_all(dir);
}

// Runs from before the counters: "not counted", never a change, whichever run lacks them; a
// redefined case is not compared for work either.
TEST(CompareRunsWork, ResultsWithoutWorkAreNotCounted) {
  const auto dir = tempDir("cmpwork");
  const std::string plain = write(dir / "plain.json", makeRun());
  const std::string counted = write(dir / "counted.json", withWork(makeRun()));
  for (const auto& [a, b] : {std::pair{plain, plain}, {plain, counted}, {counted, plain}}) {
    const auto r = runCli(compareRuns(a, b));
    EXPECT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_EQ(r.out.rfind("work changed: none (0 cases compared; 3 cases not counted", 0), 0u)
        << r.out;
    const json doc = json::parse(runCli(compareRuns(a, b) + " --json --fail-on-work-change").out);
    EXPECT_EQ(doc["status"], 0);
    EXPECT_EQ(doc["work"]["not_counted_cases"], 3);
    EXPECT_EQ(doc["cases"][0]["work"], "not counted");
  }
  json redefined = withWork(makeRun());
  redefined["results"][0]["shadow"] = "osm";
  redefined["results"][0]["passes"][0]["work"]["draws"] = 7;
  const auto r = runCli(compareRuns(counted, write(dir / "redefined.json", redefined)) + " --json");
  const json doc = json::parse(r.out);
  EXPECT_EQ(doc["work"]["changed_cases"], 0) << r.out;
  EXPECT_EQ(doc["cases"][0]["work"], "not compared");
  // The library call directly.
  const json result = makeRun()["results"][0];
  EXPECT_EQ(sb::compareWork(result, withWork(makeRun())["results"][0]).status,
            sb::WorkStatus::NotCounted);
  EXPECT_EQ(sb::compareWork(result, result).status, sb::WorkStatus::NotCounted);
  std::filesystem::remove_all(dir);
}

}  // namespace
