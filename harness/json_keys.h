// The keys of a JSON object checked against those a format allows, for the harness's
// JSON inputs (suites, the baselines manifest); reading them is reports/json_file.h.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "base/errors.h"
#include "base/options.h"

namespace sb {

// Throws InputError "<where>: expected a JSON object" when `obj` is not one, and
// "<where>: unknown <kind> '<key>' (did you mean '<closest>'?); valid <kind>s: ..." for its
// first key not in `valid`. Json: nlohmann::json or nlohmann::ordered_json.
template <class Json>
void checkKeys(const Json& obj, const std::vector<std::string>& valid, const std::string& where,
               const std::string& kind) {
  if (!obj.is_object()) throw InputError(where + ": expected a JSON object");
  for (const auto& [key, value] : obj.items()) {
    if (std::find(valid.begin(), valid.end(), key) == valid.end())
      throw InputError(where + ": " + unknownNameMessage(kind, key, valid));
  }
}

}  // namespace sb
