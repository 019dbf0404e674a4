// Suites (suites/*.json): groups of cases swept over axes, expanded into one
// RenderRequest per case and backend. The format is in docs/suites-and-results.md.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness/render.h"

namespace sb {

struct SweepCase {
  std::string id;  // "<group>/<axis>=<value>,...,backend=<backend>"
  std::string group;
  std::string stem;               // file-system safe and unique: the case's file names
  int index = 0;                  // order in the suite
  nlohmann::ordered_json params;  // axis -> value (backend included)
  RenderRequest request;
};

struct Suite {
  std::string name, description, file;
  nlohmann::ordered_json doc;     // the suite as read
  nlohmann::ordered_json groups;  // [{name, description, axes}]
  std::vector<SweepCase> cases;
};

// Parses and expands a suite; every case's settings and technique specs are
// checked here, before anything runs. Throws InputError naming the file and,
// for malformed JSON, the line and column.
Suite parseSuite(const std::string& text, const std::string& file);
Suite loadSuite(const std::string& path);

// "<id with unsafe characters replaced>-<8 hex digits of a hash of the id>"
std::string caseStem(const std::string& id);

}  // namespace sb
