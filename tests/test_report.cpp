// The report writer: results.csv, report.md and report.html from a synthetic
// results document, and report.html loaded offline in headless Chromium.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "browser_util.h"
#include "imaging/image.h"
#include "reports/report_writer.h"
#include "reports/svg_chart.h"
#include "scenes/scene.h"
#include "test_util.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const char* const kScene = "curly:strands=1000,points=24,head=0";

// A small picture with many values, so images and heatmaps look like images.
void writePng(const fs::path& path, float tint) {
  sb::Image img(16, 16, 3);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      img.at(x, y, 0) = float(x) / 15.0f;
      img.at(x, y, 1) = float(y) / 15.0f;
      img.at(x, y, 2) = tint;
    }
  sb::writeImage(img, path.string());
}

json makeResult(const std::string& group, const json& params, int index, double ms,
                double shadowMiB) {
  std::string id = group + "/";
  for (const auto& [k, v] : params.items())
    if (k != "backend") id += k + "=" + (v.is_string() ? v.get<std::string>() : v.dump()) + ",";
  id += "backend=" + params["backend"].get<std::string>();
  const double shadowBytes = shadowMiB * 1024 * 1024;
  return {
      {"backend", params["backend"]},
      {"device", "llvmpipe"},
      {"scene", {{"spec", kScene}, {"strands", 1000}, {"points", 24000}, {"segments", 23000}}},
      {"shadow", params.value("shadow", "osm:maps=" + params.value("shadow.maps", json(1)).dump())},
      {"oit", "none"},
      {"size", {128, 96}},
      {"passes",
       {{{"name", "shadow.build"}, {"ms", {{"median", ms * 0.25}}}},
        {{"name", "shadow.filter"}, {"ms", {{"median", ms * 0.25}}}},
        {{"name", "draw"}, {"ms", {{"median", ms * 0.5}}}}}},
      {"frame_ms", {{"median", ms}, {"min", ms * 0.9}, {"max", ms * 1.2}, {"stddev", ms * 0.05}}},
      {"memory",
       {{"shadow_bytes", shadowBytes},
        {"oit_bytes", 0},
        {"total_bytes", shadowBytes + 4 * 1024 * 1024}}},
      {"error",
       {{"image",
         {{"rmse", 0.05 / ms},
          {"psnr", 40.0 - ms},
          {"ssim", 0.99},
          {"flip", {{"mean", 0.02 / ms}}}}},
        {"visibility", {{"rmse", 0.1 / ms}, {"max", 0.5}}},
        {"own",
         {{"technique", "shadow"},
          {"reference", {{"shadow", "exact"}, {"oit", "none"}}},
          {"image", {{"rmse", 0.03 / ms}, {"flip", {{"mean", 0.01 / ms}}}}}}},
        {"by_eye_layers",
         {{{"layers", {0, 0}}, {"pixels", 40}, {"flip_mean", 0.001}},
          {{"layers", {1, 1}}, {"pixels", 20}, {"flip_mean", 0.01 / ms}},
          {{"layers", {2, 3}}, {"pixels", 10}, {"flip_mean", 0.03 / ms}}}}}},
      {"depth_complexity", {{"eye", {{"max", 12}}}, {"light", nullptr}}},
      {"warnings", json::array()},
      {"case", {{"id", id}, {"group", group}, {"index", index}, {"params", params}}},
  };
}

// Two groups (one with a numeric technique axis and a probe), a paper table
// with a baseline row and one without, images for three cases (one missing).
json makeDocument(const fs::path& dir) {
  json results = json::array();
  int index = 0;
  const std::vector<std::pair<std::string, std::vector<double>>> shadows = {
      {"none", {2.0, 2.5}}, {"osm:maps=16", {4.0, 5.5}}, {"dom:layers=3", {3.0, 3.5}}};
  for (const auto& [shadow, ms] : shadows) {
    for (int b = 0; b < 2; ++b) {
      const std::string backend = b ? "vulkan" : "gl";
      results.push_back(makeResult("shadows", {{"shadow", shadow}, {"backend", backend}}, index++,
                                   ms[b], shadow == "none" ? 0.0 : 2.0 + b));
    }
  }
  for (int maps : {1, 2, 4})
    results.push_back(makeResult("osm-maps", {{"shadow.maps", maps}, {"backend", "gl"}}, index++,
                                 1.0 + maps, 0.5 * maps));

  // Absent and non-finite values: no error, NaN and infinity (written as null).
  results[0].erase("error");
  results[0]["depth_complexity"] = nullptr;
  results[1]["error"]["image"]["psnr"] = std::numeric_limits<double>::infinity();
  results[4]["frame_ms"]["stddev"] = std::numeric_limits<double>::quiet_NaN();
  results[3]["warnings"] = {"peeling cap hit: 8 layers | more needed & <tag>"};
  // Work counters on one case (the others predate them); no queries: samples null.
  results[2]["passes"][0]["executions"] = 2;
  results[2]["passes"][0]["work"] = {{"fragment_invocations", 1234567},
                                     {"vertex_invocations", 30000},
                                     {"samples_passed", nullptr},
                                     {"draws", 3},
                                     {"bytes_written", 16 * 1024 * 1024}};
  results[2]["frame_work"] = results[2]["passes"][0]["work"];
  // The paper table's work ratios: OSM 16 (gl) against no shadows, whose work only its
  // Vulkan case has: 3x the fragments, 2x the bytes.
  results[2]["frame_work"]["bytes_read"] = 0;
  results[2]["frame_work"]["bytes_storage"] = 0;
  results[1]["frame_work"] = {{"fragment_invocations", 1234567.0 / 3},
                              {"bytes_written", 4 * 1024 * 1024},
                              {"bytes_read", 2 * 1024 * 1024},
                              {"bytes_storage", 2 * 1024 * 1024}};
  results[6]["probe"] = {{"texel", {64, 64}},
                         {"map_size", 128},
                         {"light_depth", {0.1, 0.3, 0.5, 0.7, 0.9}},
                         {"exact", {1.0, 0.8, 0.5, 0.3, 0.2}},
                         {"visibility", {1.0, 0.7, 0.55, 0.25, nullptr}}};

  fs::create_directories(dir / "images");
  for (int i : {2, 3}) {
    const std::string stem = "images/case" + std::to_string(i);
    for (const char* kind : {"", ".reference", ".heatmap"})
      writePng(dir / (stem + kind + ".png"), 0.1f * i);
    results[i]["images"] = {{"image", stem + ".png"},
                            {"reference", stem + ".reference.png"},
                            {"heatmap", stem + ".heatmap.png"}};
  }
  results[4]["images"] = {{"image", "images/gone.png"}};
  // One animated case with its strip.
  writePng(dir / "images/case3.animation.png", 0.5f);
  results[3]["images"]["animation"] = "images/case3.animation.png";
  results[3]["animation"] = {
      {"kind", "light-orbit"},
      {"frames", 3},
      {"degrees", 30},
      {"flicker", {{"image", 0.004}, {"visibility", 0.02}, {"visibility_pixels", 300}}},
      {"per_frame",
       {{{"frame", 0},
         {"image", {{"rmse", 0.01}, {"flip", 0.02}}},
         {"visibility", {{"rmse", 0.05}}}},
        {{"frame", 1},
         {"image", {{"rmse", 0.02}, {"flip", 0.03}}},
         {"visibility", {{"rmse", 0.06}}}},
        {{"frame", 2},
         {"image", {{"rmse", 0.015}, {"flip", 0.025}}},
         {"visibility", {{"rmse", 0.04}}}}}},
      {"strip_frames", {0, 1, 2}}};

  return {
      {"schema_version", 1},
      {"suite",
       {{"name", "quick & dirty"}, {"description", "a test | suite"}, {"file", "suites/q.json"}}},
      {"context",
       {{"date", "2026-11-22T22:10:00Z"},
        {"commit", "e31ecd4"},
        {"commit_dirty", true},
        {"cpu", "Test CPU (2 threads)"},
        {"devices",
         {{{"backend", "gl"}, {"platform", "egl"}, {"device", "llvmpipe"}},
          {{"backend", "vulkan"}, {"device", "lavapipe"}}}}}},
      {"groups",
       {{{"name", "shadows"},
         {"description", "every shadow technique"},
         {"axes",
          {{"shadow", {"none", "osm:maps=16", "dom:layers=3"}}, {"backend", {"gl", "vulkan"}}}}},
        {{"name", "osm-maps"}, {"axes", {{"shadow.maps", {1, 2, 4}}, {"backend", {"gl"}}}}}}},
      {"tables",
       {{{"title", "DOM paper, Fig. 1"},
         {"source", "Yuksel & Keyser 2008"},
         {"group", "shadows"},
         {"metric", "frame_ms"},
         {"paper_unit", "fps"},
         {"rows",
          {{{"label", "no shadows"},
            {"match", {{"shadow", "none"}}},
            {"paper", 154},
            {"baseline", true}},
           {{"label", "OSM 16"}, {"match", {{"shadow", "osm:maps=16"}}}, {"paper", 81}},
           {{"label", "no such row"}, {"match", {{"shadow", "xyz"}}}, {"paper", 10}}}}},
        {{"title", "Shadow passes"},
         {"group", "osm-maps"},
         {"metric", "passes:shadow."},
         {"paper_unit", "ms"},
         {"rows", {{{"label", "4 maps"}, {"match", {{"shadow.maps", 4}}}, {"paper", 1.25}}}}}}},
      {"results", results},
  };
}

// Minimal RFC 4180 reader: rows of fields.
std::vector<std::vector<std::string>> parseCsv(const std::string& s) {
  std::vector<std::vector<std::string>> rows(1, std::vector<std::string>(1));
  bool quoted = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (quoted) {
      if (c == '"' && i + 1 < s.size() && s[i + 1] == '"')
        rows.back().back() += s[++i];
      else if (c == '"')
        quoted = false;
      else
        rows.back().back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      rows.back().emplace_back();
    } else if (c == '\n') {
      rows.emplace_back(1);
    } else {
      rows.back().back() += c;
    }
  }
  if (rows.back().size() == 1 && rows.back()[0].empty()) rows.pop_back();
  return rows;
}

// The cells of a markdown table row, trimmed.
std::vector<std::string> mdCells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line.substr(1));
  std::string cell;
  while (std::getline(in, cell, '|')) {
    const auto b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
    cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  return cells;
}

// The first line of `text` that starts with `prefix`.
std::string lineStarting(const std::string& text, const std::string& prefix) {
  std::stringstream in(text);
  std::string line;
  while (std::getline(in, line))
    if (line.starts_with(prefix)) return line;
  return "";
}

class ReportWriter : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = sbtest::tempDir("report");
    doc_ = makeDocument(dir_);
    sb::writeReports(doc_, dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  json doc_;
};

TEST_F(ReportWriter, CsvHasOneQuotedRowPerResult) {
  const std::string csv = sbtest::readFile(dir_ / "results.csv");
  const auto rows = parseCsv(csv);
  ASSERT_EQ(rows.size(), 1 + doc_["results"].size());
  for (const auto& row : rows) EXPECT_EQ(row.size(), rows[0].size());
  EXPECT_EQ(rows[0][0], "case_id");
  // Specs with commas are quoted and read back whole.
  EXPECT_NE(csv.find(std::string(",\"") + kScene + "\","), std::string::npos);
  const auto col = [&](const std::string& name) {
    return std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin();
  };
  EXPECT_EQ(rows[1][col("scene")], kScene);
  EXPECT_EQ(rows[1][col("case_id")], "shadows/shadow=none,backend=gl");
  EXPECT_EQ(rows[1][col("size")], "128x96");
  EXPECT_EQ(rows[1][col("image_rmse")], "");                // no error
  EXPECT_EQ(rows[1][col("depth_complexity_eye_max")], "");  // null depth complexity
  EXPECT_EQ(rows[2][col("image_psnr")], "");                // infinity
  EXPECT_EQ(rows[5][col("frame_ms_stddev")], "");           // NaN
  EXPECT_DOUBLE_EQ(std::stod(rows[3][col("frame_ms_median")]), 4.0);
  EXPECT_DOUBLE_EQ(std::stod(rows[3][col("image_flip_mean")]), 0.02 / 4.0);
  EXPECT_EQ(rows[1][col("image_flip_mean")], "");  // no error
  EXPECT_EQ(rows[3][col("memory_shadow_bytes")], std::to_string(2 * 1024 * 1024));
  EXPECT_EQ(rows[3][col("depth_complexity_eye_max")], "12");
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
}

TEST_F(ReportWriter, WorkInCsvPassesCsvAndReports) {
  const auto rows = parseCsv(sbtest::readFile(dir_ / "results.csv"));
  const auto col = [&](const std::vector<std::string>& header, const std::string& name) {
    return std::find(header.begin(), header.end(), name) - header.begin();
  };
  ASSERT_LT(col(rows[0], "bytes_storage"), static_cast<long>(rows[0].size()));
  EXPECT_EQ(rows[3][col(rows[0], "fragment_invocations")], "1234567");
  EXPECT_EQ(rows[3][col(rows[0], "samples_passed")], "");        // null: no queries
  EXPECT_EQ(rows[1][col(rows[0], "fragment_invocations")], "");  // no work: empty

  const auto passes = parseCsv(sbtest::readFile(dir_ / "passes.csv"));
  ASSERT_EQ(passes.size(), 1 + 3 * doc_["results"].size());  // three passes per case
  for (const auto& row : passes) EXPECT_EQ(row.size(), passes[0].size());
  EXPECT_EQ(passes[0][0], "case_id");
  const auto& shadowBuild = passes[1 + 3 * 2];
  EXPECT_EQ(shadowBuild[col(passes[0], "pass")], "shadow.build");
  EXPECT_EQ(shadowBuild[col(passes[0], "executions")], "2");
  EXPECT_EQ(shadowBuild[col(passes[0], "bytes_written")], std::to_string(16 * 1024 * 1024));
  EXPECT_EQ(shadowBuild[col(passes[0], "bytes_read")], "");

  const std::string md = sbtest::readFile(dir_ / "report.md");
  EXPECT_NE(md.find("## Passes: time and work"), std::string::npos);
  EXPECT_NE(lineStarting(md,
                         "| shadow=osm:maps=16 | gl | shadow.build | 2 | 1.00 | "
                         "1.2 M | 30 k | – | – | 3 | – | 16 MiB | – | – |"),
            "")
      << md;
  // Where the case's label does not name the technique, a column does.
  EXPECT_NE(lineStarting(md, "| shadow.maps=1 | gl | osm:maps=1 | shadow.build |"), "") << md;
  // One case with counters on gl: no fit, and said so.
  EXPECT_NE(md.find("## Cost model"), std::string::npos);
  EXPECT_NE(md.find("too few cases to fit"), std::string::npos);
  const json model = json::parse(sbtest::readFile(dir_ / "cost_model.json"));
  ASSERT_TRUE(model["models"].is_array());
  EXPECT_FALSE(model["models"][0]["fitted"].get<bool>());

  const std::string html = sbtest::readFile(dir_ / "report.html");
  EXPECT_NE(html.find("<details class=\"passes\"><summary>shadows"), std::string::npos);
  EXPECT_NE(html.find("<h2 id=\"cost-model\">"), std::string::npos);
}

TEST_F(ReportWriter, MarkdownHasTablesRatiosAndWarnings) {
  const std::string md = sbtest::readFile(dir_ / "report.md");
  EXPECT_NE(md.find("# strandbench report: quick & dirty"), std::string::npos);
  EXPECT_NE(md.find("a test \\| suite"), std::string::npos);  // escaped pipe
  EXPECT_NE(md.find("### shadows"), std::string::npos);
  EXPECT_NE(md.find("### osm-maps"), std::string::npos);
  EXPECT_NE(md.find("| PSNR dB (total) | FLIP mean (total) | Visibility RMSE | Own error of | "
                    "Image RMSE (own) | FLIP mean (own) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("### DOM paper, Fig. 1"), std::string::npos);

  // OSM 16 on gl: 4 ms against the 2 ms baseline; the paper's 81 fps against 154 fps.
  const auto header = mdCells(lineStarting(md, "| Row |"));
  const auto row = mdCells(lineStarting(md, "| OSM 16 |"));
  ASSERT_EQ(header.size(), row.size()) << md;
  const auto at = [&](const std::string& name) {
    const auto i = std::find(header.begin(), header.end(), name) - header.begin();
    return i < static_cast<long>(row.size()) ? row[i] : std::string("missing");
  };
  EXPECT_NEAR(std::stod(at("gl ratio")), 2.0, 1e-9);
  EXPECT_NEAR(std::stod(at("vulkan ratio")), 5.5 / 2.5, 0.005);
  EXPECT_NEAR(std::stod(at("Paper ratio")), 154.0 / 81.0, 0.005);
  EXPECT_EQ(at("Paper"), "81 fps (12.3 ms)");
  EXPECT_NEAR(std::stod(at("gl (ms)")), 4.0, 1e-9);
  // The claim in work: the frame's fragments and bytes over the baseline's.
  EXPECT_NEAR(std::stod(at("fragments ratio")), 3.0, 1e-6);
  EXPECT_NEAR(std::stod(at("bytes ratio")), 2.0, 1e-6);
  EXPECT_NE(md.find("no such row"), std::string::npos);

  // Without a baseline: ours / paper. passes:shadow. sums two passes of 5 ms: 2.5 ms.
  const auto maps = mdCells(lineStarting(md, "| 4 maps |"));
  ASSERT_EQ(maps.size(), 4u) << md;
  EXPECT_NEAR(std::stod(maps[2]), 2.5, 1e-9);
  EXPECT_NEAR(std::stod(maps[3]), 2.0, 1e-9);

  // Group table: median ± stddev, memory MiB.
  EXPECT_NE(lineStarting(md, "| osm:maps=16 | gl | 4.00 ± 0.20 | 6.00 |"), "") << md;
  EXPECT_NE(md.find("peeling cap hit: 8 layers \\| more needed & \\<tag\\>"), std::string::npos);

  // Budgets on gl (both groups: same scene and size): OSM 1 map (2 ms) alone
  // fits 2 ms; DOM (3 ms, FLIP 0.0067) is the first of a tie within 3 ms; OSM
  // 16 maps (4 ms, FLIP 0.005) within 4 ms; "none" has no error, no choice.
  const std::size_t gl = md.find("128x96 \\| gl\n");
  ASSERT_NE(gl, std::string::npos) << md;
  const std::string budgets = md.substr(gl, md.find("###", gl) - gl);
  EXPECT_NE(lineStarting(budgets, "| ≤ 3.00 | dom:layers=3 | 0.00667 | dom:layers=3 | 0.0167 |"),
            "")
      << budgets;
  EXPECT_NE(lineStarting(budgets, "| ≤ 4.00 | osm:maps=16 | 0.00500 | osm:maps=16 | 0.0125 |"), "")
      << budgets;
  EXPECT_NE(lineStarting(budgets, "| ≤ 2.00 | osm:maps=1 | 0.0100 | osm:maps=1 | 0.0250 |"), "")
      << budgets;
  EXPECT_EQ(budgets.find("| none |"), std::string::npos) << budgets;
  EXPECT_NE(md.find("## Error under animation"), std::string::npos);
  EXPECT_NE(lineStarting(md,
                         "| shadows/shadow=osm:maps=16,backend=vulkan | osm:maps=16 | "
                         "light-orbit | 3 | 0.00400 | 0.0200 |"),
            "")
      << md;
}

TEST_F(ReportWriter, HtmlIsSelfContainedWithChartsAndImages) {
  const std::string html = sbtest::readFile(dir_ / "report.html");
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_NE(html.find("data:image/png;base64,iVBORw0KGgo"), std::string::npos);  // PNG signature
  EXPECT_NE(html.find("<svg class=\"chart-error-time\""), std::string::npos);
  EXPECT_NE(html.find("<polyline class=\"pareto-frontier\""), std::string::npos);
  EXPECT_NE(html.find("frame time vs shadow.maps"), std::string::npos);
  EXPECT_NE(html.find("memory vs shadow.maps"), std::string::npos);
  EXPECT_NE(html.find("image RMSE vs shadow.maps"), std::string::npos);
  EXPECT_NE(html.find("visibility along a light ray"), std::string::npos);
  EXPECT_NE(html.find("images/gone.png is missing"), std::string::npos);
  EXPECT_NE(html.find("<th>FLIP mean (total)</th>"), std::string::npos);
  EXPECT_NE(html.find("<th>FLIP mean (own)</th>"), std::string::npos);
  EXPECT_NE(html.find("FLIP 0.005"), std::string::npos);  // in a thumbnail caption
  EXPECT_NE(html.find("quick &amp; dirty"), std::string::npos);
  EXPECT_NE(html.find("&lt;tag&gt;"), std::string::npos);
  EXPECT_EQ(html.find("<tag>"), std::string::npos);
}

TEST(ReportWriterInput, SparseDocumentsGiveReports) {
  const fs::path dir = sbtest::tempDir("report-sparse");
  json bare = makeResult("g", {{"backend", "gl"}}, 0, 1.0, 1.0);
  bare["frame_ms"]["median"] = std::numeric_limits<double>::quiet_NaN();
  bare["probe"] = {{"light_depth", json::array()}, {"exact", nullptr}};
  bare["tables_in_result"] = json::object();
  for (const json& doc :
       {json::object(), json{{"results", json::array()}},
        json{{"results", {json::object(), bare}}, {"tables", {{{"rows", {json::object()}}}}}}}) {
    ASSERT_NO_THROW(sb::writeReports(doc, dir)) << doc.dump();
    for (const char* f : {"results.csv", "report.md", "report.html"})
      EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  EXPECT_EQ(parseCsv(sbtest::readFile(dir / "results.csv")).size(), 3u);
  fs::remove_all(dir);
}

// occ-fig2's chart: its no-transparency point (occupancy shadows) beside the
// occupancy-ordered one (occupancy shadows) is labelled "none + occupancy", not
// "occupancy"; a chart of shadow techniques alone keeps the shadow's name.
TEST(ReportWriterInput, PointWithoutTransparencyNamesItBesideTransparencyTechniques) {
  const fs::path dir = sbtest::tempDir("report-labels");
  json results = json::array();
  int index = 0;
  for (const char* oit : {"none", "occupancy"}) {
    json r = makeResult(oit, {{"backend", "gl"}}, index, 2.0 + index, 1.0);
    r["shadow"] = "occupancy";
    r["oit"] = oit;
    results.push_back(r);
    ++index;
  }
  sb::writeReports({{"results", results}}, dir);
  const std::string html = sbtest::readFile(dir / "report.html");
  EXPECT_NE(html.find(">none + occupancy</text>"), std::string::npos);
  EXPECT_NE(html.find(">occupancy + occupancy</text>"), std::string::npos);
  EXPECT_EQ(html.find(">occupancy</text>"), std::string::npos);
  EXPECT_NE(html.find("none + occupancy</td>"), std::string::npos);  // the budget table

  json shadowsOnly = results;
  shadowsOnly[1]["oit"] = "none";
  shadowsOnly[1]["shadow"] = "dom:layers=3";
  sb::writeReports({{"results", shadowsOnly}}, dir);
  const std::string plain = sbtest::readFile(dir / "report.html");
  EXPECT_NE(plain.find(">occupancy</text>"), std::string::npos);
  EXPECT_EQ(plain.find("none + "), std::string::npos);
  fs::remove_all(dir);
}

// The same technique's point without shadows beside its points with shadows is labelled
// "abuffer + none", not "abuffer"; and the depth-complexity chart's legend names each case
// once, with what tells it from the others ("gl, primitive=lines"), not "gl, vulkan, gl".
TEST(ReportWriterInput, LabelsAndLegendsNameEachCaseOnce) {
  const fs::path dir = sbtest::tempDir("report-legend");
  json results = json::array();
  int index = 0;
  for (const char* shadow : {"none", "dom:layers=3"})
    for (const char* primitive : {"lines", "ribbons"})
      for (const char* backend : {"gl", "vulkan"}) {
        json r = makeResult("g", {{"backend", backend}, {"primitive", primitive}}, index,
                            2.0 + index, 1.0);
        r["shadow"] = shadow;
        r["oit"] = "abuffer";
        results.push_back(r);
        ++index;
      }
  sb::writeReports({{"results", results}}, dir);
  const std::string html = sbtest::readFile(dir / "report.html");
  EXPECT_NE(html.find(">abuffer + none</text>"), std::string::npos);
  EXPECT_NE(html.find(">abuffer + dom:layers=3</text>"), std::string::npos);
  EXPECT_EQ(html.find(">abuffer</text>"), std::string::npos);
  for (const char* legend : {">gl, primitive=lines</text>", ">vulkan, primitive=ribbons</text>"})
    EXPECT_NE(html.find(legend), std::string::npos) << legend;
  EXPECT_EQ(html.find(">gl</text>"), std::string::npos);  // a bare backend repeats
  // Control: with one case per backend a chart's legend is the backend alone.
  sb::writeReports({{"results", json::array({results[0], results[1]})}}, dir);
  const std::string two = sbtest::readFile(dir / "report.html");
  EXPECT_NE(two.find(">gl</text>"), std::string::npos);
  EXPECT_NE(two.find(">vulkan</text>"), std::string::npos);
  fs::remove_all(dir);
}

TEST(ReportWriterInput, UnwritableFolderIsAnInputError) {
  const fs::path dir = sbtest::tempDir("report-bad");
  sbtest::expectInputError([&] { sb::writeReports(json::object(), dir / "missing"); },
                           {"missing", "does not exist"});
  std::ofstream(dir / "file") << "x";
  sbtest::expectInputError([&] { sb::writeReports(json::object(), dir / "file"); }, {"file"});
  sbtest::expectInputError([&] { sb::writeReports(json::array(), dir); }, {"JSON object"});
  if (::geteuid() != 0) {  // root writes to read-only folders
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
    sbtest::expectInputError([&] { sb::writeReports(json::object(), dir); }, {"not writable"});
    fs::permissions(dir, fs::perms::owner_all);
  }
  fs::remove_all(dir);
}

TEST(SvgChart, ParetoFrontierAndScales) {
  const auto front = sb::paretoFrontier(
      {{1, 5, "a"}, {2, 3, "b"}, {3, 4, "c"}, {4, 1, "d"}, {2, 3.5, "e"}, {NAN, 0, "nan"}});
  ASSERT_EQ(front.size(), 3u);
  EXPECT_EQ(front[0].tip + front[1].tip + front[2].tip, "abd");

  sb::Chart chart{"t & <u>", "x", "y"};
  chart.series.push_back({"s", {{1, 0.001, "p1"}, {2, 1.0, "p2"}}});
  const std::string svg = sb::svgChart(chart);
  EXPECT_NE(svg.find("y (log)"), std::string::npos);  // three decades
  EXPECT_EQ(svg.find("x (log)"), std::string::npos);
  EXPECT_NE(svg.find("t &amp; &lt;u&gt;"), std::string::npos);
  EXPECT_NE(svg.find("<title>p2</title>"), std::string::npos);
  EXPECT_NE(sb::svgChart(sb::Chart{"empty"}).find("no data"), std::string::npos);
}

TEST(SvgChart, LogAxisAboveTenfoldRange) {
  auto chart = [](double lo, double hi) {
    sb::Chart c{"frame time", "case", "frame ms"};
    c.series.push_back({"s", {{1, lo, "lo"}, {2, (lo + hi) / 2, "mid"}, {3, hi, "hi"}}});
    return sb::svgChart(c);
  };
  const std::string wide = chart(4, 60);  // 15x
  EXPECT_NE(wide.find("frame ms (log)"), std::string::npos);
  // Ticks at 1, 2, 5 x 10^k within the data's range, not two bare decades.
  for (const char* tick : {">5</text>", ">10</text>", ">20</text>", ">50</text>"})
    EXPECT_NE(wide.find(tick), std::string::npos) << tick;
  EXPECT_EQ(chart(4, 20).find("(log)"), std::string::npos);  // 5x: linear
}

// Stacked bars: each part as wide as its value on the shared axis, in its own colour,
// named in the legend and its tooltip; absent parts drawn as nothing.
TEST(SvgChart, StackedBarsWidthsFollowTheValues) {
  sb::StackedBars b{"frame by pass", "ms", {"depth", "shade"}, {}};
  b.rows.push_back({"one", {1, 3}});
  b.rows.push_back({"two", {2, NAN}});
  const std::string svg = sb::svgStackedBars(b);
  std::vector<double> widths;
  for (std::size_t at = svg.find("<rect x="); at != std::string::npos;
       at = svg.find("<rect x=", at + 1)) {
    const std::size_t end = svg.find('>', at);
    if (svg[end - 1] == '/') continue;  // a legend swatch (self-closing): bars have a title
    widths.push_back(std::stod(svg.substr(svg.find("width=\"", at) + 7)));
  }
  ASSERT_EQ(widths.size(), 3u) << svg;  // the missing part is not drawn
  EXPECT_NEAR(widths[1], 3 * widths[0], 1e-6);
  EXPECT_NEAR(widths[2], 2 * widths[0], 1e-6);
  EXPECT_NE(svg.find("depth: 1</title>"), std::string::npos);
  EXPECT_NE(svg.find(">shade</text>"), std::string::npos);  // legend
}

// Charts shown side by side share their axes by covering each other's range: a chart
// of values 4 to 20 given the range 4 to 60 draws the same axes as one of 4 to 60.
TEST(SvgChart, SharedRangeGivesTheSameAxes) {
  auto ticks = [](double hi, bool share) {
    sb::Chart c{"frame time", "case", "frame ms"};
    c.series.push_back({"s", {{1, 4, "lo"}, {2, hi, "hi"}}});
    if (share) c.xLo = 1, c.xHi = 2, c.yLo = 4, c.yHi = 60;
    const std::string svg = sb::svgChart(c);
    std::vector<std::string> found;
    for (const char* t : {">5</text>", ">10</text>", ">20</text>", ">50</text>", "(log)"})
      if (svg.find(t) != std::string::npos) found.push_back(t);
    return found;
  };
  EXPECT_EQ(ticks(20, true), ticks(60, false));
  EXPECT_NE(ticks(20, false), ticks(60, false));  // unshared: its own, linear axes
}

TEST(SvgChart, PointLabelsDoNotOverprint) {
  sb::Chart c{"crowd", "frame ms", "error"};
  c.autoLog = false;
  sb::ChartSeries s{"points"};
  s.line = false;
  for (int i = 0; i < 20; ++i)  // nearly one spot
    s.points.push_back({10 + 0.01 * i, 0.5 + 0.001 * i, "tip", "technique-" + std::to_string(i)});
  s.points.push_back({1, 0.1, "tip", "far-low"});
  s.points.push_back({20, 0.9, "tip", "far-high"});
  c.series.push_back(s);
  const std::string svg = sb::svgChart(c);

  struct Box {
    double x0, y0, x1, y1;
  };
  std::vector<Box> boxes;
  std::vector<std::string> placed;
  const std::regex label(
      R"re(<text class="point-label" x="([-0-9.]+)" y="([-0-9.]+)"[^>]*>([^<]*)</text>)re");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label); it != std::sregex_iterator();
       ++it) {
    const double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
    const std::string text = (*it)[3];
    const double w = static_cast<double>(text.size()) * sb::kLabelFontSize * 0.6;
    boxes.push_back({x, y - sb::kLabelFontSize, x + w, y});
    placed.push_back(text);
  }
  for (std::size_t a = 0; a < boxes.size(); ++a)
    for (std::size_t b = a + 1; b < boxes.size(); ++b) {
      const Box &p = boxes[a], &q = boxes[b];
      EXPECT_FALSE(p.x0 < q.x1 && q.x0 < p.x1 && p.y0 < q.y1 && q.y0 < p.y1)
          << placed[a] << " overlaps " << placed[b];
    }
  std::string crowded;
  const std::regex listed(R"re(<text class="crowded"[^>]*>([^<]*)</text>)re");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), listed); it != std::sregex_iterator();
       ++it)
    crowded += std::string((*it)[1]) + "\n";
  // Every label is either drawn or listed as crowded, not both; the far ones are drawn.
  EXPECT_GT(placed.size(), 2u);
  EXPECT_LT(placed.size(), 22u) << "20 labels cannot all fit around one spot";
  for (int i = 0; i < 20; ++i) {
    const std::string name = "technique-" + std::to_string(i);
    const bool drawn = std::count(placed.begin(), placed.end(), name) == 1;
    const bool listedHere = crowded.find(name + " — ") != std::string::npos;
    EXPECT_NE(drawn, listedHere) << name << "\n" << crowded;
  }
  EXPECT_EQ(std::count(placed.begin(), placed.end(), "far-low"), 1);
  EXPECT_EQ(std::count(placed.begin(), placed.end(), "far-high"), 1);
  EXPECT_NE(crowded.find("crowded"), std::string::npos);
}

// report.html in a real browser, offline: no console message (no script error,
// no load blocked by the page's Content-Security-Policy), the tables and charts
// in the DOM, and a screenshot with something on it. Then the same checks fail
// on a page with a script error and on a blank page.
TEST(ReportBrowser, LoadsOfflineWithoutConsoleErrors) {
  if (!fs::exists(sbtest::kChromium))
    GTEST_SKIP() << sbtest::kChromium << " is not installed (apt-get install chromium)";
  const fs::path dir = sbtest::tempDir("report-browser");
  sb::writeReports(makeDocument(dir), dir);

  const sbtest::PageLoad page = sbtest::loadPage(dir / "report.html", dir / "chromium");
  ASSERT_EQ(page.status, 0) << page.log;
  EXPECT_TRUE(page.console.empty()) << "console: " << ::testing::PrintToString(page.console);
  EXPECT_NE(page.dom.find("<table>"), std::string::npos);
  EXPECT_NE(page.dom.find("class=\"chart-error-time\""), std::string::npos);
  EXPECT_NE(page.dom.find("class=\"pareto-frontier\""), std::string::npos);
  // The error charts: FLIP as a third error axis, every point labelled
  // with its technique and a bar for its spread over repetitions, error
  // against depth complexity per technique, the budget table, the animation.
  for (const char* needle :
       {"metric-image-rmse", "metric-visibility-rmse", "metric-flip", "<text class=\"point-label\"",
        ">osm:maps=16</text>", "class=\"error-bar\"", "class=\"chart-depth-complexity\"",
        "Most accurate by FLIP", "Most accurate by image RMSE", "class=\"chart-animation\"",
        "alt=\"animation strip\"", "Image RMSE (own)"})
    EXPECT_NE(page.dom.find(needle), std::string::npos) << needle;
  const sbtest::ScreenshotVerdict shot = sbtest::inspectScreenshot(page.screenshot);
  EXPECT_FALSE(shot.blank) << shot.distinct << " colours, " << shot.inked << " inked";

  // A script error is caught.
  std::string broken = sbtest::readFile(dir / "report.html");
  broken.insert(broken.rfind("</body>"), "<script>undefinedFunction();</script>");
  std::ofstream(dir / "broken.html") << broken;
  const sbtest::PageLoad bad = sbtest::loadPage(dir / "broken.html", dir / "chromium-broken");
  ASSERT_EQ(bad.console.size(), 1u) << bad.log;
  EXPECT_NE(bad.console[0].find("Uncaught ReferenceError: undefinedFunction"), std::string::npos);

  // A blank page is blank.
  std::ofstream(dir / "blank.html") << "<!DOCTYPE html><html><body></body></html>";
  const sbtest::PageLoad blank = sbtest::loadPage(dir / "blank.html", dir / "chromium-blank");
  EXPECT_TRUE(blank.console.empty()) << blank.log;
  EXPECT_TRUE(sbtest::inspectScreenshot(blank.screenshot).blank);
  fs::remove_all(dir);
}

TEST(ReportBrowser, ConsoleMessagesAreFoundInTheLog) {
  const std::string log =
      "[1:2:1122/220850.699932:ERROR:dbus/bus.cc:405] Failed to connect to the bus\n"
      "[1:1:1122/220851.396526:INFO:CONSOLE:1] \"hi\", source: file:///a.html (1)\n"
      "[1:1:1122/220851.396723:INFO:CONSOLE(7)] \"Uncaught Error: x\", source: file:///a.html "
      "(7)\n";
  const auto messages = sbtest::consoleMessages(log);
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[0], "\"hi\", source: file:///a.html (1)");
  EXPECT_NE(messages[1].find("Uncaught Error: x"), std::string::npos);
}

}  // namespace
