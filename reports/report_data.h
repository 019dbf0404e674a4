// Internals of the report writer: tolerant access to a results document and the
// tables that report.md and report.html both show (reports/report_writer.h).
#pragma once

#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "reports/cost_model.h"

namespace sb::report {

using nlohmann::json;

// --- JSON access that tolerates missing keys, wrong types and null (NaN, Inf) ---

// The value at `path` (object keys), or nullptr where a key is missing or a
// step is not an object.
const json* find(const json& j, std::initializer_list<std::string_view> path);
// A finite number (a JSON number or a string holding one), else nullopt.
std::optional<double> number(const json* j);
// Strings as they are, numbers in shortest round-trip form, booleans as
// true/false, "" for null or missing, anything else as compact JSON.
std::string text(const json* j);

// v with `digits` significant digits in fixed notation (1.90, 154, 0.00123).
std::string formatSig(double v, int digits = 3);
// A count for reading: "950", "288 k", "1.2 M", "3.4 G".
std::string formatCount(double v);
// Bytes for reading: "256 B", "320 KiB", "16 MiB", "1.5 GiB".
std::string formatBytes(double v);
// Shortest text that reads back as v.
std::string shortest(double v);
// The text of a cell with no value.
inline constexpr const char* kNone = "–";

// --- one result ---

std::string caseId(const json& r);
std::string groupOf(const json& r);
std::string backendOf(const json& r);  // `backend`, else case.params.backend
// "WxH" from `size` [w, h], "" when absent.
std::string sizeOf(const json& r);
// Technique label: "shadow SPEC, oit SPEC".
std::string techniqueOf(const json& r);
// The reason a case failed (its `failed.reason`), "" for a case that ran.
std::string failureOf(const json& r);
// The technique a case is about, short (a chart's point label): the
// transparency technique with its shadow technique ("wboit + dom:layers=3")
// when oit is not none, else the shadow technique; with `nameOit`, "none + dom"
// then, so that a point without transparency is not read as one with a
// transparency technique of the shadow's name ("occupancy" beside
// "occupancy + occupancy"). Likewise with `nameShadow`, "abuffer + none" for a
// point without shadows beside "abuffer + dom" ones, not "abuffer".
std::string shortTechniqueOf(const json& r, bool nameOit = false, bool nameShadow = false);
// Whether any of `results` has a transparency technique / a shadow technique: the
// `nameOit` / `nameShadow` of the labels shown together with theirs.
bool anyTransparency(const std::vector<const json*>& results);
bool anyShadow(const std::vector<const json*>& results);
// The results' "scene | size | backend": cases whose times and errors compare.
std::string comparableKey(const json& r);
// Median frame time in ms / total memory in MiB, when present and finite.
std::optional<double> frameMs(const json& r);
std::optional<double> memoryMiB(const json& r, const char* key = "total_bytes");
// A work counter of the frame (frame_work.key; null where the device has no queries), and
// its bytes written, read and bound as storage together.
std::optional<double> frameCounter(const json& r, const char* key);
std::optional<double> frameBytes(const json& r);

// --- tables ---

struct Cell {
  std::string text;
  bool number = false;  // right-aligned
};

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<Cell>> rows;
};

struct PaperTable {
  std::string title;
  std::string about;  // source, group, metric, how ratios are formed
  Table table;
  std::vector<std::string> notes;  // rows without results, ambiguous matches
};

struct Group {
  std::string name, description;
  std::vector<std::string> params;  // case.params keys: sorted, backend last
  std::vector<const json*> results;
  Table table;
  Table passes;  // one row per case and pass: its median time and work (no rows: no passes)
};

// The work counters of a pass (`work`) or frame (`frame_work`) that the reports show:
// key, column header, and whether the value is bytes.
struct WorkColumn {
  const char* key;
  const char* header;
  bool bytes;
};
inline constexpr WorkColumn kWorkColumns[] = {{"fragment_invocations", "Fragments", false},
                                              {"vertex_invocations", "Vertices", false},
                                              {"samples_passed", "Samples passed", false},
                                              {"compute_invocations", "Compute", false},
                                              {"draws", "Draws", false},
                                              {"dispatches", "Dispatches", false},
                                              {"bytes_written", "Written", true},
                                              {"bytes_read", "Read", true},
                                              {"bytes_storage", "Storage", true}};

// Per scene, size and backend: for each frame-time budget (the frame times of
// the Pareto frontiers), the most accurate technique that fits it.
struct BudgetTable {
  std::string key;  // comparableKey
  Table table;
};

// A case rendered under animation (render --animate): its flicker and per-frame errors.
struct Animation {
  const json* result = nullptr;
  std::string caseId, technique, spec;  // spec: "light-orbit:frames=8,degrees=30"
};

struct Warning {
  std::string caseId, message;
};

struct ReportData {
  std::string title, description;
  std::vector<std::pair<std::string, std::string>> context;  // label, value
  Table devices;
  std::vector<PaperTable> paperTables;
  std::vector<Group> groups;
  std::vector<BudgetTable> budgets;
  std::vector<Animation> animations;
  Table animationTable;  // one row per animated case
  std::vector<Warning> warnings;
  // Cases that did not finish (a sweep records the reason: out of memory, a
  // device error) and keep going: shown as failed in every table.
  std::vector<Warning> failures;
  std::vector<const json*> results;   // in document order
  std::vector<CostModel> costModels;  // per backend and device
};

// The tables of a cost model: its terms with coefficients, and its cases by
// measured / predicted.
Table costTermsTable(const CostModel& m);
Table costCasesTable(const CostModel& m);

// Throws InputError when `doc` is not a JSON object; anything missing inside it
// is shown as absent.
ReportData buildReport(const json& doc);
// The names of the further references the results were compared with
// (error.<name> with a reference spec: "aa"), in the order first met.
std::vector<std::string> moreReferenceNames(const std::vector<const json*>& results);

// Whether result r is of `group` and its case.params hold every key and value of `match`
// (an object; null or absent matches all): a paper table row's and a figure cell's match.
bool matches(const json& r, const std::string& group, const json* match);
// Markdown inline text with markup characters escaped, and a table (report.md, figure.md).
std::string md(const std::string& s);
void mdTable(std::ostream& o, const Table& t);

std::string renderCsv(const ReportData& data);
// passes.csv: one row per case and pass, with the pass's median time and work.
std::string renderPassesCsv(const ReportData& data);
std::string renderMarkdown(const ReportData& data);

// The explanations and headings that report.md and report.html share.
inline constexpr const char* kPassesAbout =
    "Per case and pass: how often the pass ran in a frame, its median time, and its exact work: "
    "shader invocations and samples passed from the device's queries, draws, dispatches and "
    "the bytes the pass writes, reads and binds as storage from the front end (– where the "
    "device has no queries or the result predates the counters).";
inline constexpr const char* kCostModelAbout =
    "Per backend and device, the median frame time fitted against the frame's work with "
    "non-negative least squares: ms per million fragments, vertices and compute invocations, "
    "per MiB written, read or bound as storage, per pass execution, and a constant. Each case's "
    "prediction comes from the fit over the other cases; a case measured over 2x its prediction, "
    "by more than 3 robust spreads of the residuals, is marked \"inefficient: look at it\": "
    "its time is not explained by its work, and the fit is redone without it so that it does "
    "not inflate the others' costs. Counters that grow together (vertices and fragments) share "
    "their time between them: a coefficient describes this run, not the device.";
std::string costModelTitle(const CostModel& m);    // "gl on llvmpipe (...)"
std::string costModelSummary(const CostModel& m);  // "R² = 0.93 over 48 cases." or the note
// Images named by results' `images` are read relative to `dir` and embedded.
std::string renderHtml(const ReportData& data, const std::filesystem::path& dir);

}  // namespace sb::report
