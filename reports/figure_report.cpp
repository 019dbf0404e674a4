#include "reports/figure_report.h"

#include <cmath>
#include <set>
#include <sstream>

#include "base/errors.h"
#include "reports/report_data.h"

namespace sb::report {

namespace {

void stringList(const json& j, const char* key, const std::string& where,
                std::vector<std::string>& out) {
  const json* v = find(j, {key});
  if (!v || !v->is_array() || v->empty())
    throw InputError(where + ": \"figure\"." + key + " must be a non-empty array of labels");
  for (const json& x : *v) {
    if (!x.is_string()) throw InputError(where + ": \"figure\"." + key + " holds a non-string");
    out.push_back(x);
  }
}

std::optional<double> at(const json* r, std::initializer_list<std::string_view> path) {
  return r ? number(find(*r, path)) : std::nullopt;
}

Cell numCell(std::optional<double> v, int digits = 3) {
  if (!v) return {kNone, true};
  return {formatSig(*v, digits), true};
}

// A count (segments) in full: 150000, not 1.50e+05.
Cell countCell(std::optional<double> v) {
  if (!v) return {kNone, true};
  return {std::to_string(std::llround(*v)), true};
}

}  // namespace

void checkFigureBlock(const json& suite, const std::string& where) {
  const json* f = find(suite, {"figure"});
  if (!f || !f->is_object())
    throw InputError(where +
                     ": \"figure\" (an object with title, rows, columns, cells) is required");
  for (const auto& [key, value] : f->items()) {
    static const std::set<std::string> known = {"title",   "source", "group",  "rows",
                                                "columns", "cells",  "models", "note"};
    if (!known.contains(key))
      throw InputError(where + ": \"figure\" has an unknown key \"" + key +
                       "\" (known: title, source, group, rows, columns, cells, models, note)");
  }
  if (text(find(*f, {"title"})).empty())
    throw InputError(where + ": \"figure\".title (a string) is required");
  std::vector<std::string> rows, columns;
  stringList(*f, "rows", where, rows);
  stringList(*f, "columns", where, columns);
  std::set<std::string> groups;
  if (const json* gs = find(suite, {"groups"}); gs && gs->is_array())
    for (const json& g : *gs) groups.insert(text(find(g, {"name"})));
  const std::string figureGroup = text(find(*f, {"group"}));
  const json* cells = find(*f, {"cells"});
  if (!cells || !cells->is_array() || cells->size() != rows.size())
    throw InputError(where + ": \"figure\".cells must be an array of " +
                     std::to_string(rows.size()) + " rows (one per label of \"rows\")");
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const json& row = (*cells)[r];
    if (!row.is_array() || row.size() != columns.size())
      throw InputError(where + ": \"figure\".cells row " + std::to_string(r + 1) + " (\"" +
                       rows[r] + "\") must hold " + std::to_string(columns.size()) +
                       " cells (one per label of \"columns\")");
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const json& cell = row[c];
      if (cell.is_null()) continue;  // the paper has no image there
      const std::string cw = where + ": \"figure\".cells[" + std::to_string(r) + "][" +
                             std::to_string(c) + "] (" + rows[r] + ", " + columns[c] + ")";
      if (!cell.is_object()) throw InputError(cw + ": a cell is {\"group\", \"match\"} or null");
      std::string g = text(find(cell, {"group"}));
      if (g.empty()) g = figureGroup;
      if (!groups.contains(g))
        throw InputError(cw + ": group \"" + g + "\" is not a group of the suite");
      const json* m = find(cell, {"match"});
      if (m && !m->is_object()) throw InputError(cw + ": \"match\" must be an object");
    }
  }
}

FigureGrid buildFigureGrid(const json& figure, const json& results, const std::string& name,
                           const std::string& backend) {
  FigureGrid g;
  g.name = name;
  g.backend = backend;
  g.title = text(find(figure, {"title"}));
  g.source = text(find(figure, {"source"}));
  g.description = text(find(figure, {"note"}));
  for (const json& x : figure.value("rows", json::array())) g.rows.push_back(text(&x));
  for (const json& x : figure.value("columns", json::array())) g.columns.push_back(text(&x));
  const std::string figureGroup = text(find(figure, {"group"}));
  const json* rs = find(results, {"results"});
  const json* cells = find(figure, {"cells"});
  for (std::size_t r = 0; r < g.rows.size(); ++r) {
    std::vector<FigureCell> row;
    for (std::size_t c = 0; c < g.columns.size(); ++c) {
      FigureCell cell;
      cell.row = g.rows[r];
      cell.column = g.columns[c];
      const json* jc = cells && cells->is_array() && r < cells->size() && (*cells)[r].is_array() &&
                               c < (*cells)[r].size()
                           ? &(*cells)[r][c]
                           : nullptr;
      if (!jc || jc->is_null()) {
        cell.note = "no image in the paper";
        row.push_back(std::move(cell));
        continue;
      }
      cell.group = text(find(*jc, {"group"}));
      if (cell.group.empty()) cell.group = figureGroup;
      if (const json* m = find(*jc, {"match"})) cell.match = *m;
      if (rs && rs->is_array())
        for (const json& res : *rs)
          if (backendOf(res) == backend && matches(res, cell.group, &cell.match)) {
            cell.result = &res;
            break;
          }
      if (!cell.result)
        cell.note = "no result of group " + cell.group + " on " + backend + " matches " +
                    (cell.match.is_null() ? std::string("{}") : cell.match.dump());
      else if (!failureOf(*cell.result).empty())
        cell.note = "failed: " + failureOf(*cell.result);
      row.push_back(std::move(cell));
    }
    g.cells.push_back(std::move(row));
  }
  return g;
}

json figureJson(const FigureGrid& g, const json& layout) {
  json cells = json::array();
  for (const auto& row : g.cells) {
    json jr = json::array();
    for (const FigureCell& c : row) {
      json jc = {{"row", c.row}, {"column", c.column}};
      const json* r = c.result;
      jc["case"] = r ? json(caseId(*r)) : json(nullptr);
      jc["images"] = r && find(*r, {"images"}) ? *find(*r, {"images"}) : json::object();
      auto put = [&](const char* key, std::optional<double> v) {
        jc[key] = v ? json(*v) : json(nullptr);
      };
      put("frame_ms", r ? frameMs(*r) : std::nullopt);
      put("image_rmse", at(r, {"error", "image", "rmse"}));
      put("flip_mean", at(r, {"error", "image", "flip", "mean"}));
      put("visibility_rmse", at(r, {"error", "visibility", "rmse"}));
      put("shadow_mib", r ? memoryMiB(*r, "shadow_bytes") : std::nullopt);
      put("segments", at(r, {"scene", "segments"}));
      if (!c.note.empty()) jc["note"] = c.note;
      jr.push_back(std::move(jc));
    }
    cells.push_back(std::move(jr));
  }
  return {{"schema_version", 1},  {"name", g.name},       {"title", g.title},
          {"source", g.source},   {"backend", g.backend}, {"rows", g.rows},
          {"columns", g.columns}, {"cells", cells},       {"layout", layout}};
}

std::string renderFigureMarkdown(const FigureGrid& g, const json& results,
                                 const std::string& imageFile, const std::string& command) {
  std::ostringstream o;
  o << "# " << md(g.title) << "\n\n";
  if (!g.source.empty()) o << "Source: " << md(g.source) << "\n\n";
  if (!g.description.empty()) o << md(g.description) << "\n\n";
  o << "Command: `" << command << "` (backend " << g.backend << ")\n\n";
  o << "![" << md(g.title) << "](" << imageFile << ")\n\n";
  o << "The grid has the paper's rows and columns; each cell is our image (left) and its error "
       "heatmap against the exact reference (right).\n\n";

  o << "## Cells\n\n";
  Table t;
  t.header = {"Row",        "Column",    "Case",      "Segments",   "Frame (ms)",
              "Image RMSE", "FLIP mean", "Vis. RMSE", "Shadow MiB", "Note"};
  for (const auto& row : g.cells)
    for (const FigureCell& c : row) {
      const json* r = c.result;
      t.rows.push_back({{c.row},
                        {c.column},
                        {r ? caseId(*r) : std::string(kNone)},
                        countCell(at(r, {"scene", "segments"})),
                        numCell(r ? frameMs(*r) : std::nullopt),
                        numCell(at(r, {"error", "image", "rmse"})),
                        numCell(at(r, {"error", "image", "flip", "mean"})),
                        numCell(at(r, {"error", "visibility", "rmse"})),
                        numCell(r ? memoryMiB(*r, "shadow_bytes") : std::nullopt),
                        {c.note}});
    }
  mdTable(o, t);

  const ReportData d = buildReport(results);
  if (!d.paperTables.empty()) {
    o << "## Our numbers beside the paper's\n\n";
    for (const PaperTable& pt : d.paperTables) {
      o << "### " << md(pt.title) << "\n\n" << md(pt.about) << "\n\n";
      mdTable(o, pt.table);
      for (const std::string& n : pt.notes) o << "- Note: " << md(n) << "\n";
      if (!pt.notes.empty()) o << "\n";
    }
  }
  o << "The sweep's own reports (report.md, report.html, results.json) are in this folder.\n";
  return o.str();
}

}  // namespace sb::report
