// The reports of a sweep: results.json (docs/suites-and-results.md) turned into
// results.csv, report.md and a self-contained, offline report.html.
#pragma once

#include <filesystem>
#include <nlohmann/json_fwd.hpp>

namespace sb {

// Writes dir/results.csv (one row per result), dir/passes.csv (one row per case
// and pass), dir/cost_model.json (reports/cost_model.h), dir/report.md (context,
// paper tables, one table per group, passes, cost model, warnings) and
// dir/report.html (the same plus
// inline-SVG charts and the images named by results' `images`, relative to dir,
// embedded as data URIs). Each file is written as NAME.tmp and renamed into
// place. Missing keys, null (NaN, Inf) values and an empty results array are
// shown as absent values. Throws InputError when `dir` is missing or not
// writable, or `results` is not a JSON object.
void writeReports(const nlohmann::json& results, const std::filesystem::path& dir);

}  // namespace sb
