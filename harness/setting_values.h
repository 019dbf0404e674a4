// The values of the render settings (harness/settings.h) in their three forms: CLI
// text, suite/manifest JSON and the canonical JSON the table stores, with each
// type's range check. Internal to harness/settings*.cpp: the table
// (settings.cpp) names a type per setting, this file knows the types.
#pragma once

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness/settings.h"

namespace sb::setting_values {

using ojson = nlohmann::ordered_json;

// A value's problem; the caller names the setting and the value.
struct Problem {
  std::string what;
};

constexpr uint32_t kMaxSize = 16384;
constexpr long long kMaxSamples = 1000000;
// Animation: every frame is rendered twice (technique and reference).
constexpr long long kMaxFrames = 1000;
// Extra lights: the key light and these make at most 8, each with its own shadow maps.
constexpr std::size_t kMaxExtraLights = 7;

// "a, b or c".
std::string joinOr(const std::vector<std::string>& v);
// The shortest text that reads back as the same float (values are stored as floats).
std::string numberText(double d);
ojson vec3Json(const glm::vec3& v);
glm::vec3 jsonVec3(const ojson& j);
// One extra light, canonical: {"type", "position" or "direction", "color", "intensity"}.
ojson lightJson(const std::string& type, const ojson& at, const ojson& color, double intensity);

// A setting's canonical value from its CLI text and from its suite/manifest JSON
// (Problem when malformed), and the CLI text of a canonical value.
ojson fromText(const Setting& s, const std::string& t);
ojson fromJson(const Setting& s, const ojson& v);
std::string textOf(const Setting& s, const ojson& v);
// "unknown <kind> 'value' (did you mean ...?); expected a, b or c".
std::string unknownChoice(const std::string& kind, const std::string& value,
                          const std::vector<std::string>& choices);
// The range and choices of a canonical value (Problem when outside).
void checkValue(const Setting& s, const ojson& v);
// "'text'" for strings, the JSON otherwise: how a suite or manifest value is quoted.
std::string jsonShown(const ojson& v);

}  // namespace sb::setting_values
