// Suites (suites/*.json): groups of cases swept over axes, expanded into one
// RenderRequest per case and backend. The format is in docs/suites-and-results.md.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "base/errors.h"
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

// Opens and reads every file the cases' scenes name (path=, mesh=), each once, so that a
// missing, truncated or unreadable file refuses a sweep before anything runs. Throws InputError
// naming the suite, the case and the file's problem. A scene too large for the host's memory
// is left to its case (a failed case, as at run time).
void checkSuiteFiles(const std::string& suiteFile, const std::vector<const SweepCase*>& cases);

// The drivers scripts/drivers.sh fetches. A suite may name one that is not installed (its cases
// are not run); any other name that is not a driver is refused as a mistake.
bool fetchableDriver(const std::string& name);

// A part the case needs that this machine lacks, known before it runs: its driver is not
// installed (the message says what fetches it). Parts known only once a device is made (ray
// queries) are an UnavailableError from the run itself. nullopt when nothing is missing.
std::optional<UnavailableError> missingPart(const SweepCase& c);

// "<id with unsafe characters replaced>-<8 hex digits of a hash of the id>"
std::string caseStem(const std::string& id);

}  // namespace sb
