// `strandbench figure`: every figure's --small variant on both backends writes its grid
// (figure.png with the paper's rows x columns, each cell our image and its error heatmap) and
// its table (figure.md, figure.json); a bad name is refused with the list of figures; the grid
// check fails on a grid of the wrong shape. One ctest entry per figure (ctest -j2 splits them).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "harness/figure.h"
#include "imaging/image.h"
#include "reports/figure_report.h"
#include "test_util.h"

namespace {

using namespace sbtest;
namespace fs = std::filesystem;
using json = nlohmann::json;

// The papers' grids, written here apart from the figure files: rows x columns.
const std::map<std::string, std::pair<int, int>> kPaperShapes = {
    {"dom-fig1", {1, 4}},      {"dom-fig3", {1, 4}},      {"dom-fig5", {1, 4}},
    {"dom-fig7", {1, 1}},      {"dom-fig8", {1, 3}},      {"occ-fig1", {1, 2}},
    {"occ-fig2", {1, 4}},      {"occ-steps", {1, 1}},     {"occ-fig6", {1, 2}},
    {"occ-fig9", {1, 3}},      {"occ-fig10", {1, 3}},     {"occ-memory", {1, 5}},
    {"osm-fig4", {1, 6}},      {"osm-plate2", {1, 4}},    {"osm-plate3", {1, 2}},
    {"thesis-table1", {3, 3}}, {"thesis-table2", {3, 2}}, {"osm-fig3", {1, 3}},
    {"osm-fig5", {1, 8}},      {"osm-steps", {1, 1}},     {"dom-fig2", {1, 3}},
    {"dom-fig4", {1, 4}},      {"dom-fig6", {1, 4}},      {"dom-depth-bits", {2, 3}},
    {"occ-fig4", {1, 2}},      {"occ-fig5", {1, 3}},      {"occ-fps", {1, 2}}};

json figureFile(const std::string& name) {
  return json::parse(readFile(sb::figuresDir() / (name + ".json")));
}

// A rectangle of figure.png holds more than one colour: something was pasted there.
bool varied(const sb::Image& img, int x0, int y0, int w, int h) {
  for (int y = y0; y < y0 + h; y += 2)
    for (int x = x0; x < x0 + w; x += 2)
      for (int c = 0; c < 3; ++c)
        if (std::abs(img.at(x, y, c) - img.at(x0, y0, c)) > 0.02f) return true;
  return false;
}

// Checks a figure folder against its figure file; returns the problems found.
std::vector<std::string> checkFigureFolder(const fs::path& dir, const json& file,
                                           const std::string& backend) {
  std::vector<std::string> problems;
  auto fail = [&](const std::string& s) { problems.push_back(s); };
  for (const char* f : {"figure.png", "figure.md", "figure.json", "results.json", "report.md"})
    if (!fs::is_regular_file(dir / f)) fail(std::string("missing ") + f);
  if (!problems.empty()) return problems;
  const json fig = json::parse(readFile(dir / "figure.json"));
  if (fig["backend"] != backend) fail("backend " + fig["backend"].dump());
  if (fig["rows"] != file["figure"]["rows"]) fail("rows differ from the figure file");
  if (fig["columns"] != file["figure"]["columns"]) fail("columns differ from the figure file");
  const std::size_t rows = fig["rows"].size(), cols = fig["columns"].size();
  if (fig["cells"].size() != rows) fail("cells: not one row per label");
  const sb::Image png = sb::readImage((dir / "figure.png").string());
  const json& L = fig["layout"];
  if (png.width != L["width"].get<int>() || png.height != L["height"].get<int>())
    fail("figure.png is not the layout's size");
  if (L["width"].get<int>() !=
      L["x0"].get<int>() +
          static_cast<int>(cols) * (L["cell_width"].get<int>() + L["margin"].get<int>()))
    fail("figure.png does not hold one cell per column");
  if (L["height"].get<int>() !=
      L["y0"].get<int>() +
          static_cast<int>(rows) * (L["cell_height"].get<int>() + L["margin"].get<int>()))
    fail("figure.png does not hold one cell per row");
  const std::string md = readFile(dir / "figure.md");
  for (std::size_t r = 0; r < fig["cells"].size(); ++r) {
    if (fig["cells"][r].size() != cols) fail("cells row " + std::to_string(r) + ": wrong size");
    for (std::size_t c = 0; c < fig["cells"][r].size(); ++c) {
      const json& cell = fig["cells"][r][c];
      const std::string where =
          cell["row"].get<std::string>() + " / " + cell["column"].get<std::string>() + ": ";
      if (file["figure"]["cells"][r][c].is_null()) continue;
      if (cell["case"].is_null()) {
        fail(where + "no case");
        continue;
      }
      if (cell.contains("note")) fail(where + cell["note"].get<std::string>());
      for (const char* k : {"image", "heatmap"})
        if (!cell["images"].contains(k) ||
            !fs::is_regular_file(dir / cell["images"][k].get<std::string>()))
          fail(where + "no " + k);
      if (!cell["frame_ms"].is_number()) fail(where + "no frame time");
      if (!cell["image_rmse"].is_number()) fail(where + "no image error");
      const int x = L["x0"].get<int>() +
                    static_cast<int>(c) * (L["cell_width"].get<int>() + L["margin"].get<int>());
      const int y = L["y0"].get<int>() +
                    static_cast<int>(r) * (L["cell_height"].get<int>() + L["margin"].get<int>());
      if (!varied(png, x, y, L["tile"].get<int>(), L["tile"].get<int>()))
        fail(where + "the image tile is flat");
      // Markdown escapes the case id's underscores (shadow.depth\_bits=8).
      std::string escaped;
      for (char ch : cell["case"].get<std::string>())
        escaped += ch == '_' ? "\\_" : std::string(1, ch);
      if (md.find(cell["case"].get<std::string>()) == std::string::npos &&
          md.find(escaped) == std::string::npos)
        fail(where + "figure.md does not name the case");
    }
  }
  for (const json& t : file.value("tables", json::array()))
    if (md.find(t["title"].get<std::string>()) == std::string::npos)
      fail("figure.md lacks the paper table " + t["title"].get<std::string>());
  return problems;
}

std::vector<std::string> missingModels(const json& file) {
  std::vector<std::string> missing;
  for (const json& m : file["figure"].value("models", json::array()))
    if (!fs::is_regular_file(sb::modelsDir() / m.get<std::string>()))
      missing.push_back((sb::modelsDir() / m.get<std::string>()).string());
  return missing;
}

// (figure, API): the test command runs every figure on one API, the APIs alternating down the
// list (Figures/); the nightly job runs each on the other (Nightly/, which ctest leaves out:
// cmake/TestSuites.cmake). Together every figure on both.
using FigureApi = std::pair<std::string, std::string>;
class FigureSmall : public ::testing::TestWithParam<FigureApi> {};

std::vector<FigureApi> figureApis(bool nightly) {
  std::vector<FigureApi> out;
  const std::vector<std::string> names = sb::figureNames();
  for (std::size_t i = 0; i < names.size(); ++i)
    out.emplace_back(names[i], (i % 2 == 0) != nightly ? "gl" : "vulkan");
  return out;
}

TEST_P(FigureSmall, WritesItsGridAndTable) {
  const auto& [name, backend] = GetParam();
  const json file = figureFile(name);
  ASSERT_TRUE(kPaperShapes.contains(name)) << name << ": add the paper's grid shape to the test";
  EXPECT_EQ(file["figure"]["rows"].size(), static_cast<std::size_t>(kPaperShapes.at(name).first));
  EXPECT_EQ(file["figure"]["columns"].size(),
            static_cast<std::size_t>(kPaperShapes.at(name).second));
  if (const auto missing = missingModels(file); !missing.empty())
    GTEST_SKIP() << name << " needs " << missing[0] << ", which is not there (../shared/models)";
  const fs::path dir = tempDir("figure-" + name);
  const fs::path out = dir / "out";
  const CliResult r =
      runCli("figure " + name + " --small --backend " + backend + " --out " + out.string());
  EXPECT_EQ(r.status, 0) << backend << "\n" << r.out << r.err;
  for (const std::string& p : checkFigureFolder(out, file, backend))
    ADD_FAILURE() << name << " on " << backend << ": " << p;
  // Only the figure folder is left: no temporary folder beside it.
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1) << "a temporary folder was left in " << dir;
  // What it says it wrote is there (the sweep runs in a temporary folder renamed at the
  // end: its messages name the final one).
  EXPECT_EQ(r.out.find(".tmp-"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("wrote " + (out / "results.json").string()), std::string::npos) << r.out;
  EXPECT_TRUE(fs::is_regular_file(out / "results.json"));
  fs::remove_all(dir);
}

// --backend both: one run, the paper's rows once per API, the paper table with a column per API.
TEST(Figure, BothBackendsInOneRunShowEachAPI) {
  const fs::path dir = tempDir("figure-both");
  const fs::path out = dir / "out";
  const CliResult r = runCli("figure osm-steps --small --backend both --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const json fig = json::parse(readFile(out / "figure.json"));
  EXPECT_EQ(fig["backend"], "gl + vulkan");
  EXPECT_EQ(fig["rows"], json::array({"340k lines (gl)", "340k lines (vulkan)"}));
  ASSERT_EQ(fig["cells"].size(), 2u);
  for (const json& row : fig["cells"]) {
    EXPECT_FALSE(row[0].contains("note")) << row[0].dump();
    EXPECT_TRUE(row[0]["frame_ms"].is_number()) << row[0].dump();
  }
  EXPECT_NE(fig["cells"][0][0]["case"], fig["cells"][1][0]["case"]);
  const std::string md = readFile(out / "figure.md");
  for (const char* s : {"--backend both", "Backend gl + vulkan", "| gl (ms) |", "| vulkan (ms) |"})
    EXPECT_NE(md.find(s), std::string::npos) << s << "\n" << md;
  // Control: a single API's page has no other API's column.
  const fs::path gl = dir / "gl";
  ASSERT_EQ(runCli("figure osm-steps --small --backend gl --out " + gl.string()).status, 0);
  EXPECT_EQ(readFile(gl / "figure.md").find("| vulkan (ms) |"), std::string::npos);
  fs::remove_all(dir);
}

// The papers' numbers the benchmarks print come from the figure files (one place), with the
// techniques of the rows' groups; a row naming a group the suite lacks is refused.
TEST(Figure, PaperTablesAreReadFromTheFigureFiles) {
  const sb::FigurePaperTable t = sb::figurePaperTable("occ-fig2");
  const json file = figureFile("occ-fig2");
  ASSERT_EQ(t.rows.size(), file["tables"][0]["rows"].size());
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    EXPECT_EQ(t.rows[i].label, file["tables"][0]["rows"][i]["label"]);
    EXPECT_EQ(*t.rows[i].paper, file["tables"][0]["rows"][i]["paper"].get<double>());
    EXPECT_EQ(t.rows[i].unit, "fps");
  }
  EXPECT_EQ(t.row("peel", true).label, "depth peeling");
  EXPECT_EQ(t.row("peel", true).shadow, "occupancy");  // the suite's default
  EXPECT_NEAR(*t.row("peel", true).paperMs(), 1000.0 / 4.01, 1e-9);
  expectInputError([&] { t.row("kbuffer", true); }, {"occ-fig2", "kbuffer"});
  const fs::path dir = tempDir("figure-paper-table");
  json bad = file;
  bad["tables"][0]["rows"][0]["group"] = "nope";
  std::ofstream(dir / "bad.json") << bad.dump();
  expectInputError([&] { sb::figurePaperTable((dir / "bad.json").string()); }, {"group \"nope\""});
  expectInputError([&] { sb::figurePaperTable("occ-fig2", 5); }, {"no paper table 6"});
  fs::remove_all(dir);
}

// Test names: the figure's name with '-' as '_', then the API.
std::string testName(const ::testing::TestParamInfo<FigureApi>& p) {
  std::string n = p.param.first + "_" + p.param.second;
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(Figures, FigureSmall, ::testing::ValuesIn(figureApis(false)), testName);
INSTANTIATE_TEST_SUITE_P(Nightly, FigureSmall, ::testing::ValuesIn(figureApis(true)), testName);

TEST(Figure, EveryPaperFigureHasAFile) {
  const auto names = sb::figureNames();
  for (const auto& [name, shape] : kPaperShapes)
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

TEST(Figure, ListHoldsEveryFigureOfTheFourPapers) {
  const CliResult l = runCli("figure --list");
  EXPECT_EQ(l.status, 0);
  int lines = 0;
  for (char c : l.out) lines += c == '\n';
  EXPECT_GE(lines, 26) << l.out;
  for (const char* n : {"osm-fig3", "osm-fig5", "osm-steps", "dom-fig2", "dom-fig4", "dom-fig6",
                        "dom-depth-bits", "occ-fig4", "occ-fig5", "occ-fps"})
    EXPECT_NE(l.out.find(std::string(n) + "  "), std::string::npos) << n << "\n" << l.out;
}

// The paper's settings in the figures that reproduce it: the OSM paper's 3x3 kernel on every
// OSM lookup of its figures, the thesis's DOM counting in the thesis's tables.
TEST(Figure, PaperSettingsInThePapersFigures) {
  for (const std::string& name : sb::figureNames()) {
    const json file = figureFile(name);
    std::vector<std::string> shadows;
    if (file.contains("defaults")) shadows.push_back(file["defaults"].value("shadow", ""));
    for (const json& g : file["groups"]) shadows.push_back(g.value("shadow", ""));
    for (const std::string& s : shadows) {
      if (name.starts_with("osm-") && s.starts_with("osm")) {
        EXPECT_NE(s.find("filter=box3x3"), std::string::npos) << name << ": " << s;
      }
      if (name.starts_with("thesis-") && s.starts_with("dom")) {
        EXPECT_NE(s.find("counting=thesis"), std::string::npos) << name << ": " << s;
      }
    }
  }
}

TEST(Figure, BadNameIsRefusedWithTheListAndWritesNothing) {
  const fs::path dir = tempDir("figure-bad");
  const CliResult r = runCli("figure dom-fig99 --small --out " + (dir / "out").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("unknown figure 'dom-fig99'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("dom-fig1"), std::string::npos) << r.err;  // the list
  EXPECT_NE(r.err.find("osm-plate3"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
  const CliResult b =
      runCli("figure dom-fig1 --small --backend metal --out " + (dir / "out").string());
  EXPECT_EQ(b.status, 2);
  EXPECT_NE(b.err.find("--backend metal"), std::string::npos) << b.err;
  const CliResult none = runCli("figure");
  EXPECT_EQ(none.status, 2);
  EXPECT_NE(none.err.find("dom-fig1"), std::string::npos) << none.err;
  // An existing folder that is not a figure's is left alone.
  fs::create_directories(dir / "mine");
  std::ofstream(dir / "mine" / "keep.txt") << "x";
  const CliResult o = runCli("figure dom-fig1 --small --out " + (dir / "mine").string());
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.err.find("not a figure folder"), std::string::npos) << o.err;
  EXPECT_TRUE(fs::is_regular_file(dir / "mine" / "keep.txt"));
  const CliResult l = runCli("figure --list");
  EXPECT_EQ(l.status, 0);
  EXPECT_NE(l.out.find("thesis-table1"), std::string::npos) << l.out;
  fs::remove_all(dir);
}

const char* kSuite = R"({
  "name": "f", "groups": [{"name": "a"}, {"name": "b"}],
  "figure": {"title": "T", "rows": ["r1", "r2"], "columns": ["c1", "c2"],
             "cells": [[{"group": "a"}, {"group": "b"}], [null, {"group": "a", "match": {"shadow": "x"}}]]}
})";

TEST(Figure, FigureBlockMustHaveThePapersShape) {
  json s = json::parse(kSuite);
  EXPECT_NO_THROW(sb::report::checkFigureBlock(s, "f.json"));
  json bad = s;
  bad["figure"]["cells"][1] = json::array({nullptr});  // a row one cell short
  expectInputError([&] { sb::report::checkFigureBlock(bad, "f.json"); },
                   {"f.json", "cells row 2", "must hold 2 cells"});
  bad = s;
  bad["figure"]["cells"].erase(1);
  expectInputError([&] { sb::report::checkFigureBlock(bad, "f.json"); }, {"2 rows"});
  bad = s;
  bad["figure"]["cells"][0][0]["group"] = "nope";
  expectInputError([&] { sb::report::checkFigureBlock(bad, "f.json"); },
                   {"(r1, c1)", "group \"nope\""});
  bad = s;
  bad["figure"].erase("rows");
  expectInputError([&] { sb::report::checkFigureBlock(bad, "f.json"); }, {"\"figure\".rows"});
}

TEST(Figure, GridPicksEachCellsResultOnItsBackend) {
  const json s = json::parse(kSuite);
  auto result = [](const char* group, const char* shadow, const char* backend) {
    return json{{"backend", backend},
                {"case",
                 {{"id", std::string(group) + "/" + backend},
                  {"group", group},
                  {"params", {{"shadow", shadow}, {"backend", backend}}}}},
                {"frame_ms", {{"median", 2.0}}}};
  };
  const json results = {{"results", json::array({result("a", "x", "vulkan"), result("a", "x", "gl"),
                                                 result("b", "y", "gl")})}};
  const auto g = sb::report::buildFigureGrid(s["figure"], results, "f", "gl");
  ASSERT_EQ(g.cells.size(), 2u);
  ASSERT_EQ(g.cells[0].size(), 2u);
  ASSERT_NE(g.cells[0][0].result, nullptr);
  EXPECT_EQ((*g.cells[0][0].result)["backend"], "gl");
  ASSERT_NE(g.cells[0][1].result, nullptr);
  EXPECT_EQ(g.cells[1][0].result, nullptr);  // null: the paper has no image there
  EXPECT_EQ(g.cells[1][0].note, "no image in the paper");
  ASSERT_NE(g.cells[1][1].result, nullptr);
  // On vulkan, group b has no result: the cell says so.
  const auto v = sb::report::buildFigureGrid(s["figure"], results, "f", "vulkan");
  EXPECT_EQ(v.cells[0][1].result, nullptr);
  EXPECT_NE(v.cells[0][1].note.find("no result of group b on vulkan"), std::string::npos);
  const json j = sb::report::figureJson(g, json::object());
  EXPECT_EQ(j["cells"][0][0]["case"], "a/gl");
  EXPECT_EQ(j["cells"][0][0]["frame_ms"], 2.0);
  EXPECT_TRUE(j["cells"][1][0]["case"].is_null());
}

TEST(Figure, ErrorClaimsHoldOrFailOnTheCellsValues) {
  sb::report::FigureGrid g;
  g.rows = {"r"};
  g.columns = {"a", "b"};
  const json ra = {{"error", {{"visibility", {{"rmse", 0.10}}}, {"image", {{"rmse", 0.0200}}}}}};
  const json rb = {{"error", {{"visibility", {{"rmse", 0.13}}}, {"image", {{"rmse", 0.0209}}}}}};
  sb::report::FigureCell a, b;
  a.result = &ra;
  b.result = &rb;
  a.banding = 0.5;
  g.cells = {{a, b}};
  sb::report::FigureErrorClaim c{"a below b", "visibility_rmse", "below", 0, 0, 0, 1, 0.05};
  EXPECT_EQ(sb::report::errorClaimVerdict(g, c), "holds");
  std::swap(c.column, c.thanColumn);
  EXPECT_EQ(sb::report::errorClaimVerdict(g, c), "fails");
  // 0.0200 against 0.0209: 4.3% apart, within 5%, not within 4%.
  sb::report::FigureErrorClaim same{"same", "image_rmse", "same", 0, 0, 0, 1, 0.05};
  EXPECT_EQ(sb::report::errorClaimVerdict(g, same), "holds");
  same.tolerance = 0.04;
  EXPECT_EQ(sb::report::errorClaimVerdict(g, same), "fails");
  // b has no banding: no verdict; a cell outside the grid: none either.
  EXPECT_EQ(sb::report::errorClaimVerdict(g, {"x", "banding", "below", 0, 0, 0, 1, 0.05}), "-");
  EXPECT_EQ(sb::report::errorClaimVerdict(g, {"x", "image_rmse", "below", 0, 0, 2, 1, 0.05}), "-");
}

// Memory claims: a cell's shadow MiB against another cell's (scaled by a factor) or against the
// paper's own number; each fails when the numbers say so.
TEST(Figure, MemoryClaimsHoldOrFailOnTheCellsShadowMemory) {
  sb::report::FigureGrid g;
  g.rows = {"r"};
  g.columns = {"a", "b"};
  const double mib = 1024.0 * 1024.0;
  const json ra = {{"memory", {{"shadow_bytes", 10 * mib}}}};
  const json rb = {{"memory", {{"shadow_bytes", 130 * mib}}}};
  sb::report::FigureCell a, b;
  a.result = &ra;
  b.result = &rb;
  g.cells = {{a, b}};
  sb::report::FigureErrorClaim c{"a below b", "shadow_mib", "below", 0, 0, 0, 1, 0.05};
  EXPECT_EQ(sb::report::errorClaimVerdict(g, c), "holds");
  c.factor = 0.1;  // an order of magnitude below: 10 against 13
  EXPECT_EQ(sb::report::errorClaimVerdict(g, c), "holds");
  c.factor = 0.05;  // against 6.5: fails
  EXPECT_EQ(sb::report::errorClaimVerdict(g, c), "fails");
  sb::report::FigureErrorClaim paper{"a is 10 MB", "shadow_mib", "same", 0, 0, 0, 0, 0.1};
  paper.paper = 10.5;
  EXPECT_EQ(sb::report::errorClaimVerdict(g, paper), "holds");
  EXPECT_EQ(*sb::report::claimTarget(g, paper), 10.5);
  paper.paper = 18;
  EXPECT_EQ(sb::report::errorClaimVerdict(g, paper), "fails");
  // A result without memory: no verdict.
  const json none = json::object();
  g.cells[0][0].result = &none;
  EXPECT_EQ(sb::report::errorClaimVerdict(g, paper), "-");
}

}  // namespace
