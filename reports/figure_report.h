// A paper figure (`strandbench figure`, docs/suites-and-results.md "Figures"): its grid of
// cells resolved against a sweep's results.json, figure.json and figure.md. The image of the
// grid (figure.png) is composed in cli/figure_command.cpp; this part needs only JSON.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace sb::report {

struct FigureCell {
  std::string row, column;
  std::string group;                       // the cell's group (its own, else the figure's)
  nlohmann::json match;                    // the cell's match (null: every case of the group)
  const nlohmann::json* result = nullptr;  // the matching result on the figure's backend
  std::string note;                        // why there is no result, or that it failed
  // The banding measure (bandingMeasure, imaging/metrics.h) of the cell's image against its
  // reference, where the figure command could read both.
  std::optional<double> banding;
};

// A claim of the paper about errors or memory, read from the figure block's "claims":
//   {"text": "...", "metric": "image_rmse" | "flip_mean" | "visibility_rmse" | "banding" |
//    "shadow_mib", "cell": [row, column], "than": [row, column] | "paper": VALUE,
//    "factor": F, "relation": "below" | "same", "tolerance": 0.05}
// The cell's metric against the other cell's times `factor` (default 1; 0.1: "an order of
// magnitude below"), or against the paper's own value (`paper`, in the metric's unit: MiB for
// shadow_mib) where there is no "than". "below": the cell's metric is below it; "same":
// within `tolerance` (relative) of it. Errors and memory are deterministic (the same run
// gives the same images and allocations), so the verdict is holds or fails, "-" where a
// cell has no value.
struct FigureErrorClaim {
  std::string text, metric, relation;
  int row = 0, column = 0, thanRow = 0, thanColumn = 0;
  double tolerance = 0.05;
  std::optional<double> paper;  // the paper's value, instead of another cell's
  double factor = 1.0;          // the other cell's value scaled
};

struct FigureGrid {
  std::string name, title, source, description, backend;
  std::vector<std::string> rows, columns;
  std::vector<std::vector<FigureCell>> cells;  // [row][column]
  std::vector<FigureErrorClaim> errorClaims;
};

// A cell's value of a claim's metric (image_rmse, flip_mean, visibility_rmse, banding,
// shadow_mib: the memory the shadow technique holds, MiB).
std::optional<double> cellMetric(const FigureCell& c, const std::string& metric);
// What a claim's cell is compared with: the paper's value, or the other cell's times factor.
std::optional<double> claimTarget(const FigureGrid& g, const FigureErrorClaim& c);
// holds / fails / "-" for one error or memory claim of the grid.
std::string errorClaimVerdict(const FigureGrid& g, const FigureErrorClaim& c);

// Checks a suite's "figure" block (title, rows, columns, cells: rows x columns, each cell
// {"group", "match"} or null) against the suite's groups; throws InputError naming `where`
// and the key.
void checkFigureBlock(const nlohmann::json& suite, const std::string& where);

// The figure of a results.json document (its "suite" holds the figure block, written by the
// figure command as "figure") resolved on `backend`: each cell's first matching result.
FigureGrid buildFigureGrid(const nlohmann::json& figure, const nlohmann::json& results,
                           const std::string& name, const std::string& backend);
// The same on several APIs (`figure --backend both`): the paper's rows once per API ("ROW
// (gl)", "ROW (vulkan)"), each error claim judged on each API's rows; backend "gl + vulkan".
FigureGrid buildFigureGrid(const nlohmann::json& figure, const nlohmann::json& results,
                           const std::string& name, const std::vector<std::string>& backends);

// figure.json: name, title, backend, rows, columns, and per cell its case id, images, frame
// time and errors (null where there is no result); `layout` (the grid image's geometry) is
// copied in as given.
nlohmann::json figureJson(const FigureGrid& g, const nlohmann::json& layout);

// figure.md: the generated header (figureHeader), title and source, how the run was made
// (command, commit, date, machine, device, load), the grid image, a table of every cell (our
// frame time with its 95% interval, image error against the exact reference, FLIP, banding,
// visibility error), the paper tables of the results (our numbers beside the paper's, with
// ratios) and the verdict on each of the paper's claims (figureClaims).
std::string renderFigureMarkdown(const FigureGrid& g, const nlohmann::json& results,
                                 const std::string& imageFile, const std::string& command);

// The first line of every figure.md (and of its copy in docs/figures/NAME.md):
//   <!-- strandbench figure NAME: written by `COMMAND`, commit SHA, digest HEX; do not edit -->
// HEX is figureDigest of everything after the line, so a table edited by hand, or copied from
// another run, no longer matches its header (tests/test_figure_docs.cpp).
std::string figureHeader(const std::string& name, const std::string& command,
                         const std::string& commit, const std::string& body);
// FNV-1a 64 of `body`, 16 hex digits.
std::string figureDigest(const std::string& body);
struct FigureHeader {
  std::string name, command, commit, digest;
};
// Parses the first line of a figure Markdown file; nullopt where it is not a figure header.
std::optional<FigureHeader> parseFigureHeader(const std::string& markdown);

// A paper's claim on one row of a paper table with a baseline: the row is faster (ratio
// below 1) or slower than the baseline, as the paper's own ratio says. Verdicts at 95%: in
// time, "holds" / "fails" / "undecided" by the bootstrap interval of our median ratio (the
// frame samples of both cases, paired by round; orderingVerdict) where both were timed in one
// interleaved run, else none; in work, by the fragment shader
// invocations and bytes ratios (counted, not sampled: "holds" or "fails" on their side of 1,
// "-" without counters). Results of several APIs make each claim once per API (the table's
// title names it).
struct FigureClaim {
  std::string table, row, baseline;
  double paperRatio = 0;
  std::optional<double> low, estimate, high;  // our ratio's interval (time)
  // Both cases timed in one interleaved run (their measurements' "interleaved_run"): only
  // then has the ratio an interval and a verdict in time; else the medians' ratio alone.
  bool oneRun = false;
  std::string time, fragments, bytes;  // verdicts
};
std::vector<FigureClaim> figureClaims(const nlohmann::json& results);

}  // namespace sb::report
