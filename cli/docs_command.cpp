// `strandbench docs refresh` and `docs check`: the docs' marked blocks rendered from the
// results store (reports/docs_store.h); git is asked here, for `--stale`.
#include <cstdio>
#include <iostream>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "base/errors.h"
#include "cli/commands.h"
#include "harness/figure.h"
#include "reports/docs_store.h"
#include "reports/figure_report.h"
#include "reports/files.h"

namespace sb {

namespace fs = std::filesystem;

namespace {

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::vector<std::string> outputLines(const std::string& cmd, int* status = nullptr) {
  std::vector<std::string> out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) throw InputError("cannot run: " + cmd);
  std::string line;
  char buf[1024];
  while (std::fgets(buf, sizeof buf, p)) {
    line += buf;
    if (!line.empty() && line.back() == '\n') {
      line.pop_back();
      if (!line.empty()) out.push_back(line);
      line.clear();
    }
  }
  if (!line.empty()) out.push_back(line);
  const int raw = ::pclose(p);
  if (status) *status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return out;
}

// The files under `paths` that differ between `commit` and the working tree, untracked
// ones included: what changed since the run.
std::vector<std::string> changedSince(const fs::path& root, const std::string& commit,
                                      const std::vector<std::string>& paths) {
  const std::string git = "git -C " + quoted(root.string()) + " ";
  int status = 0;
  outputLines(git + "cat-file -e " + quoted(commit + "^{commit}") + " 2>/dev/null", &status);
  if (status != 0) return {"(commit " + commit + " is not in this repository)"};
  std::string spec;
  for (const auto& p : paths) spec += " " + quoted(p);
  if (spec.empty()) return {};
  auto out =
      outputLines(git + "diff --name-only " + quoted(commit) + " --" + spec + " 2>/dev/null");
  for (auto& f :
       outputLines(git + "ls-files --others --exclude-standard --" + spec + " 2>/dev/null"))
    out.push_back(f);
  return out;
}

// The commits a page's numbers were measured at: its stored runs', its figure header's, or
// the commit a script-written page names in its first lines.
std::set<std::string> measuredAt(const fs::path& root, const fs::path& page,
                                 const std::string& text) {
  std::set<std::string> out;
  for (const auto& b : docs::markedBlocks(text, page.generic_string())) {
    if (!b.fromStore()) continue;
    const std::string run = b.name.substr(0, b.name.rfind('/'));
    out.insert(docs::loadRun(root / "docs/results", run).meta["commit"].get<std::string>());
  }
  if (const auto h = report::parseFigureHeader(text)) out.insert(h->commit);
  if (docs::scriptWrittenPage(text)) {
    std::istringstream in(text);
    static const std::regex named(R"((commit|on) `?([0-9a-f]{7,40})\b)", std::regex::icase);
    std::string line;
    for (int i = 0; i < 6 && std::getline(in, line); ++i) {
      std::smatch m;
      if (std::regex_search(line, m, named)) out.insert(m[2].str());
    }
  }
  return out;
}

// The docs index's ages: per page, the commits between the oldest run it cites and HEAD.
std::string agesTable(const fs::path& root) {
  const std::string git = "git -C " + quoted(root.string()) + " ";
  const auto head = outputLines(git + "rev-parse --short HEAD 2>/dev/null");
  std::string out =
      "Each page's measurements and their age: the commits from the oldest run it cites to " +
      std::string(head.empty() ? "HEAD" : "`" + head[0] + "`") +
      ", the commit this was refreshed on (`strandbench docs refresh`).\n\n"
      "| page | measured at | age in commits |\n|---|---|---:|\n";
  for (const auto& page : docs::docPages(root)) {
    if (page.parent_path() == "docs/figures" || page == "README.md") continue;
    const auto commits = measuredAt(root, page, readTextFile(root / page));
    if (commits.empty()) continue;
    long age = -1;
    std::string shown;
    for (const auto& c : commits) {
      int status = 0;
      const auto n =
          outputLines(git + "rev-list --count " + quoted(c) + "..HEAD 2>/dev/null", &status);
      if (status == 0 && !n.empty()) age = std::max(age, std::stol(n[0]));
      shown += (shown.empty() ? "`" : ", `") + c.substr(0, 7) + "`";
    }
    const std::string name = page.generic_string();
    out += "| [" + name + "](" + name + ") | " + shown + " | " +
           (age < 0 ? std::string("?") : std::to_string(age)) + " |\n";
  }
  return out;
}

// README.md's docs-index block rewritten with the ages (git, so not part of `docs check`).
std::string withAges(const fs::path& root, const std::string& text) {
  static const std::regex block(
      R"((<!-- docs-index:begin[^\n]*-->\n)[\s\S]*?(<!-- docs-index:end -->))");
  if (!std::regex_search(text, block)) return text;
  const std::string table = agesTable(root);
  return std::regex_replace(text, block,
                            "$1" + std::regex_replace(table, std::regex("\\$"), "$$$$") + "$2",
                            std::regex_constants::format_first_only);
}

bool sameTree(const fs::path& root) {
  std::error_code ec;
  return fs::equivalent(root, SB_SOURCE_DIR, ec);
}

int refresh(const fs::path& root, bool write, std::ostream& os) {
  int changedPages = 0, blocks = 0, loose = 0;
  // Every page is rendered before any is written: a run missing from the store leaves all as
  // they were.
  std::vector<std::pair<fs::path, std::string>> writes;
  for (const auto& page : docs::docPages(root)) {
    const std::string text = readTextFile(root / page);
    std::string fresh = docs::refreshPage(text, root / "docs/results", page);
    if (write && page == "README.md") fresh = withAges(root, fresh);
    if (!write) {
      // What is generated but not from the store yet: named, so it is not forgotten.
      if (docs::scriptWrittenPage(text))
        os << page.generic_string() << ": written whole by a script, not from the store\n";
      for (const auto& b : docs::markedBlocks(text, page.generic_string()))
        if (!b.fromStore() && b.name != "not-measured" && b.name != "docs-index")
          os << page.generic_string() << ":" << b.line << ": block '" << b.name
             << "' written by a script, not from the store\n";
    }
    for (const auto& b : docs::markedBlocks(fresh, page.generic_string())) blocks += b.fromStore();
    if (fresh != text) {
      ++changedPages;
      if (write)
        writes.emplace_back(root / page, fresh);
      else
        os << page.generic_string() << ": a block differs from what its stored run renders\n";
    }
    for (const auto& n : docs::looseNumbers(fresh, page.generic_string())) {
      ++loose;
      os << page.generic_string() << ":" << n.line << ": measured number outside a marked block: '"
         << n.match << "'\n";
    }
  }
  for (const auto& [path, text] : writes) writeFileAtomic(path, text);
  if (write) {
    os << "docs refresh: " << blocks << " blocks rendered from docs/results, " << changedPages
       << " pages rewritten\n";
    return 0;
  }
  os << "docs check: " << blocks << " blocks, " << changedPages << " pages differ from the store, "
     << loose << " measured numbers outside marked blocks\n";
  return changedPages > 0 || loose > 0 ? 1 : 0;
}

}  // namespace

void registerDocsCommands(CLI::App& app) {
  auto* docs = app.add_subcommand("docs", "the docs' measured blocks and the results store");
  docs->require_subcommand(1);
  auto root = std::make_shared<std::string>(SB_SOURCE_DIR);
  auto stale = std::make_shared<bool>(false);
  auto* refreshCmd = docs->add_subcommand(
      "refresh", "render every marked block of README.md and docs/ from docs/results");
  refreshCmd->add_option("--root", *root, "the repository")->capture_default_str();
  refreshCmd->add_flag("--stale", *stale,
                       "write nothing: list the blocks whose dependency paths changed (git) "
                       "since their run's commit; exit 1 when any is listed");
  refreshCmd->footer(
      "A block is '<!-- RUN/BLOCK:begin ... -->' ... '<!-- RUN/BLOCK:end -->'; RUN is a folder "
      "of\ndocs/results (meta.json, results.json, blocks.json). docs/measured-pages.md says "
      "how a\nmeasured page is born.");
  refreshCmd->callback([=] {
    runGuarded("docs refresh", [&] {
      if (!*stale) return refresh(*root, true, std::cout);
      const auto list = docs::staleBlocks(
          *root,
          [&](const std::string& c, const std::vector<std::string>& p) {
            return changedSince(*root, c, p);
          },
          // Only for the tree this binary was built from: its figures and registry.
          sameTree(*root) ? docs::FigureDepends(figureDepends) : nullptr);
      for (const auto& s : list) {
        std::cout << s.page.generic_string() << ": " << s.block << " (run of "
                  << s.commit.substr(0, 7) << "):";
        for (const auto& f : s.changed) std::cout << " " << f;
        std::cout << "\n";
      }
      return list.empty() ? 0 : 1;
    });
  });
  auto checkRoot = std::make_shared<std::string>(SB_SOURCE_DIR);
  auto* checkCmd = docs->add_subcommand(
      "check",
      "exit 1 when a marked block differs from what its stored run renders, or a measured "
      "number stands outside a marked block");
  checkCmd->add_option("--root", *checkRoot, "the repository")->capture_default_str();
  checkCmd->callback(
      [=] { runGuarded("docs check", [&] { return refresh(*checkRoot, false, std::cout); }); });
}

}  // namespace sb
