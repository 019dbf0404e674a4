// One measurement per case across figure pages (harness/case_store.h): two figures that share
// a case, run one after the other with one case store, print the same measurement of it (time,
// interval, errors, images), taken once; without the store (the control) the case is measured
// twice and the two measurements differ. A damaged entry reads as a miss. A time verdict of a
// figure's claim comes only from a ratio of one interleaved run.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "harness/case_store.h"
#include "harness/suite.h"
#include "reports/figure_report.h"
#include "test_util.h"

namespace {

using namespace sbtest;
namespace fs = std::filesystem;
using json = nlohmann::json;

// A tiny figure: the shared case (occupancy shadows, in a group named `sharedGroup`, its
// shadow spec written as `sharedSpec`) and one of its own, with a paper table that compares
// the two in time.
std::string figureText(const std::string& name, const std::string& sharedGroup,
                       const std::string& sharedSpec, const std::string& ownShadow) {
  json f = {
      {"name", name},
      {"defaults",
       {{"scene", "straight:strands=40,points=8,alpha=0.5"},
        {"size", "40x40"},
        {"repeat", 3},
        {"warmup", 1},
        {"reference", true}}},
      {"groups",
       {{{"name", sharedGroup}, {"shadow", sharedSpec}}, {{"name", "own"}, {"shadow", ownShadow}}}},
      {"figure",
       {{"title", name},
        {"rows", {"r"}},
        {"columns", {"shared", "own"}},
        {"cells", {{{{"group", sharedGroup}}, {{"group", "own"}}}}}}},
      {"tables",
       {{{"title", name + " table"},
         {"metric", "frame_ms"},
         {"paper_unit", "ms"},
         {"rows",
          {{{"label", "own"}, {"group", "own"}, {"paper", 10}, {"baseline", true}},
           {{"label", "shared"}, {"group", sharedGroup}, {"paper", 20}}}}}}}};
  return f.dump(1);
}

json resultOf(const fs::path& dir, const std::string& group) {
  const json r = json::parse(readFile(dir / "results.json"));
  for (const json& x : r["results"])
    if (x["case"]["group"] == group) return x;
  ADD_FAILURE() << dir << ": no result of group " << group;
  return json::object();
}

// The cells table's row of a case in figure.md, cell by cell (Row, Column, Case, Segments,
// Frame, 95% interval, Image RMSE, FLIP, Banding, Vis. RMSE, Shadow MiB, Note).
std::vector<std::string> mdRow(const fs::path& dir, const std::string& caseId) {
  const std::string md = readFile(dir / "figure.md");
  const std::size_t at = md.find("| " + caseId + " |");
  if (at == std::string::npos) return {};
  const std::size_t start = md.rfind('\n', at) + 1;
  const std::string line = md.substr(start, md.find('\n', at) - start);
  std::vector<std::string> cols;
  for (std::size_t p = 1, q; (q = line.find('|', p)) != std::string::npos; p = q + 1) {
    std::string c = line.substr(p, q - p);
    c.erase(0, c.find_first_not_of(' '));
    c.erase(c.find_last_not_of(' ') + 1);
    cols.push_back(c);
  }
  return cols;
}

TEST(FigureCases, TwoFiguresPrintOneMeasurementOfTheirSharedCase) {
  const fs::path dir = tempDir("figure-cases");
  std::ofstream(dir / "fig-a.json") << figureText("fig-a", "occ", "occupancy", "none");
  // The same case spelled otherwise (its default option written out), in another group.
  std::ofstream(dir / "fig-b.json")
      << figureText("fig-b", "same", "occupancy:jitter=off", "shadowmap");
  const fs::path store = dir / "cases";
  auto figure = [&](const std::string& name, const std::string& out, const std::string& more,
                    const std::string& env = "") {
    const CliResult r = runCli("figure " + (dir / (name + ".json")).string() +
                                   " --backend gl --out " + (dir / out).string() + more,
                               env);
    EXPECT_EQ(r.status, 0) << name << "\n" << r.out << r.err;
    return r;
  };
  const CliResult a = figure("fig-a", "a", " --cases " + store.string());
  EXPECT_NE(a.out.find(": 0 taken (measured once, by an earlier sweep), 2 measured here and kept"),
            std::string::npos)
      << a.out;
  // The environment names the store as docs-refresh-stale.sh does.
  const CliResult b = figure("fig-b", "b", "", "SB_FIGURE_CASES=" + store.string());
  EXPECT_NE(b.out.find("same/backend=gl  "), std::string::npos) << b.out;
  EXPECT_NE(b.out.find("(measured once: taken from the case store, measured for fig-a)"),
            std::string::npos)
      << b.out;
  EXPECT_NE(b.out.find(": 1 taken (measured once, by an earlier sweep), 1 measured here"),
            std::string::npos)
      << b.out;

  // One measurement: the same samples, interval, errors and images on both.
  const json ra = resultOf(dir / "a", "occ"), rb = resultOf(dir / "b", "same");
  ASSERT_TRUE(ra.contains("frame_ms")) << ra.dump();
  EXPECT_EQ(ra["frame_ms"], rb["frame_ms"]);
  EXPECT_EQ(ra["measurement"], rb["measurement"]);
  EXPECT_EQ(ra["error"], rb["error"]);
  EXPECT_EQ(rb["case"]["id"], "same/backend=gl");
  EXPECT_EQ(rb["shared"]["measured_for"], "fig-a");
  EXPECT_EQ(rb["shared"]["case"], "occ/backend=gl");
  for (const char* kind : {"image", "reference", "heatmap", "flip"}) {
    const std::string ia = ra["images"][kind], ib = rb["images"][kind];
    EXPECT_NE(ia, ib);  // each under its own case's name
    EXPECT_EQ(readFile(dir / "a" / ia), readFile(dir / "b" / ib)) << kind;
  }
  const std::vector<std::string> rowA = mdRow(dir / "a", "occ/backend=gl"),
                                 rowB = mdRow(dir / "b", "same/backend=gl");
  ASSERT_EQ(rowA.size(), 12u) << readFile(dir / "a" / "figure.md");
  ASSERT_EQ(rowB.size(), rowA.size()) << readFile(dir / "b" / "figure.md");
  for (std::size_t k = 3; k + 1 < rowA.size(); ++k)  // segments .. shadow MiB
    EXPECT_EQ(rowA[k], rowB[k]) << "column " << k;
  EXPECT_EQ(rowA.back(), "");
  EXPECT_NE(rowB.back().find("measured once, for fig-a (case occ/backend=gl)"), std::string::npos)
      << rowB.back();
  const std::string mdB = readFile(dir / "b" / "figure.md");
  EXPECT_NE(mdB.find("Measured once: the cells whose note names another figure"),
            std::string::npos);
  // fig-a timed both cases of its claim in one run: a verdict; fig-b's shared case was timed
  // in fig-a's run: its ratio compares two runs, no verdict in time.
  const std::string mdA = readFile(dir / "a" / "figure.md");
  EXPECT_EQ(mdA.find("not timed in one interleaved run"), std::string::npos) << mdA;
  EXPECT_NE(mdB.find("(two runs) | none: not timed in one interleaved run"), std::string::npos)
      << mdB;

  // The control: without the store the case is measured again, and the two measurements of
  // it differ (timing samples are never equal run to run).
  const CliResult again = figure("fig-b", "b2", "");
  EXPECT_EQ(again.out.find("taken from the case store"), std::string::npos) << again.out;
  const json rc = resultOf(dir / "b2", "same");
  EXPECT_FALSE(rc.contains("shared"));
  EXPECT_NE(ra["frame_ms"]["samples"], rc["frame_ms"]["samples"]);
  EXPECT_EQ(ra["error"], rc["error"]);  // errors are deterministic; times are not

  // A damaged entry reads as a miss: the case is measured again and kept anew.
  int entries = 0;
  for (const auto& e : fs::directory_iterator(store)) {
    std::ofstream(e.path() / "entry.json") << "{\"format\": 1, \"key\": ";
    ++entries;
  }
  EXPECT_EQ(entries, 3);  // fig-a's two cases, fig-b's own
  const CliResult damaged = figure("fig-b", "b3", " --cases " + store.string());
  EXPECT_NE(damaged.out.find(": 0 taken (measured once, by an earlier sweep), 2 measured"),
            std::string::npos)
      << damaged.out;
  EXPECT_NE(resultOf(dir / "b3", "same")["frame_ms"]["samples"], ra["frame_ms"]["samples"]);
  fs::remove_all(dir);
}

// The key: one case however its specs are spelled; another size, rounds or technique option
// is another case; a key that differs from the entry's (a hash collision) is a miss.
TEST(FigureCases, TheKeyIsTheCanonicalCaseAndItsRounds) {
  const sb::Suite s = sb::parseSuite(R"({"name": "k", "defaults": {"scene":
      "straight:strands=40,alpha=0.5", "size": "40x40", "backend": "gl"}, "groups": [
      {"name": "a", "shadow": "occupancy"}, {"name": "b", "shadow": "occupancy:jitter=off"},
      {"name": "c", "shadow": "occupancy:jitter=on"}, {"name": "d", "shadow": "occupancy",
      "size": "40x41"}, {"name": "e", "shadow": "occupancy", "scene":
      "straight:alpha=0.50,strands=40"}]})",
                                     "k.json");
  ASSERT_EQ(s.cases.size(), 5u);
  const fs::path dir = tempDir("case-key");
  const sb::CaseStore store(dir / "cases");
  const sb::RepetitionOptions three{3, 3, 0}, five{5, 5, 0};
  auto key = [&](int i, const sb::RepetitionOptions& r = {3, 3, 0}) {
    return store.key(s.cases[std::size_t(i)], r, true);
  };
  EXPECT_EQ(key(0), key(1));  // the default written out
  EXPECT_EQ(key(0), key(4));  // 0.50 is 0.5, in any order
  EXPECT_NE(key(0), key(2));
  EXPECT_NE(key(0), key(3));
  EXPECT_NE(key(0, three), key(0, five));
  // Interleaved, `repeat` is only the rounds' default: the rounds are the key.
  sb::SweepCase repeated = s.cases[0];
  repeated.request.repeat = 5;
  EXPECT_EQ(store.key(repeated, three, true), key(0, three));
  EXPECT_NE(store.key(repeated, three, false), store.key(s.cases[0], three, false));
  EXPECT_NE(store.key(s.cases[0], three, true), store.key(s.cases[0], three, false));
  EXPECT_NE(key(0).find("\"commit\""), std::string::npos);
  EXPECT_NE(key(0).find("\"executable\""), std::string::npos);
  // Nothing stored: a miss, nothing written.
  EXPECT_FALSE(store.take(key(0), dir / "sweep", s.cases[0]).has_value());
  EXPECT_FALSE(fs::exists(dir / "sweep"));
  fs::remove_all(dir);
}

// A claim's verdict in time needs both cases timed in one interleaved run.
TEST(FigureCases, ATimeVerdictOnlyFromOneInterleavedRun) {
  auto result = [](const char* group, double ms, const char* run) {
    json r = {{"backend", "gl"},
              {"case", {{"id", std::string(group) + "/gl"}, {"group", group}}},
              {"frame_ms", {{"median", ms}, {"samples", {ms, ms * 1.01, ms * 0.99, ms}}}}};
    if (*run) r["measurement"] = {{"interleaved_run", run}};
    return r;
  };
  const json table = {{"title", "T"},
                      {"metric", "frame_ms"},
                      {"paper_unit", "ms"},
                      {"rows",
                       {{{"label", "base"}, {"group", "base"}, {"paper", 10}, {"baseline", true}},
                        {{"label", "x"}, {"group", "x"}, {"paper", 20}}}}};
  auto claim = [&](const char* runBase, const char* runX) {
    const json results = {{"tables", {table}},
                          {"results", {result("base", 10, runBase), result("x", 20, runX)}}};
    const auto claims = sb::report::figureClaims(results);
    EXPECT_EQ(claims.size(), 1u);
    return claims.empty() ? sb::report::FigureClaim{} : claims[0];
  };
  const auto one = claim("r1", "r1");
  EXPECT_TRUE(one.oneRun);
  EXPECT_EQ(one.time, "holds");
  ASSERT_TRUE(one.low.has_value());
  EXPECT_GT(*one.low, 1.0);
  // The control: the same samples from two runs, or without a run, give no verdict in time.
  for (const auto& c : {claim("r1", "r2"), claim("", "")}) {
    EXPECT_FALSE(c.oneRun);
    EXPECT_EQ(c.time, "none: not timed in one interleaved run");
    EXPECT_FALSE(c.low.has_value());
    ASSERT_TRUE(c.estimate.has_value());
    EXPECT_DOUBLE_EQ(*c.estimate, 2.0);
  }
}

}  // namespace
