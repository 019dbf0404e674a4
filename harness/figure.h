// `strandbench figure NAME`: one command per figure and table of the papers. A figure is a
// suite file in suites/figures/NAME.json with two more keys (docs/suites-and-results.md
// "Figures"): "figure" (the paper's grid: rows, columns, each cell a case match) and "small"
// (overrides for a run in under a minute, `--small`). The command runs the suite (a sweep),
// then writes figure.png (the grid: our image and its error heatmap per cell, labelled),
// figure.md (our numbers beside the paper's) and figure.json beside the sweep's files.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "harness/backend_names.h"
#include "harness/run_options.h"

namespace sb {

struct FigureOptions {
  std::string name;    // a figure of figureNames(), or a path to a figure file (.json)
  bool small = false;  // apply the figure's "small" overrides
  std::string backend = defaultBackend();  // or kBothBackends
  std::string out;    // the folder written (default: figures/NAME, or NAME-small)
  RunOptions rounds;  // the sweep's rounds (--min-reps 0: the figure's repeat)
  std::string docs;   // also write docs/NAME.md and NAME.png into this folder (docs/figures)
  // The shared case store (harness/case_store.h; --cases, $SB_FIGURE_CASES): a case another
  // figure measured for the same key is taken from it, and this figure's cases are kept in it.
  std::string cases;
  bool progressBar = false;
};

// `--backend both`: every case on every API in one interleaved run; the page shows the paper's
// rows once per API and each paper table with a column per API.
inline constexpr const char* kBothBackends = "both";
// The APIs of a --backend value (a backend name or kBothBackends); InputError for another.
std::vector<std::string> figureBackends(const std::string& backend);

// suites/figures of the source tree.
std::filesystem::path figuresDir();
// Where the figures' models are: $SB_MODELS_DIR, else ../shared/models beside the source tree.
std::filesystem::path modelsDir();
// The figures' names (the stems of suites/figures/*.json), sorted.
std::vector<std::string> figureNames();

// The suite a figure runs: the file with its "small" overrides applied (when `small`), every
// case on `backend`'s APIs (figureBackends), and "../shared/models/" in scene specs replaced by
// modelsDir(). Throws InputError for an unknown name (listing the figures), a malformed figure, or
// a model that is missing (naming it).
nlohmann::ordered_json figureSuite(const std::string& name, bool small, const std::string& backend);

// Runs the figure into o.out (written in a temporary folder beside it and renamed into place:
// an existing figure folder there is replaced, anything else is refused): every case of the
// figure in one interleaved run (its paper tables compare cases of different groups), but the
// cases o.cases holds, which are taken from it. Returns 0, or 1 when a case failed (its cell
// says so).
// Refused with --docs (InputError) on a tree with uncommitted code (run_context.h
// uncommittedCode): the page names the commit that ran.
int runFigure(const FigureOptions& o);

// One row of a figure's paper table (its "tables" key): the row's label, the technique specs
// of its group (the group's "shadow" and "oit", else the suite defaults'), the paper's number
// as the paper gives it and its unit (fps, ms, MiB), and whether it is the table's baseline.
// The papers' numbers are kept there once: `bench-shadows` and `bench-oit` read them.
struct FigurePaperRow {
  std::string label, shadow = "none", oit = "none";
  std::optional<double> paper;
  std::string unit = "ms";
  bool baseline = false;
  // The paper's number as a time in ms (fps converted); nullopt for another unit or none.
  std::optional<double> paperMs() const;
};
struct FigurePaperTable {
  std::string figure, title, source;
  std::vector<FigurePaperRow> rows;
  // The first row whose technique spec (its oit where `oit`, else its shadow) is `spec`; InputError
  // naming the figure where there is none.
  const FigurePaperRow& row(const std::string& spec, bool oit = false) const;
};
// Table `index` of figure `name` (suites/figures/NAME.json); InputError where the figure has
// no such table or a row names a group the suite lacks.
FigurePaperTable figurePaperTable(const std::string& name, std::size_t index = 0);

// The paths a figure's page depends on, relative to the source tree: the figure file, the
// figure code, the folders of the techniques it names, the families' defaults and the exact
// references (`docs refresh --stale`).
std::vector<std::string> figureDepends(const std::string& name);

}  // namespace sb
