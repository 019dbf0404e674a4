// The figure tables in docs/ are written by their commands, never by hand: every
// docs/figures/NAME.md opens with the header `strandbench figure NAME --docs docs/figures`
// writes (the command, the commit, and the digest of everything below the header), NAME is a
// figure of suites/figures, its grid image is beside it, the digest matches (a number edited
// by hand, or a table pasted from another run, no longer does), and no other page of docs/
// holds a figure header (a copy of a generated table).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>

#include "harness/figure.h"
#include "reports/figure_report.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;
using sbtest::readFile;

const fs::path kDocs = fs::path(SB_SOURCE_DIR) / "docs";

TEST(FigureDocs, HeaderRoundTripsAndADigestCatchesAHandEdit) {
  const std::string body = "# T\n\n| a | b |\n|---|---|\n| 1.50 | 2 |\n";
  const std::string cmd = "strandbench figure occ-fps --backend gl --out x --docs docs/figures";
  const std::string sha = "0123456789abcdef0123456789abcdef01234567";
  const std::string doc = sb::report::figureHeader("occ-fps", cmd, sha, body) + body;
  const auto h = sb::report::parseFigureHeader(doc);
  ASSERT_TRUE(h.has_value()) << doc;
  EXPECT_EQ(h->name, "occ-fps");
  EXPECT_EQ(h->command, cmd);
  EXPECT_EQ(h->commit, sha);
  EXPECT_EQ(h->digest, sb::report::figureDigest(body));
  std::string edited = body;
  edited.replace(edited.find("1.50"), 4, "1.22");
  EXPECT_NE(sb::report::figureDigest(edited), h->digest);
  EXPECT_FALSE(sb::report::parseFigureHeader(body).has_value());
  EXPECT_FALSE(sb::report::parseFigureHeader("<!-- strandbench figure x -->\n").has_value());
  // FNV-1a 64 of the empty string: its offset basis.
  EXPECT_EQ(sb::report::figureDigest(""), "cbf29ce484222325");
}

TEST(FigureDocs, EveryFigurePageWasWrittenByItsCommand) {
  const fs::path dir = kDocs / "figures";
  ASSERT_TRUE(fs::is_directory(dir)) << dir;
  const auto names = sb::figureNames();
  int pages = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const fs::path p = e.path();
    const std::string stem = p.stem().string();
    if (p.extension() == ".png") {
      EXPECT_TRUE(fs::is_regular_file(dir / (stem + ".md"))) << p << ": an image with no page";
      continue;
    }
    ASSERT_EQ(p.extension(), ".md") << p << ": docs/figures holds the pages and their images";
    if (stem == "README") continue;
    ++pages;
    const std::string text = readFile(p);
    const auto h = sb::report::parseFigureHeader(text);
    ASSERT_TRUE(h.has_value()) << p << ": no header; write it with `strandbench figure " << stem
                               << " --docs docs/figures`";
    EXPECT_EQ(h->name, stem) << p;
    EXPECT_NE(std::find(names.begin(), names.end(), stem), names.end())
        << p << ": no figure " << stem << " in suites/figures";
    EXPECT_TRUE(h->command.starts_with("strandbench figure " + stem + " ")) << h->command;
    EXPECT_NE(h->command.find("--docs"), std::string::npos) << h->command;
    EXPECT_TRUE(std::regex_match(h->commit, std::regex("[0-9a-f]{40}")))
        << p << ": commit " << h->commit;
    const std::string body = text.substr(text.find('\n') + 1);
    EXPECT_EQ(sb::report::figureDigest(body), h->digest)
        << p << ": edited after its command wrote it; run the command again";
    EXPECT_NE(body.find("Written by `" + h->command + "` on commit `" + h->commit.substr(0, 12)),
              std::string::npos)
        << p << ": the visible line contradicts the header";
    EXPECT_TRUE(fs::is_regular_file(dir / (stem + ".png"))) << p << ": its grid is missing";
  }
  EXPECT_GT(pages, 0);
}

TEST(FigureDocs, NoOtherPageHoldsACopiedFigureTable) {
  const auto names = sb::figureNames();
  for (const auto& e : fs::recursive_directory_iterator(kDocs)) {
    if (e.path().extension() != ".md" || e.path().parent_path() == kDocs / "figures") continue;
    const std::string text = readFile(e.path());
    for (const std::string& n : names)  // a real header (the format's example names NAME)
      EXPECT_EQ(text.find("<!-- strandbench figure " + n + ": "), std::string::npos)
          << e.path() << ": include docs/figures/" << n << ".md by a link instead of a copy";
  }
}

// A figure page depends on its figure file, the figure code and the folders of the
// techniques it runs (and the exact references), not on every technique: `docs refresh
// --stale` lists it when one of those changes.
TEST(FigureDocs, AFigureDependsOnItsFileAndTheTechniquesItRuns) {
  const auto deps = sb::figureDepends("occ-fig1");
  auto has = [&](const std::string& p) {
    return std::find(deps.begin(), deps.end(), p) != deps.end();
  };
  EXPECT_TRUE(has("suites/figures/occ-fig1.json"));
  EXPECT_TRUE(has("harness/figure.cpp"));
  EXPECT_TRUE(has("techniques/occupancy"));      // --shadow occupancy
  EXPECT_TRUE(has("techniques/occupancy_oit"));  // --oit occupancy
  EXPECT_TRUE(has("techniques/exact"));          // the reference
  EXPECT_FALSE(has("techniques/osm"));           // not run by this figure
  for (const auto& p : deps) EXPECT_TRUE(fs::exists(fs::path(SB_SOURCE_DIR) / p)) << p;
  EXPECT_EQ(sb::figureDepends("no-such-figure"),
            std::vector<std::string>{"suites/figures/no-such-figure.json"});
}

}  // namespace
