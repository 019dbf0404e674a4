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
  const std::set<std::string> text = {".cpp",  ".h",    ".glsl", ".vert", ".frag", ".comp",
                                      ".json", ".sh",   ".md",   ".py",   ".txt",  ".cmake",
                                      ".dict", ".supp", ".yml",  ".yaml", ".in",   ".sbatch"};
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

}  // namespace
