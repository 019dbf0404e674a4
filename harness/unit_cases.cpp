#include "harness/unit_cases.h"

#include <algorithm>

#include "reports/files.h"

namespace sb {

std::vector<UnitCaseFile> unitCaseFiles(const std::filesystem::path& central) {
  namespace fs = std::filesystem;
  const fs::path techniques = fs::absolute(central).parent_path().parent_path() / "techniques";
  std::vector<UnitCaseFile> out;
  if (!fs::is_directory(techniques)) return out;
  for (const auto& e : fs::directory_iterator(techniques)) {
    const fs::path f = e.path() / "cases.json";
    if (fs::is_regular_file(f)) out.push_back({f, readTextFile(f)});
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.file < b.file; });
  return out;
}

const std::vector<std::string>& unitCaseKeys() {
  static const std::vector<std::string> keys = {"comment", "baselines", "quick"};
  return keys;
}

}  // namespace sb
