#include "reports/json_file.h"

#include <algorithm>

#include "base/errors.h"
#include "reports/files.h"

namespace sb {

namespace {

// nlohmann's message without its "[json.exception.parse_error.101] parse error at line L,
// column C: " prefix (the position is given once, ours).
std::string detail(const nlohmann::json::exception& e) {
  std::string s = e.what();
  if (s.starts_with("[json.exception.")) {
    if (const auto p = s.find("] "); p != std::string::npos) s.erase(0, p + 2);
  }
  if (s.starts_with("parse error")) {
    if (const auto p = s.find(": "); p != std::string::npos) s.erase(0, p + 2);
  }
  return s;
}

}  // namespace

template <class Json>
Json parseJson(const std::string& text, const std::string& file) {
  try {
    return Json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte: 1-based offset of the character where parsing stopped.
    const std::size_t end = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, text.size());
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < end; ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    const std::string l = std::to_string(line), c = std::to_string(column);
    throw InputError(file + ":" + l + ":" + c + ": not valid JSON at line " + l + ", column " + c +
                     ": " + detail(e));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file + ": not valid JSON: " + detail(e));
  }
}

template <class Json>
Json readJsonFile(const std::filesystem::path& file) {
  return parseJson<Json>(readTextFile(file), file.string());
}

template nlohmann::json parseJson<nlohmann::json>(const std::string&, const std::string&);
template nlohmann::ordered_json parseJson<nlohmann::ordered_json>(const std::string&,
                                                                  const std::string&);
template nlohmann::json readJsonFile<nlohmann::json>(const std::filesystem::path&);
template nlohmann::ordered_json readJsonFile<nlohmann::ordered_json>(const std::filesystem::path&);

}  // namespace sb
