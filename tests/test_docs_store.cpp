// Every measured number the docs publish is rendered from a stored run (docs/results/,
// reports/docs_store.h): the blocks of README.md and docs/ are what their runs render, no
// measured number stands outside a block, `docs refresh --stale` names the blocks whose code
// changed since their run, and two pages citing the same case print the same values. Each
// check is shown failing on a planted case.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "base/errors.h"
#include "reports/docs_store.h"
#include "reports/figure_report.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using sbtest::readFile;

const fs::path kRoot = SB_SOURCE_DIR;

void writeFile(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

int sh(const std::string& cmd) { return std::system(("(" + cmd + ") >/dev/null 2>&1").c_str()); }

TEST(DocsStore, TemplatesFillValuesSectionsFiltersAndFormats) {
  const json data = {{"rows",
                      {{{"name", "dom"}, {"ms", 12.345}, {"bytes", 3 * 1048576}, {"n", 1234567}},
                       {{"name", "osm"}, {"ms", 0.5}, {"bytes", 1048576}, {"n", 7}}}},
                     {"ok", true},
                     {"scene", {{"size", "64x64"}}}};
  EXPECT_EQ(sb::docs::renderTemplate(
                "{{#rows}}| {{name}} | {{ms:.1f}} | {{bytes|mib:.2f}} | {{n:,d}} |\n{{/rows}}",
                data, "t"),
            "| dom | 12.3 | 3.00 | 1,234,567 |\n| osm | 0.5 | 1.00 | 7 |\n");
  EXPECT_EQ(sb::docs::renderTemplate("{{#ok}}yes {{scene.size}}{{/ok}}{{#missing}}no{{/missing}}",
                                     data, "t"),
            "yes 64x64");
  EXPECT_EQ(sb::docs::renderTemplate("{{#rows}}{{name}} at {{scene.size}};{{/rows}}", data, "t"),
            "dom at 64x64;osm at 64x64;");
  // A value that is not there stops the refresh rather than printing a blank.
  EXPECT_THROW(sb::docs::renderTemplate("{{nope}}", data, "t"), sb::InputError);
  EXPECT_THROW(sb::docs::renderTemplate("{{#rows}}x", data, "t"), sb::InputError);
  EXPECT_THROW(sb::docs::renderTemplate("{{ms|furlong}}", json{{"ms", 1}}, "t"), sb::InputError);
}

TEST(DocsStore, LooseNumbersAreFoundOutsideBlocksAndAllowedOnlyWhereMarked) {
  auto loose = [](const std::string& text) { return sb::docs::looseNumbers(text, "x.md").size(); };
  // Planted: each is a measured number in prose or a table.
  EXPECT_EQ(loose("The frame took 12 ms here.\n"), 1u);
  EXPECT_EQ(loose("It needs 3.5 MiB and runs at 60 fps.\n"), 1u);
  EXPECT_EQ(loose("DOM 3 is 1.08x the time of no shadows.\n"), 1u);
  EXPECT_EQ(loose("Its visibility RMSE 0.0996 without.\n"), 1u);
  EXPECT_EQ(loose("about 25% less\n"), 1u);
  EXPECT_EQ(loose("| technique | frame ms |\n|---|---:|\n| dom | 363 |\n"), 1u);
  EXPECT_EQ(loose("| technique | error |\n|---|---|\n| dom | 0.0224 / 0.0310 |\n"), 1u);
  // Not measured numbers: counts, sizes of a setting, option values.
  EXPECT_EQ(loose("Run `--size 256x256 --repeat 3` on 2 cores with dom:layers=3.\n"), 0u);
  EXPECT_EQ(loose("| option | default |\n|---|---|\n| layers | 3 |\n"), 0u);
  // Inside a generated block, or marked as the paper's, a tolerance or a setting.
  EXPECT_EQ(loose("<!-- r/b:begin (written by strandbench docs refresh; do not edit) -->\n"
                  "took 12 ms\n<!-- r/b:end -->\n"),
            0u);
  EXPECT_EQ(loose("The paper gives 154 fps. <!-- not-measured (paper) -->\n"), 0u);
  EXPECT_EQ(loose("<!-- not-measured:begin (paper: Table 1) -->\n| OSM | 2.3 fps |\n"
                  "<!-- not-measured:end -->\nours: 4 ms\n"),
            1u);
  // A marker in a fenced code block is an example: no block, and it hides nothing.
  const std::string example =
      "```\n<!-- r/b:begin (written by strandbench docs refresh) -->\n"
      "took 12 ms\n<!-- r/b:end -->\n```\n";
  EXPECT_TRUE(sb::docs::markedBlocks(example, "x.md").empty());
  EXPECT_EQ(loose(example), 1u);
  // A marker with another reason allows nothing.
  EXPECT_EQ(loose("took 12 ms <!-- not-measured (I say so) -->\n"), 1u);
}

// Every block of the published pages is what its stored run renders, and no measured number
// stands outside a block; planted edits fail both.
TEST(DocsStore, PublishedPagesAreRenderedFromTheStoreWithNoLooseNumber) {
  const fs::path store = kRoot / "docs/results";
  int blocks = 0;
  for (const auto& page : sb::docs::docPages(kRoot)) {
    const std::string text = readFile(kRoot / page);
    EXPECT_EQ(sb::docs::refreshPage(text, store, page), text)
        << page
        << ": a block differs from what its stored run renders: run `build/strandbench "
           "docs refresh`";
    for (const auto& n : sb::docs::looseNumbers(text, page.generic_string()))
      ADD_FAILURE() << page.generic_string() << ":" << n.line << ": '" << n.match
                    << "' is a measured number outside a marked block (docs/measured-pages.md)";
    for (const auto& b : sb::docs::markedBlocks(text, page.generic_string()))
      blocks += b.fromStore();
  }
  EXPECT_GT(blocks, 0) << "no page renders a stored run";
  // Controls: a number typed into the README, and a number edited inside a block.
  const std::string readme = readFile(kRoot / "README.md");
  EXPECT_FALSE(
      sb::docs::looseNumbers(readme + "\nThe main command took 336 s.\n", "README.md").empty());
  const auto rb = sb::docs::markedBlocks(readme, "README.md");
  const auto it = std::find_if(rb.begin(), rb.end(), [](const auto& b) { return b.fromStore(); });
  ASSERT_NE(it, rb.end()) << "README.md renders no stored run";
  std::string edited = readme;
  const auto at = edited.find(it->content);
  ASSERT_NE(at, std::string::npos);
  edited.insert(at + it->content.size() - 1, " 1 s less.");
  EXPECT_NE(sb::docs::refreshPage(edited, store, "README.md"), edited);
}

// Two pages citing the same case render the same stored run: the same block on two pages
// prints the same values, in the published docs and in a fixture where one page was edited.
TEST(DocsStore, TwoPagesCitingTheSameCasePrintTheSameValues) {
  std::map<std::string, std::pair<fs::path, std::string>> seen;
  int shared = 0;
  for (const auto& page : sb::docs::docPages(kRoot)) {
    for (const auto& b : sb::docs::markedBlocks(readFile(kRoot / page), page.generic_string())) {
      if (!b.fromStore()) continue;
      // The provenance line links the run relative to its page; the rest is the case.
      const std::string values = b.content.substr(std::min(b.content.find('\n'), b.content.size()));
      auto [pos, fresh] = seen.try_emplace(b.name, page, values);
      if (fresh || pos->second.first == page) continue;
      ++shared;
      EXPECT_EQ(pos->second.second, values)
          << b.name << " differs between " << pos->second.first << " and " << page;
    }
  }
  EXPECT_GT(shared, 0) << "no case is cited by two pages";

  const fs::path dir = sbtest::tempDir("docs-same");
  writeFile(dir / "docs/results/r/meta.json",
            R"({"command": "x", "commit": "0123456789abcdef", "date": "2026-12-06 00:00 UTC"})");
  writeFile(dir / "docs/results/r/results.json", R"({"ms": 12.5})");
  writeFile(dir / "docs/results/r/blocks.json",
            R"({"blocks": {"case": {"template": "frame {{ms:.1f}} ms"}}})");
  const std::string begin =
      "<!-- r/case:begin (written by strandbench docs refresh; do not edit) -->\n";
  const std::string page = "# p\n\n" + begin + "frame 99.0 ms\n<!-- r/case:end -->\n";
  auto a = sb::docs::refreshPage(page, dir / "docs/results", "docs/a.md");
  auto b = sb::docs::refreshPage(page, dir / "docs/results", "README.md");
  const auto ba = sb::docs::markedBlocks(a, "a"), bb = sb::docs::markedBlocks(b, "b");
  ASSERT_EQ(ba.size(), 1u);
  ASSERT_EQ(bb.size(), 1u);
  EXPECT_NE(ba[0].content.find("frame 12.5 ms"), std::string::npos) << ba[0].content;
  EXPECT_EQ(ba[0].content.substr(ba[0].content.find('\n')),
            bb[0].content.substr(bb[0].content.find('\n')));
  fs::remove_all(dir);
}

// `docs refresh` on a repository: writes every block, changes nothing the second time;
// `--stale` lists nothing on the run's commit and the blocks depending on a technique once a
// file of its folder changes; a run recorded on a dirty tree is refused.
TEST(DocsStore, RefreshIsStableAndStaleFollowsTheDependencyPaths) {
  const fs::path dir = sbtest::tempDir("docs-stale");
  const std::string git = "git -C '" + dir.string() + "' -c user.name=t -c user.email=t@t ";
  writeFile(dir / "techniques/dom/dom.frag", "// a\n");
  writeFile(dir / "techniques/osm/osm.frag", "// b\n");
  writeFile(dir / "README.md", "# r\n");
  ASSERT_EQ(
      sh("git init -q '" + dir.string() + "' && " + git + "add -A && " + git + "commit -qm a"), 0);
  std::string commit;
  if (FILE* p = ::popen(("git -C '" + dir.string() + "' rev-parse HEAD").c_str(), "r")) {
    char buf[64] = {};
    if (std::fgets(buf, sizeof buf, p)) commit = std::string(buf).substr(0, 40);
    ::pclose(p);
  }
  ASSERT_EQ(commit.size(), 40u);
  writeFile(dir / "docs/results/dom-run/meta.json",
            R"({"command": "scripts/x.sh", "commit": ")" + commit +
                R"(", "date": "2026-12-06 00:00 UTC", "load_before": "0.1 0.1 0.1"})");
  writeFile(dir / "docs/results/dom-run/results.json", R"({"rows": [{"t": "dom", "ms": 3.25}]})");
  writeFile(dir / "docs/results/dom-run/blocks.json",
            R"({"depends": ["techniques/dom"], "blocks": {"times": {"template":
               ["| technique | ms |", "|---|---:|", "{{#rows}}| {{t}} | {{ms:.2f}} |", "{{/rows}}"]}}})");
  writeFile(dir / "README.md",
            "# r\n\n<!-- dom-run/times:begin (written by strandbench docs refresh; do not edit) "
            "-->\n<!-- dom-run/times:end -->\n");
  ASSERT_EQ(sh(git + "add -A && " + git + "commit -qm b"), 0);
  const std::string root = " --root '" + dir.string() + "'";

  auto r = sbtest::runCli("docs refresh" + root);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string once = readFile(dir / "README.md");
  EXPECT_NE(once.find("| dom | 3.25 |"), std::string::npos) << once;
  EXPECT_NE(once.find("on commit `" + commit.substr(0, 7) + "`"), std::string::npos) << once;
  r = sbtest::runCli("docs refresh" + root);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(readFile(dir / "README.md"), once) << "a second refresh changed the page";
  r = sbtest::runCli("docs check" + root);
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  ASSERT_EQ(sh(git + "commit -qam c"), 0);

  r = sbtest::runCli("docs refresh --stale" + root);
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(r.out, "");
  // Another technique's folder: not a dependency.
  writeFile(dir / "techniques/osm/osm.frag", "// b changed\n");
  r = sbtest::runCli("docs refresh --stale" + root);
  EXPECT_EQ(r.status, 0) << r.out;
  // The technique's own folder: committed or not, the block is listed.
  writeFile(dir / "techniques/dom/dom.frag", "// a changed\n");
  r = sbtest::runCli("docs refresh --stale" + root);
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("README.md: dom-run/times"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("techniques/dom/dom.frag"), std::string::npos) << r.out;
  ASSERT_EQ(sh(git + "commit -qam d"), 0);
  r = sbtest::runCli("docs refresh --stale" + root);
  EXPECT_EQ(r.status, 1) << r.out;

  // A hand edit inside the block: check fails, refresh restores it.
  std::string edited = once;
  edited.replace(edited.find("3.25"), 4, "2.00");
  writeFile(dir / "README.md", edited);
  r = sbtest::runCli("docs check" + root);
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("README.md: a block differs"), std::string::npos) << r.out;
  // A run recorded on a dirty tree is refused, and the page is left as it was.
  writeFile(dir / "docs/results/dom-run/meta.json",
            R"({"command": "x", "commit": ")" + commit + R"(", "date": "d", "dirty": true})");
  r = sbtest::runCli("docs refresh" + root);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("uncommitted changes"), std::string::npos) << r.err;
  EXPECT_EQ(readFile(dir / "README.md"), edited);
  fs::remove_all(dir);
}

// A figure page (its header names the commit that ran) is stale when a path its figure
// depends on changed since that commit, and only then.
TEST(DocsStore, StaleListsAFigurePageWhoseDependenciesChanged) {
  const fs::path dir = sbtest::tempDir("docs-stale-figure");
  const std::string sha = "0123456789abcdef0123456789abcdef01234567";
  const std::string body = "# F\n";
  writeFile(dir / "README.md", "# r\n");
  writeFile(
      dir / "docs/figures/occ-x.md",
      sb::report::figureHeader("occ-x", "strandbench figure occ-x --docs docs/figures", sha, body) +
          body);
  std::vector<std::string> asked;
  auto depends = [](const std::string& name) {
    return std::vector<std::string>{"suites/figures/" + name + ".json", "techniques/occupancy"};
  };
  auto changedIn = [&](const std::string& folder) {
    return [&, folder](const std::string& commit, const std::vector<std::string>& paths) {
      EXPECT_EQ(commit, sha);
      asked = paths;
      std::vector<std::string> out;
      for (const auto& p : paths)
        if (p == folder) out.push_back(folder + "/occupancy.frag");
      return out;
    };
  };
  auto stale = sb::docs::staleBlocks(dir, changedIn("techniques/osm"), depends);
  EXPECT_TRUE(stale.empty());
  EXPECT_EQ(asked, depends("occ-x"));
  stale = sb::docs::staleBlocks(dir, changedIn("techniques/occupancy"), depends);
  ASSERT_EQ(stale.size(), 1u);
  EXPECT_EQ(stale[0].page, fs::path("docs/figures/occ-x.md"));
  EXPECT_EQ(stale[0].block, "figure occ-x");
  EXPECT_EQ(stale[0].changed, std::vector<std::string>{"techniques/occupancy/occupancy.frag"});
  // Without the figures' dependencies (another tree than the binary's), no figure is listed.
  EXPECT_TRUE(sb::docs::staleBlocks(dir, changedIn("techniques/occupancy")).empty());
  fs::remove_all(dir);
}

}  // namespace
