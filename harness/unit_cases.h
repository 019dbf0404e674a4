// The cases a unit's folder carries (techniques/<folder>/cases.json), merged at load into the
// central files that ask for them ("unit_cases": true in baselines/manifest.json and
// suites/quick.json), so that a new technique edits neither central file and a copied folder
// brings its cases along. A folder's file: {"comment": "...", "baselines": [manifest cases],
// "quick": [quick-suite groups]}, each part optional.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace sb {

struct UnitCaseFile {
  std::filesystem::path file;
  std::string text;  // the JSON, parsed by the central file's reader
};

// The unit folders' case files of the tree the central file belongs to
// (<central>/../../techniques/*/cases.json), in folder order.
std::vector<UnitCaseFile> unitCaseFiles(const std::filesystem::path& central);

// The keys a unit's case file may hold.
const std::vector<std::string>& unitCaseKeys();

}  // namespace sb
