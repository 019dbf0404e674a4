// The JSON helpers every reader uses (reports/json_file.h, harness/json_keys.h): messages
// name the file, and the line and column where invalid JSON stops.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness/json_keys.h"
#include "reports/json_file.h"
#include "test_util.h"

namespace {

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const sb::InputError& e) {
    return e.what();
  }
  return "no InputError";
}

}  // namespace

TEST(JsonFile, ParsesBothKindsOfDocument) {
  EXPECT_EQ(sb::parseJson(R"({"b": 1, "a": 2})", "x.json")["a"], 2);
  const auto ordered = sb::parseJson<nlohmann::ordered_json>(R"({"b": 1, "a": 2})", "x.json");
  EXPECT_EQ(ordered.begin().key(), "b");  // document order kept
}

TEST(JsonFile, InvalidJsonNamesFileLineAndColumn) {
  EXPECT_EQ(messageOf([] { (void)sb::parseJson("{\n  \"a\": [,]\n}", "x.json"); }),
            "x.json:2:9: not valid JSON at line 2, column 9: syntax error while parsing value - "
            "unexpected ','; expected '[', '{', or a literal");
  EXPECT_EQ(messageOf([] { (void)sb::parseJson<nlohmann::ordered_json>("", "e.json"); }),
            "e.json:1:1: not valid JSON at line 1, column 1: syntax error while parsing value - "
            "unexpected end of input; expected '[', '{', or a literal");
  // Not a parse error to nlohmann (out_of_range), still bad input.
  EXPECT_EQ(messageOf([] { (void)sb::parseJson(R"({"a": 1e999})", "big.json"); }),
            "big.json: not valid JSON: number overflow parsing '1e999'");
}

TEST(JsonFile, ReadsFilesAndNamesUnreadableOnes) {
  const auto dir = sbtest::tempDir("jsonfile");
  std::ofstream(dir / "ok.json") << R"({"results": []})";
  EXPECT_TRUE(sb::readJsonFile(dir / "ok.json")["results"].is_array());
  std::ofstream(dir / "bad.json") << "{\"results\": [";
  sbtest::expectInputError([&] { (void)sb::readJsonFile(dir / "bad.json"); },
                           {(dir / "bad.json").string() + ":1:14: not valid JSON at line 1"});
  sbtest::expectInputError([&] { (void)sb::readJsonFile(dir / "missing.json"); },
                           {(dir / "missing.json").string(), "cannot read"});
  std::filesystem::remove_all(dir);
}

TEST(JsonFile, UnknownKeysGetTheClosestValidName) {
  const std::vector<std::string> valid = {"name", "groups"};
  EXPECT_NO_THROW(sb::checkKeys(nlohmann::json{{"name", "x"}}, valid, "s.json", "suite key"));
  EXPECT_EQ(messageOf([&] {
              sb::checkKeys(nlohmann::ordered_json{{"grups", 1}}, valid, "s.json", "suite key");
            }),
            "s.json: unknown suite key 'grups' (did you mean 'groups'?); valid suite keys: name, "
            "groups");
  EXPECT_EQ(messageOf([&] { sb::checkKeys(nlohmann::json::array(), valid, "s.json", "key"); }),
            "s.json: expected a JSON object");
}
