// JSON read from text or a file, with one form of message for every reader (suites, the
// baselines manifest, results.json and case files): the file, and the line and column
// where invalid JSON stops.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace sb {

// `text` parsed as Json (nlohmann::json or nlohmann::ordered_json); `file` names it in
// messages. Throws InputError "<file>:<line>:<column>: not valid JSON at line <line>,
// column <column>: <what is wrong>" (1-based), or "<file>: not valid JSON: <what>" for a
// number out of range.
template <class Json = nlohmann::json>
Json parseJson(const std::string& text, const std::string& file);

// The whole file parsed as above; throws InputError naming the file when it cannot be read.
template <class Json = nlohmann::json>
Json readJsonFile(const std::filesystem::path& file);

extern template nlohmann::json parseJson<nlohmann::json>(const std::string&, const std::string&);
extern template nlohmann::ordered_json parseJson<nlohmann::ordered_json>(const std::string&,
                                                                         const std::string&);
extern template nlohmann::json readJsonFile<nlohmann::json>(const std::filesystem::path&);
extern template nlohmann::ordered_json readJsonFile<nlohmann::ordered_json>(
    const std::filesystem::path&);

}  // namespace sb
