// A paper figure (`strandbench figure`, docs/suites-and-results.md "Figures"): its grid of
// cells resolved against a sweep's results.json, figure.json and figure.md. The image of the
// grid (figure.png) is composed in cli/figure_command.cpp; this part needs only JSON.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sb::report {

struct FigureCell {
  std::string row, column;
  std::string group;                       // the cell's group (its own, else the figure's)
  nlohmann::json match;                    // the cell's match (null: every case of the group)
  const nlohmann::json* result = nullptr;  // the matching result on the figure's backend
  std::string note;                        // why there is no result, or that it failed
};

struct FigureGrid {
  std::string name, title, source, description, backend;
  std::vector<std::string> rows, columns;
  std::vector<std::vector<FigureCell>> cells;  // [row][column]
};

// Checks a suite's "figure" block (title, rows, columns, cells: rows x columns, each cell
// {"group", "match"} or null) against the suite's groups; throws InputError naming `where`
// and the key.
void checkFigureBlock(const nlohmann::json& suite, const std::string& where);

// The figure of a results.json document (its "suite" holds the figure block, written by the
// figure command as "figure") resolved on `backend`: each cell's first matching result.
FigureGrid buildFigureGrid(const nlohmann::json& figure, const nlohmann::json& results,
                           const std::string& name, const std::string& backend);

// figure.json: name, title, backend, rows, columns, and per cell its case id, images, frame
// time and errors (null where there is no result); `layout` (the grid image's geometry) is
// copied in as given.
nlohmann::json figureJson(const FigureGrid& g, const nlohmann::json& layout);

// figure.md: title and source, the grid image, a table of every cell (our frame time, image
// error against the exact reference, FLIP, visibility error), and the paper tables of the
// results (our numbers beside the paper's, with ratios).
std::string renderFigureMarkdown(const FigureGrid& g, const nlohmann::json& results,
                                 const std::string& imageFile, const std::string& command);

}  // namespace sb::report
