#include "reports/figure_report.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "base/errors.h"
#include "base/fnv.h"
#include "reports/report_data.h"
#include "reports/stats.h"

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

std::vector<double> frameSamples(const json* r) {
  std::vector<double> v;
  const json* s = r ? find(*r, {"frame_ms", "samples"}) : nullptr;
  if (s && s->is_array())
    for (const json& x : *s)
      if (x.is_number()) v.push_back(x.get<double>());
  return v;
}

// The interleaved run that timed a result (sweep.cpp: every case timed in it shares the
// name); "" where it was not timed in rounds.
std::string interleavedRun(const json* r) {
  return r ? text(find(*r, {"measurement", "interleaved_run"})) : "";
}

// Where a cell's measurement was taken from the shared case store: the figure it was
// measured for; "" for a case measured by this run.
std::string measuredFor(const json* r) {
  return r ? text(find(*r, {"shared", "measured_for"})) : "";
}

// "date, CPU, load average A (1 min) when it started, B when it ended": the machine and load
// of a run (a results context or a stored case's).
std::string machineText(const json& c) {
  std::string s;
  auto add = [&](const std::string& part) { s += (s.empty() ? "" : ", ") + part; };
  if (const std::string d = text(find(c, {"date"})); !d.empty()) add(d);
  if (const std::string cpu = text(find(c, {"cpu"})); !cpu.empty()) add(cpu);
  if (const auto l = number(find(c, {"load_before", "1min"})))
    add("load average " + formatSig(*l) + " (1 min) when it started");
  if (const auto l = number(find(c, {"load_after", "1min"}))) add(formatSig(*l) + " when it ended");
  return s;
}

// The median frame time's 95% bootstrap interval, "[a, b]"; kNone with fewer than 2 samples.
Cell intervalCell(const json* r) {
  const std::vector<double> v = frameSamples(r);
  if (v.size() < 2) return {kNone, true};
  const Interval i = bootstrapMedian(v);
  return {"[" + formatSig(i.low) + ", " + formatSig(i.high) + "]", true};
}

std::string contextLine(const json& results, const std::string& command) {
  const json* c = find(results, {"context"});
  std::string commit = c ? text(find(*c, {"commit"})) : "";
  if (commit.empty()) commit = "unknown";
  const json* dirty = c ? find(*c, {"commit_dirty"}) : nullptr;
  std::string s = "Written by `" + command + "` on commit `" + commit.substr(0, 12) + "`";
  if (dirty && *dirty == true) s += " (with uncommitted changes)";
  if (c)
    if (const std::string m = machineText(*c); !m.empty()) s += ", " + m;
  return s +
         ". Frame times are this machine's under this load, from this run's rounds: a time on "
         "another page or from another run is not comparable with them unless a ratio of one "
         "interleaved run says so.";
}

bool anyShared(const FigureGrid& g) {
  for (const auto& row : g.cells)
    for (const FigureCell& c : row)
      if (!measuredFor(c.result).empty()) return true;
  return false;
}

// The cells whose measurement another figure's run made (the shared case store): which run,
// on which machine and load, so their times are read as that run's.
void sharedCells(std::ostringstream& o, const FigureGrid& g) {
  std::map<std::string, std::string> runs;  // figure -> its machine and load
  for (const auto& row : g.cells)
    for (const FigureCell& c : row)
      if (const std::string f = measuredFor(c.result); !f.empty() && c.note.empty())
        if (const json* ctx = find(*c.result, {"shared", "context"})) runs[f] = machineText(*ctx);
  if (runs.empty()) return;
  o << "Measured once: the cells whose note names another figure were measured by that "
       "figure's run in the same refresh (the shared case store, `strandbench figure --cases`) "
       "and are shown as it measured them (time, interval, errors, images), so every page that "
       "shows the case prints the same numbers. Their times are that run's, on its machine and "
       "load:\n\n";
  for (const auto& [f, m] : runs) o << "- " << md(f) << ": " << md(m) << "\n";
  o << "\n";
}

}  // namespace

std::string figureDigest(const std::string& body) {
  return hex64(fnv1a(kFnvOffset, body.data(), body.size()));
}

std::string figureHeader(const std::string& name, const std::string& command,
                         const std::string& commit, const std::string& body) {
  return "<!-- strandbench figure " + name + ": written by `" + command + "`, commit " +
         (commit.empty() ? std::string("unknown") : commit) + ", digest " + figureDigest(body) +
         "; do not edit -->\n";
}

std::optional<FigureHeader> parseFigureHeader(const std::string& markdown) {
  const std::string prefix = "<!-- strandbench figure ";
  const std::size_t eol = markdown.find('\n');
  if (!markdown.starts_with(prefix) || eol == std::string::npos) return std::nullopt;
  const std::string line = markdown.substr(0, eol);
  FigureHeader h;
  const std::size_t colon = line.find(": written by `", prefix.size());
  if (colon == std::string::npos) return std::nullopt;
  h.name = line.substr(prefix.size(), colon - prefix.size());
  const std::size_t cmdStart = colon + std::string(": written by `").size();
  const std::size_t cmdEnd = line.find("`, commit ", cmdStart);
  if (cmdEnd == std::string::npos) return std::nullopt;
  h.command = line.substr(cmdStart, cmdEnd - cmdStart);
  const std::size_t commitStart = cmdEnd + std::string("`, commit ").size();
  const std::size_t commitEnd = line.find(", digest ", commitStart);
  if (commitEnd == std::string::npos) return std::nullopt;
  h.commit = line.substr(commitStart, commitEnd - commitStart);
  const std::size_t digestStart = commitEnd + std::string(", digest ").size();
  const std::size_t digestEnd = line.find("; do not edit -->", digestStart);
  if (digestEnd == std::string::npos) return std::nullopt;
  h.digest = line.substr(digestStart, digestEnd - digestStart);
  return h;
}

std::vector<FigureClaim> figureClaims(const json& results) {
  std::vector<FigureClaim> claims;
  const json* tables = find(results, {"tables"});
  const json* rs = find(results, {"results"});
  if (!tables || !tables->is_array() || !rs || !rs->is_array()) return claims;
  // A run on both APIs makes each claim once per API (its ratio is of one API's rounds).
  std::vector<std::string> backends;
  for (const json& r : *rs)
    if (std::find(backends.begin(), backends.end(), backendOf(r)) == backends.end())
      backends.push_back(backendOf(r));
  for (const std::string& backend : backends) {
    auto first = [&](const std::string& group, const json* match) -> const json* {
      for (const json& r : *rs)
        if (backendOf(r) == backend && matches(r, group, match) && failureOf(r).empty()) return &r;
      return nullptr;
    };
    const std::string onBackend = backends.size() > 1 ? " (" + backend + ")" : "";
    for (const json& t : *tables) {
      const std::string tableMetric = text(find(t, {"metric"}));
      if (!tableMetric.empty() && tableMetric != "frame_ms") continue;
      const json* rows = find(t, {"rows"});
      if (!rows || !rows->is_array()) continue;
      const json* base = nullptr;
      for (const json& r : *rows)
        if (const json* b = find(r, {"baseline"}); b && *b == true) base = &r;
      // A claim compares frame times: a baseline of another metric (one step) makes none.
      if (!base) continue;
      if (const std::string m = text(find(*base, {"metric"})); !m.empty() && m != "frame_ms")
        continue;
      const std::string tableGroup = text(find(t, {"group"}));
      auto groupOfRow = [&](const json& r) {
        const std::string g = text(find(r, {"group"}));
        return g.empty() ? tableGroup : g;
      };
      const std::string unit = text(find(t, {"paper_unit"}));
      auto paperMs = [&](const json& r) -> std::optional<double> {
        const auto p = number(find(r, {"paper"}));
        if (!p || *p <= 0) return std::nullopt;
        return unit == "fps" ? 1000.0 / *p : *p;
      };
      const auto basePaper = paperMs(*base);
      const json* baseResult = first(groupOfRow(*base), find(*base, {"match"}));
      for (const json& r : *rows) {
        if (&r == base) continue;
        const std::string rowMetric = text(find(r, {"metric"}));
        if (!rowMetric.empty() && rowMetric != "frame_ms") continue;
        const auto paper = paperMs(r);
        if (!paper || !basePaper) continue;
        FigureClaim c;
        c.table = text(find(t, {"title"})) + onBackend;
        c.row = text(find(r, {"label"}));
        c.baseline = text(find(*base, {"label"}));
        c.paperRatio = *paper / *basePaper;
        const bool below = c.paperRatio < 1.0;
        const json* ours = first(groupOfRow(r), find(r, {"match"}));
        const std::vector<double> num = frameSamples(ours), den = frameSamples(baseResult);
        c.time = c.fragments = c.bytes = "-";
        // A verdict in time only from a ratio of one interleaved run (round r timed both cases,
        // paired): two runs' medians differ by the machine's state as much as by technique.
        const std::string run = interleavedRun(ours);
        c.oneRun = !run.empty() && run == interleavedRun(baseResult) && num.size() == den.size();
        if (!num.empty() && !den.empty() && !c.oneRun) {
          c.estimate = median(num) / median(den);
          c.time = "none: not timed in one interleaved run";
        } else if (!num.empty() && !den.empty()) {
          const Interval i = bootstrapRatio(num, den, /*paired=*/true);
          c.low = i.low;
          c.estimate = i.estimate;
          c.high = i.high;
          // An interval of one or two samples a side says nothing: no verdict in time.
          c.time = num.size() < 3 || den.size() < 3 ? "undecided (too few samples; --min-reps 3)"
                                                    : orderingVerdict(i, 1.0, below);
        }
        auto work = [&](std::optional<double> a, std::optional<double> b) -> std::string {
          if (!a || !b || *b <= 0) return "-";
          const double ratio = *a / *b;
          if (ratio == 1.0) return "undecided";
          return (ratio < 1.0) == below ? "holds" : "fails";
        };
        if (ours && baseResult) {
          c.fragments = work(frameCounter(*ours, "fragment_invocations"),
                             frameCounter(*baseResult, "fragment_invocations"));
          c.bytes = work(frameBytes(*ours), frameBytes(*baseResult));
        }
        claims.push_back(std::move(c));
      }
    }
  }
  return claims;
}

void checkFigureBlock(const json& suite, const std::string& where) {
  const json* f = find(suite, {"figure"});
  if (!f || !f->is_object())
    throw InputError(where +
                     ": \"figure\" (an object with title, rows, columns, cells) is required");
  for (const auto& [key, value] : f->items()) {
    static const std::set<std::string> known = {"title", "source", "group", "rows",  "columns",
                                                "cells", "models", "note",  "claims"};
    if (!known.contains(key))
      throw InputError(where + ": \"figure\" has an unknown key \"" + key +
                       "\" (known: title, source, group, rows, columns, cells, models, note, "
                       "claims)");
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

std::optional<double> cellMetric(const FigureCell& c, const std::string& metric) {
  if (metric == "banding") return c.banding;
  const json* r = c.result;
  if (!r || !c.note.empty()) return std::nullopt;
  if (metric == "image_rmse") return at(r, {"error", "image", "rmse"});
  if (metric == "flip_mean") return at(r, {"error", "image", "flip", "mean"});
  if (metric == "visibility_rmse") return at(r, {"error", "visibility", "rmse"});
  if (metric == "shadow_mib") return memoryMiB(*r, "shadow_bytes");
  return std::nullopt;
}

namespace {
const FigureCell* gridCell(const FigureGrid& g, int r, int col) {
  if (r < 0 || col < 0 || r >= int(g.cells.size()) || col >= int(g.cells[r].size())) return nullptr;
  return &g.cells[r][col];
}
}  // namespace

std::optional<double> claimTarget(const FigureGrid& g, const FigureErrorClaim& c) {
  if (c.paper) return c.paper;
  const FigureCell* b = gridCell(g, c.thanRow, c.thanColumn);
  const auto y = b ? cellMetric(*b, c.metric) : std::nullopt;
  if (!y) return std::nullopt;
  return *y * c.factor;
}

std::string errorClaimVerdict(const FigureGrid& g, const FigureErrorClaim& c) {
  const FigureCell* a = gridCell(g, c.row, c.column);
  const auto x = a ? cellMetric(*a, c.metric) : std::nullopt;
  const auto y = claimTarget(g, c);
  if (!x || !y) return "-";
  if (c.relation == "same")
    return std::abs(*x - *y) <= c.tolerance * std::abs(*y) ? "holds" : "fails";
  return *x < *y ? "holds" : "fails";
}

FigureGrid buildFigureGrid(const json& figure, const json& results, const std::string& name,
                           const std::string& backend) {
  FigureGrid g;
  g.name = name;
  g.backend = backend;
  g.title = text(find(figure, {"title"}));
  g.source = text(find(figure, {"source"}));
  g.description = text(find(figure, {"note"}));
  if (const json* cs = find(figure, {"claims"}); cs && cs->is_array())
    for (const json& jc : *cs) {
      FigureErrorClaim c;
      c.text = text(find(jc, {"text"}));
      c.metric = text(find(jc, {"metric"}));
      c.relation = text(find(jc, {"relation"}));
      if (const auto t = number(find(jc, {"tolerance"}))) c.tolerance = *t;
      c.paper = number(find(jc, {"paper"}));
      if (const auto f = number(find(jc, {"factor"}))) c.factor = *f;
      const json* a = find(jc, {"cell"});
      const json* b = find(jc, {"than"});
      if (a && a->is_array() && a->size() == 2) {
        c.row = (*a)[0].get<int>();
        c.column = (*a)[1].get<int>();
      }
      if (b && b->is_array() && b->size() == 2) {
        c.thanRow = (*b)[0].get<int>();
        c.thanColumn = (*b)[1].get<int>();
      }
      g.errorClaims.push_back(std::move(c));
    }
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

FigureGrid buildFigureGrid(const json& figure, const json& results, const std::string& name,
                           const std::vector<std::string>& backends) {
  if (backends.size() == 1) return buildFigureGrid(figure, results, name, backends.front());
  FigureGrid g;
  for (const std::string& b : backends) {
    FigureGrid one = buildFigureGrid(figure, results, name, b);
    const int offset = static_cast<int>(g.rows.size());
    if (g.backend.empty()) {
      g = one;
      g.rows.clear();
      g.cells.clear();
      g.errorClaims.clear();
    } else {
      g.backend += " + " + b;
    }
    // Per-API rows: the paper's rows once per API, its claims judged on each.
    for (std::size_t r = 0; r < one.rows.size(); ++r) {
      g.rows.push_back(one.rows[r] + " (" + b + ")");
      for (FigureCell& c : one.cells[r]) c.row = g.rows.back();
      g.cells.push_back(std::move(one.cells[r]));
    }
    for (FigureErrorClaim c : one.errorClaims) {
      c.text += " (" + b + ")";
      c.row += offset;
      c.thanRow += offset;
      g.errorClaims.push_back(std::move(c));
    }
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
      put("banding", c.banding);
      if (!c.note.empty()) jc["note"] = c.note;
      if (const std::string f = measuredFor(r); !f.empty()) jc["measured_for"] = f;
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
  if (const std::string about = text(find(results, {"suite", "description"})); !about.empty())
    o << md(about) << "\n\n";
  if (!g.description.empty()) o << md(g.description) << "\n\n";
  o << contextLine(results, command) << " Backend " << g.backend << ".\n\n";
  o << "![" << md(g.title) << "](" << imageFile << ")\n\n";
  o << "The grid has the paper's rows and columns; each cell is our image (left) and its error "
       "heatmap against the exact reference (right).\n\n";

  o << "## Cells\n\n";
  Table t;
  bool banding = false;
  for (const auto& row : g.cells)
    for (const FigureCell& c : row) banding |= c.banding.has_value();
  t.header = {"Row",          "Column",     "Case",      "Segments",  "Frame (ms)",
              "95% interval", "Image RMSE", "FLIP mean", "Vis. RMSE", "Shadow MiB"};
  if (banding) t.header.insert(t.header.begin() + 8, "Banding");
  t.header.push_back("Note");
  for (const auto& row : g.cells)
    for (const FigureCell& c : row) {
      const json* r = c.result;
      std::vector<Cell> cells = {{c.row},
                                 {c.column},
                                 {r ? caseId(*r) : std::string(kNone)},
                                 countCell(at(r, {"scene", "segments"})),
                                 numCell(r ? frameMs(*r) : std::nullopt),
                                 intervalCell(r),
                                 numCell(at(r, {"error", "image", "rmse"})),
                                 numCell(at(r, {"error", "image", "flip", "mean"})),
                                 numCell(at(r, {"error", "visibility", "rmse"})),
                                 numCell(r ? memoryMiB(*r, "shadow_bytes") : std::nullopt)};
      if (banding) cells.insert(cells.begin() + 8, numCell(c.banding));
      std::string note = c.note;
      if (const std::string f = measuredFor(r); !f.empty())
        note += (note.empty() ? "" : "; ") + std::string("measured once, for ") + f + " (case " +
                text(find(*r, {"shared", "case"})) + ")";
      cells.push_back({note});
      t.rows.push_back(std::move(cells));
    }
  mdTable(o, t);
  sharedCells(o, g);

  const ReportData d = buildReport(results);
  if (!d.paperTables.empty()) {
    o << "## Our numbers beside the paper's\n\n";
    if (anyShared(g))
      o << "A row whose case was measured once for another figure (its cell's note) divides "
           "medians of two runs: its ratio is not a measurement of one run (the claims below "
           "give it no verdict in time).\n\n";
    for (const PaperTable& pt : d.paperTables) {
      o << "### " << md(pt.title) << "\n\n" << md(pt.about) << "\n\n";
      mdTable(o, pt.table);
      for (const std::string& n : pt.notes) o << "- Note: " << md(n) << "\n";
      if (!pt.notes.empty()) o << "\n";
    }
  }
  if (banding)
    o << "Banding: the RMSE of the luminance error against the reference after a 7x7 box "
         "filter (imaging/metrics.h, bandingMeasure): stripes and steps, spatially coherent, "
         "survive the filter; per-pixel noise (what jitter trades them for) averages out.\n\n";
  if (!g.errorClaims.empty()) {
    o << "## The paper's claims on errors and memory\n\n";
    o << "Errors and memory are deterministic (a run gives the same images and allocations "
         "again), so each claim holds or fails on this run; \"same\" allows the relative "
         "tolerance shown; shadow\\_mib is the memory the shadow technique holds (MiB), "
         "against another cell or the paper's own number.\n\n";
    Table et;
    et.header = {"Claim", "Metric", "Cell", "Value", "Against", "Value", "Relation", "Verdict"};
    for (const FigureErrorClaim& c : g.errorClaims) {
      auto label = [&](int r, int col) -> std::string {
        if (r < 0 || col < 0 || r >= int(g.rows.size()) || col >= int(g.columns.size())) return "?";
        return g.rows[r] + " / " + g.columns[col];
      };
      const FigureCell* cell = gridCell(g, c.row, c.column);
      const std::string scaled = c.factor == 1.0 || c.paper ? "" : formatSig(c.factor) + " x ";
      et.rows.push_back(
          {{c.text},
           {c.metric},
           {label(c.row, c.column)},
           numCell(cell ? cellMetric(*cell, c.metric) : std::nullopt),
           {c.paper ? std::string("the paper") : scaled + label(c.thanRow, c.thanColumn)},
           numCell(claimTarget(g, c)),
           {c.relation == "same" ? "same within " + formatSig(100 * c.tolerance, 2) + "%"
                                 : std::string("below")},
           {errorClaimVerdict(g, c)}});
    }
    mdTable(o, et);
  }
  const std::vector<FigureClaim> claims = figureClaims(results);
  if (!claims.empty()) {
    o << "## The paper's claims, at 95%\n\n";
    o << "Each row of a paper table against its baseline: the paper's ratio says whether the "
         "row is faster (below 1) or slower; our ratio of median frame times with its "
         "bootstrap interval (the rounds paired) gives the verdict in time only where both "
         "cases were timed in one interleaved run (a case measured for another figure was "
         "not: its ratio compares two runs and has no verdict in time); the frame's fragment "
         "shader invocations and bytes give the verdict in work (counted, the same on every "
         "device).\n\n";
    Table ct;
    ct.header = {"Table", "Claim", "Paper ratio", "Our ratio [95%]", "Time", "Fragments", "Bytes"};
    for (const FigureClaim& c : claims) {
      std::string ours = kNone;
      if (c.estimate && c.oneRun)
        ours = formatSig(*c.estimate) + " [" + formatSig(*c.low) + ", " + formatSig(*c.high) + "]";
      else if (c.estimate)
        ours = formatSig(*c.estimate) + " (two runs)";
      ct.rows.push_back(
          {{c.table},
           {c.row + (c.paperRatio < 1 ? " faster than " : " slower than ") + c.baseline},
           {formatSig(c.paperRatio), true},
           {ours, true},
           {c.time},
           {c.fragments},
           {c.bytes}});
    }
    mdTable(o, ct);
  }
  o << "The sweep's own reports (report.md, report.html, results.json) are in the run's "
       "folder.\n";
  const json* c = find(results, {"context"});
  const std::string body = o.str();
  return figureHeader(g.name, command, c ? text(find(*c, {"commit"})) : "", body) + body;
}

}  // namespace sb::report
