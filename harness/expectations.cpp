#include "harness/expectations.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <set>

#include "harness/json_keys.h"
#include "reports/json_file.h"

namespace sb {

namespace fs = std::filesystem;
using nlohmann::json;

bool Expectation::matches(const std::string& name, const std::string& label) const {
  return caseName == name && (comparison.empty() || comparison == label);
}

const Expectation* Expectations::find(const std::vector<Expectation>& list, const std::string& name,
                                      const std::string& label) {
  for (const Expectation& e : list)
    if (e.matches(name, label)) return &e;
  return nullptr;
}

std::string driverKey(const std::string& driver) {
  if (driver.find('/') == std::string::npos) return driver;
  // A driver given by path: its folder's name (drivers/mesa-25.0 -> mesa-25.0).
  fs::path p = fs::path(driver).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  return p.filename().string();
}

fs::path expectationsFile(const fs::path& baselines, const std::string& driver) {
  return baselines / "expectations" / (driverKey(driver) + ".json");
}

Expectations loadExpectations(const fs::path& file, const Manifest& m) {
  if (!fs::is_regular_file(file)) throw InputError(file.string() + ": no such expectations file");
  const json root = readJsonFile<json>(file);
  const std::string where = file.string();
  checkKeys(root, {"comment", "driver", "failures", "flakes", "skips"}, where, "key");
  Expectations x;
  x.file = file;
  if (!root.contains("driver") || !root["driver"].is_string())
    throw InputError(where + ": \"driver\" (a string: the driver it describes) is required");
  x.driver = root["driver"];
  std::set<std::pair<std::string, std::string>> seen;  // (case, comparison)
  for (auto [key, list] : {std::pair{"failures", &x.failures}, std::pair{"flakes", &x.flakes},
                           std::pair{"skips", &x.skips}}) {
    if (!root.contains(key)) continue;
    if (!root[key].is_array()) throw InputError(where + ": \"" + key + "\" must be an array");
    int index = 0;
    for (const json& e : root[key]) {
      const std::string at = where + ": " + key + "[" + std::to_string(index++) + "]";
      checkKeys(e, {"case", "comparison", "reason"}, at, "key");
      auto text = [&](const char* k, bool required) -> std::string {
        if (!e.contains(k)) {
          if (required) throw InputError(at + ": \"" + k + "\" is required");
          return "";
        }
        if (!e[k].is_string() || e[k].get<std::string>().empty())
          throw InputError(at + ": \"" + k + "\" must be a non-empty string");
        return e[k];
      };
      Expectation ex{text("case", true), text("comparison", false), text("reason", true)};
      const auto c = std::find_if(m.cases.begin(), m.cases.end(),
                                  [&](const BaselineCase& b) { return b.name == ex.caseName; });
      if (c == m.cases.end())
        throw InputError(at + ": no case '" + ex.caseName + "' in " + m.file.string());
      // The comparisons the case makes: each backend, and each further one against the first.
      std::vector<std::string> labels = c->backends;
      for (std::size_t i = 1; i < c->backends.size(); ++i)
        labels.push_back(c->backends[0] + "-vs-" + c->backends[i]);
      if (!ex.comparison.empty() &&
          std::find(labels.begin(), labels.end(), ex.comparison) == labels.end())
        throw InputError(at + ": " + unknownNameMessage("comparison", ex.comparison, labels) +
                         " (case '" + ex.caseName + "')");
      for (const std::string& l : labels)
        if ((ex.comparison.empty() || ex.comparison == l) && !seen.insert({ex.caseName, l}).second)
          throw InputError(at + ": case '" + ex.caseName + "', comparison " + l +
                           " is listed twice");
      list->push_back(std::move(ex));
    }
  }
  return x;
}

}  // namespace sb
