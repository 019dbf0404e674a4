// What the project writes and says names things by what they are (a feature, a
// technique, a paper), not by the number of the issue that asked for them: a
// reader of `bench-oit`'s output, a suite or a comment has no tracker to look
// the number up in. Every text file of the tree is read; README.md is left out
// (it is rewritten on its own).
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "test_util.h"

namespace fs = std::filesystem;

namespace {

TEST(Wording, NoIssueNumbersInSourcesOutputOrSuites) {
  const fs::path root = SB_SOURCE_DIR;
  const std::set<std::string> text = {
      ".cpp", ".h",   ".glsl",  ".vert", ".frag", ".comp", ".mesh", ".json", ".sh",    ".md",
      ".py",  ".txt", ".cmake", ".dict", ".supp", ".yml",  ".yaml", ".in",   ".sbatch"};
  // "issue" or "issues" and a number, with or without "#", either case.
  const std::regex number(R"([Ii]ssues? #?[0-9])");
  std::vector<std::string> found;
  int files = 0;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator();
       ++it) {
    const fs::path rel = fs::relative(it->path(), root);
    const std::string top = rel.begin()->string();
    if (it->is_directory() && (top.starts_with(".git") || top.starts_with("build") ||
                               top.starts_with("out") || rel.filename() == "corpus")) {
      it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file() || rel == "README.md") continue;
    const std::string name = rel.filename().string();
    if (!text.count(rel.extension().string()) && name != "CMakeLists.txt") continue;
    ++files;
    std::istringstream in(sbtest::readFile(it->path()));
    int line = 0;
    for (std::string l; std::getline(in, l);) {
      ++line;
      if (std::regex_search(l, number))
        found.push_back(rel.string() + ":" + std::to_string(line) + ": " + l.substr(0, 120));
    }
  }
  EXPECT_GT(files, 100) << "the tree was not found under " << root;
  std::string list;
  for (const auto& f : found) list += "\n  " + f;
  EXPECT_TRUE(found.empty()) << found.size() << " lines name an issue by number:" << list;
}

// The relative links and images of `markdown` (a page in `dir`) that name no file: fenced code
// and code spans are skipped, web and mail addresses and same-page anchors are not checked.
std::vector<std::string> brokenLinks(const std::string& markdown, const fs::path& dir) {
  static const std::regex link(R"(!?\[[^\]]*\]\(([^)\s]+)(\s+"[^"]*")?\))");
  static const std::regex span("`[^`]*`");
  std::vector<std::string> broken;
  std::istringstream in(markdown);
  bool fenced = false;
  for (std::string l; std::getline(in, l);) {
    if (l.find("```") != std::string::npos) fenced = !fenced;
    if (fenced) continue;
    const std::string text = std::regex_replace(l, span, "");
    for (std::sregex_iterator m(text.begin(), text.end(), link), end; m != end; ++m) {
      std::string target = (*m)[1];
      if (target.starts_with("http:") || target.starts_with("https:") ||
          target.starts_with("mailto:") || target.starts_with("#"))
        continue;
      target = target.substr(0, target.find('#'));
      if (!fs::exists(dir / target)) broken.push_back(m->str());
    }
  }
  return broken;
}

// Every relative link and image of README.md and docs/ names a file that exists (a page moved
// or an image linked from the wrong folder shows as a broken link to a reader).
TEST(Wording, EveryRelativeLinkInTheDocsNamesAFile) {
  const fs::path root = SB_SOURCE_DIR;
  // The control: a page beside view.png that links it from the wrong folder, and a missing page.
  const auto control = brokenLinks(
      "![a](docs/view.png) [b](view.png) [c](nope.md#x) `[d](e.md)` [f](#g)", root / "docs");
  EXPECT_EQ(control, (std::vector<std::string>{"![a](docs/view.png)", "[c](nope.md#x)"}));
  std::vector<fs::path> pages{root / "README.md"};
  for (const auto& e : fs::recursive_directory_iterator(root / "docs"))
    if (e.path().extension() == ".md") pages.push_back(e.path());
  EXPECT_GT(pages.size(), 10u) << "the docs were not found under " << root;
  std::string list;
  for (const fs::path& page : pages)
    for (const std::string& b : brokenLinks(sbtest::readFile(page), page.parent_path()))
      list += "\n  " + fs::relative(page, root).string() + ": " + b;
  EXPECT_TRUE(list.empty()) << "links to no file:" << list;
}

}  // namespace
