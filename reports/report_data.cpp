#include "reports/report_data.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>

#include "base/errors.h"

namespace sb::report {

namespace {

constexpr double kMiB = 1024.0 * 1024.0;

std::string orDefault(std::string s, const char* fallback) { return s.empty() ? fallback : s; }

Cell num(std::optional<double> v, int digits = 3) {
  if (!v) return {kNone, true};
  return {formatSig(*v, digits), true};
}

// Values in case.params and in a row's `match` compare equal when they are equal
// JSON or read the same (4 and "4", so a hand-written suite need not match types).
bool sameValue(const json& a, const json& b) { return a == b || text(&a) == text(&b); }

}  // namespace

bool matches(const json& r, const std::string& group, const json* match) {
  if (groupOf(r) != group) return false;
  if (!match || !match->is_object()) return true;
  const json* params = find(r, {"case", "params"});
  for (const auto& [key, want] : match->items()) {
    const json* have = params ? find(*params, {key}) : nullptr;
    if (!have || !sameValue(*have, want)) return false;
  }
  return true;
}

namespace {

// The unit a metric is shown in: "ms", "MiB", or "" for an unknown metric.
std::string metricUnit(const std::string& metric) {
  if (metric == "frame_ms" || metric.starts_with("pass:") || metric.starts_with("passes:"))
    return "ms";
  if (metric.starts_with("memory:")) return "MiB";
  return "";
}

// A result's value of a table metric (see "Paper tables" in docs/suites-and-results.md).
std::optional<double> metricValue(const json& r, const std::string& metric) {
  if (metric == "frame_ms") return frameMs(r);
  if (metric.starts_with("memory:")) {
    const std::optional<double> bytes = number(find(r, {"memory", metric.substr(7)}));
    if (!bytes) return std::nullopt;
    return *bytes / kMiB;
  }
  const json* passes = find(r, {"passes"});
  if (!passes || !passes->is_array()) return std::nullopt;
  const bool prefix = metric.starts_with("passes:");
  if (!prefix && !metric.starts_with("pass:")) return std::nullopt;
  const std::string name = metric.substr(prefix ? 7 : 5);
  std::optional<double> sum;
  for (const json& p : *passes) {
    const std::string pname = text(find(p, {"name"}));
    if (prefix ? !pname.starts_with(name) : pname != name) continue;
    const std::optional<double> ms = number(find(p, {"ms", "median"}));
    if (!ms) return std::nullopt;  // a pass without a time: no honest sum
    sum = sum.value_or(0.0) + *ms;
    if (!prefix) break;
  }
  return sum;
}

PaperTable buildPaperTable(const json& t, const std::vector<const json*>& results) {
  PaperTable pt;
  pt.title = orDefault(text(find(t, {"title"})), "Paper table");
  const std::string tableGroup = text(find(t, {"group"}));
  const std::string tableMetric = orDefault(text(find(t, {"metric"})), "frame_ms");
  const std::string tableUnit = metricUnit(tableMetric);

  struct Row {
    std::string label, metric, unit, paperUnit;
    std::optional<double> paper, paperComparable;  // as written; in ms (fps converted) or MiB
    std::map<std::string, std::vector<const json*>> byBackend;
  };
  std::vector<Row> rows;
  std::vector<std::string> backends;
  int baseline = -1;
  bool rowMetrics = false;
  const json* jrows = find(t, {"rows"});
  if (jrows && jrows->is_array()) {
    for (const json& jr : *jrows) {
      Row row;
      row.label = text(find(jr, {"label"}));
      row.metric = orDefault(text(find(jr, {"metric"})), tableMetric.c_str());
      row.unit = metricUnit(row.metric);
      rowMetrics |= row.metric != tableMetric;
      row.paperUnit = text(find(jr, {"paper_unit"}));
      if (row.paperUnit.empty()) row.paperUnit = orDefault(text(find(t, {"paper_unit"})), "ms");
      row.paper = number(find(jr, {"paper"}));
      if (row.paperUnit == "fps") {
        if (row.paper && *row.paper > 0) row.paperComparable = 1000.0 / *row.paper;
      } else if (row.paperUnit == "ms" || row.paperUnit == "MiB") {
        row.paperComparable = row.paper;
      } else {
        pt.notes.push_back("row \"" + row.label + "\": unknown paper_unit " + row.paperUnit);
      }
      const json* isBaseline = find(jr, {"baseline"});
      if (baseline < 0 && isBaseline && *isBaseline == true)
        baseline = static_cast<int>(rows.size());
      const json* match = find(jr, {"match"});
      std::string group = text(find(jr, {"group"}));
      if (group.empty()) group = tableGroup;
      for (const json* r : results) {
        if (!matches(*r, group, match)) continue;
        const std::string b = backendOf(*r);
        if (std::find(backends.begin(), backends.end(), b) == backends.end()) backends.push_back(b);
        row.byBackend[b].push_back(r);
      }
      if (row.byBackend.empty())
        pt.notes.push_back("row \"" + row.label + "\": no result of group \"" + group +
                           "\" matches " + (match ? match->dump() : "{}"));
      for (const auto& [b, rs] : row.byBackend)
        if (rs.size() > 1)
          pt.notes.push_back("row \"" + row.label + "\" matches " + std::to_string(rs.size()) +
                             " results on " + b + "; the first (" + caseId(*rs[0]) + ") is shown");
      if (row.unit.empty())
        pt.notes.push_back("row \"" + row.label + "\": unknown metric " + row.metric);
      rows.push_back(std::move(row));
    }
  }

  auto ours = [&](const Row& row, const std::string& b) -> std::optional<double> {
    auto it = row.byBackend.find(b);
    if (it == row.byBackend.end()) return std::nullopt;
    return metricValue(*it->second[0], row.metric);
  };
  auto ratio = [](std::optional<double> a, std::optional<double> b) -> std::optional<double> {
    if (!a || !b || *b == 0) return std::nullopt;
    return *a / *b;
  };

  const std::string source = text(find(t, {"source"}));
  pt.about = (source.empty() ? "" : "Source: " + source + ". ") + "Group " +
             orDefault(tableGroup, "(per row)") +
             (rowMetrics ? std::string(", metric per row")
                         : ", metric " + tableMetric + " (" + orDefault(tableUnit, "?") + ")") +
             ", paper values in " + orDefault(text(find(t, {"paper_unit"})), "ms") + ". ";
  if (baseline >= 0)
    pt.about += "Ratios: ours / our baseline (\"" + rows[baseline].label +
                "\") beside paper / paper's baseline, both in time for fps tables.";
  else
    pt.about += "Ratios: ours / paper.";

  Table& tab = pt.table;
  tab.header = {"Row"};
  if (rowMetrics) tab.header.push_back("Metric");
  tab.header.push_back("Paper");
  if (baseline >= 0) tab.header.push_back("Paper ratio");
  for (const std::string& b : backends) {
    tab.header.push_back(b + " (" + orDefault(tableUnit, "?") + ")");
    tab.header.push_back(b + (baseline >= 0 ? " ratio" : " / paper"));
  }
  // A time claim in work too: the frame's counters over the baseline's, the same on
  // every API (docs/work-counters.md), so one column each, from the first backend.
  const bool workRatios = baseline >= 0 && tableMetric == "frame_ms";
  auto frameWork = [&](const Row& row, bool bytes) -> std::optional<double> {
    for (const std::string& b : backends) {
      auto it = row.byBackend.find(b);
      if (it == row.byBackend.end()) continue;
      const auto v =
          bytes ? frameBytes(*it->second[0]) : frameCounter(*it->second[0], "fragment_invocations");
      if (v) return v;
    }
    return std::nullopt;
  };
  if (workRatios) {
    tab.header.push_back("fragments ratio");
    tab.header.push_back("bytes ratio");
    pt.about +=
        " Work ratios: the frame's fragment shader invocations and bytes (written, read "
        "and bound as storage) over the baseline's: whether the claim holds in work, "
        "whatever the device.";
  }
  for (const Row& row : rows) {
    std::vector<Cell> cells = {{row.label}};
    if (rowMetrics) cells.push_back({row.metric});
    Cell paper{kNone, true};
    if (row.paper) {
      paper.text = shortest(*row.paper) + " " + row.paperUnit;  // as the paper gives it
      if (row.paperUnit == "fps" && row.paperComparable)
        paper.text += " (" + formatSig(*row.paperComparable) + " ms)";
    }
    cells.push_back(paper);
    if (baseline >= 0)
      cells.push_back(num(ratio(row.paperComparable, rows[baseline].paperComparable)));
    for (const std::string& b : backends) {
      const std::optional<double> v = ours(row, b);
      Cell c = num(v);
      if (v && row.unit != tableUnit) c.text += " " + row.unit;
      cells.push_back(c);
      if (baseline >= 0) {
        cells.push_back(num(ratio(v, ours(rows[baseline], b))));
      } else {
        // ours / paper only where both are in the same unit
        const bool comparable = (row.unit == "ms" && row.paperUnit != "MiB") ||
                                (row.unit == "MiB" && row.paperUnit == "MiB");
        cells.push_back(num(comparable ? ratio(v, row.paperComparable) : std::nullopt));
      }
    }
    if (workRatios)
      for (bool bytes : {false, true})
        cells.push_back(num(ratio(frameWork(row, bytes), frameWork(rows[baseline], bytes))));
    tab.rows.push_back(std::move(cells));
  }
  if (backends.empty()) pt.notes.push_back("no results match any row");
  return pt;
}

// A work counter as a table cell: counts as "1.2 M", bytes as "16 MiB", absent or
// null (a device without queries) as kNone.
Cell workCell(const json* work, const WorkColumn& c) {
  const std::optional<double> v = work ? number(find(*work, {c.key})) : std::nullopt;
  if (!v) return {kNone, true};
  return {c.bytes ? formatBytes(*v) : formatCount(*v), true};
}

void buildPassesTable(Group& g) {
  Table& t = g.passes;
  std::vector<std::string> params;
  for (const std::string& k : g.params)
    if (k != "backend") params.push_back(k);
  const bool nameOit = anyTransparency(g.results), nameShadow = anyShadow(g.results);
  // The case by what varies within the group (its id repeats the group and backend).
  auto labelOf = [&](const json& r) {
    std::string label;
    for (const std::string& k : params)
      label += (label.empty() ? "" : ", ") + k + "=" + text(find(r, {"case", "params", k}));
    return label.empty() ? caseId(r) : label;
  };
  // The technique gets a column only where the case's label names neither its shadow
  // nor its transparency technique ("shadow=dom:layers=3", "oit=wsum" do; the group's
  // axis is the one that varies): the table is wide enough as it is.
  const bool techniqueColumn = std::any_of(g.results.begin(), g.results.end(), [&](const json* r) {
    const std::string label = labelOf(*r);
    auto names = [&](const char* key) {
      const std::string spec = text(find(*r, {key}));
      const std::string name = spec.substr(0, spec.find(':'));  // "exact:method=abuffer"
      return !name.empty() && label.find(name) != std::string::npos;
    };
    return !names("shadow") && !names("oit");
  });
  t.header = {"Case", "Backend"};
  if (techniqueColumn) t.header.push_back("Technique");
  for (const char* h : {"Pass", "Executions", "Median ms"}) t.header.push_back(h);
  for (const WorkColumn& c : kWorkColumns) t.header.push_back(c.header);
  for (const json* r : g.results) {
    const json* passes = find(*r, {"passes"});
    if (!passes || !passes->is_array()) continue;
    const std::string label = labelOf(*r);
    for (const json& p : *passes) {
      std::vector<Cell> row = {{label}, {backendOf(*r)}};
      if (techniqueColumn) row.push_back({shortTechniqueOf(*r, nameOit, nameShadow)});
      row.insert(row.end(), {{orDefault(text(find(p, {"name"})), kNone)},
                             {orDefault(text(find(p, {"executions"})), kNone), true},
                             num(number(find(p, {"ms", "median"})))});
      const json* work = find(p, {"work"});
      for (const WorkColumn& c : kWorkColumns) row.push_back(workCell(work, c));
      t.rows.push_back(std::move(row));
    }
  }
}

Group buildGroup(const std::string& name, const json* jgroup,
                 const std::vector<const json*>& results) {
  Group g;
  g.name = name;
  if (jgroup) g.description = text(find(*jgroup, {"description"}));
  std::set<std::string> keys;
  if (jgroup) {
    if (const json* axes = find(*jgroup, {"axes"}); axes && axes->is_object())
      for (const auto& item : axes->items()) keys.insert(item.key());
  }
  for (const json* r : results) {
    if (groupOf(*r) != name) continue;
    g.results.push_back(r);
    if (const json* p = find(*r, {"case", "params"}); p && p->is_object())
      for (const auto& item : p->items()) keys.insert(item.key());
  }
  // Alphabetical (JSON objects do not keep the suite's axis order), backend last
  // as it is the innermost axis of every group.
  for (const std::string& k : keys)
    if (k != "backend") g.params.push_back(k);
  if (keys.count("backend")) g.params.push_back("backend");

  g.table.header = g.params;
  // Total: against exact shadows and exact transparency; own: against the exact
  // technique of the other family with this case's own (docs/suites-and-results.md).
  for (const char* h : {"Frame ms (median [95% CI] or ± sd)", "Memory MiB", "Image RMSE (total)",
                        "PSNR dB (total)", "FLIP mean (total)", "Visibility RMSE", "Own error of",
                        "Image RMSE (own)", "FLIP mean (own)"})
    g.table.header.push_back(h);
  // Against each further reference (error.aa): its image RMSE and FLIP mean.
  const std::vector<std::string> more = moreReferenceNames(g.results);
  for (const std::string& ref : more)
    for (const char* h : {"Image RMSE (", "FLIP mean ("}) g.table.header.push_back(h + ref + ")");
  const bool animated = std::any_of(g.results.begin(), g.results.end(),
                                    [](const json* r) { return find(*r, {"animation"}); });
  if (animated)
    for (const char* h : {"Flicker image", "Flicker visibility"}) g.table.header.push_back(h);
  for (const json* r : g.results) {
    std::vector<Cell> cells;
    for (const std::string& k : g.params) {
      const json* p = find(*r, {"case", "params", k});
      cells.push_back({p ? text(p) : kNone});
    }
    if (const std::string why = failureOf(*r); !why.empty()) {
      cells.push_back({"failed: " + why});
      for (int i = 0; i < 5; ++i) cells.push_back({kNone});
      g.table.rows.push_back(std::move(cells));
      continue;
    }
    Cell frame = num(frameMs(*r));
    // A sweep's bootstrap interval of the median (and its marked outliers); older results: sd.
    const json* ci = find(*r, {"measurement", "median_ci95_ms"});
    if (ci && ci->is_array() && ci->size() == 2 && frameMs(*r)) {
      frame.text += " [" + formatSig((*ci)[0].get<double>(), 3) + ", " +
                    formatSig((*ci)[1].get<double>(), 3) + "]";
      const json* out = find(*r, {"measurement", "outliers"});
      if (out && out->is_array() && !out->empty())
        frame.text +=
            " (" + std::to_string(out->size()) + " outlier" + (out->size() > 1 ? "s" : "") + ")";
    } else if (const auto sd = number(find(*r, {"frame_ms", "stddev"})); sd && frameMs(*r)) {
      frame.text += " ± " + formatSig(*sd, 2);
    }
    cells.push_back(frame);
    cells.push_back(num(memoryMiB(*r)));
    cells.push_back(num(number(find(*r, {"error", "image", "rmse"}))));
    cells.push_back(num(number(find(*r, {"error", "image", "psnr"}))));
    cells.push_back(num(number(find(*r, {"error", "image", "flip", "mean"}))));
    cells.push_back(num(number(find(*r, {"error", "visibility", "rmse"}))));
    cells.push_back({orDefault(text(find(*r, {"error", "own", "technique"})), kNone)});
    cells.push_back(num(number(find(*r, {"error", "own", "image", "rmse"}))));
    cells.push_back(num(number(find(*r, {"error", "own", "image", "flip", "mean"}))));
    for (const std::string& ref : more) {
      cells.push_back(num(number(find(*r, {"error", ref, "rmse"}))));
      cells.push_back(num(number(find(*r, {"error", ref, "flip", "mean"}))));
    }
    if (animated) {
      cells.push_back(num(number(find(*r, {"animation", "flicker", "image"}))));
      cells.push_back(num(number(find(*r, {"animation", "flicker", "visibility"}))));
    }
    g.table.rows.push_back(std::move(cells));
  }
  buildPassesTable(g);
  return g;
}

// For each budget (ascending), the most accurate result whose median frame time
// fits it, by `metric` (a path); the budgets are the frame times of the frontier.
struct Pick {
  const json* result = nullptr;
  double ms = 0, error = 0;
};
std::vector<Pick> frontier(const std::vector<const json*>& results,
                           std::initializer_list<std::string_view> metric) {
  std::vector<Pick> picks;
  for (const json* r : results) {
    const auto ms = frameMs(*r);
    const auto e = number(find(*r, metric));
    if (ms && e) picks.push_back({r, *ms, *e});
  }
  std::stable_sort(picks.begin(), picks.end(), [](const Pick& a, const Pick& b) {
    return a.ms != b.ms ? a.ms < b.ms : a.error < b.error;
  });
  std::vector<Pick> front;
  for (const Pick& p : picks)
    if (front.empty() || p.error < front.back().error) front.push_back(p);
  return front;
}

BudgetTable buildBudgetTable(const std::string& key, const std::vector<const json*>& results) {
  BudgetTable b;
  b.key = key;
  const std::vector<Pick> byFlip = frontier(results, {"error", "image", "flip", "mean"});
  const std::vector<Pick> byRmse = frontier(results, {"error", "image", "rmse"});
  std::vector<double> budgets;
  for (const auto* f : {&byFlip, &byRmse})
    for (const Pick& p : *f) budgets.push_back(p.ms);
  std::sort(budgets.begin(), budgets.end());
  budgets.erase(std::unique(budgets.begin(), budgets.end()), budgets.end());
  const bool nameOit = anyTransparency(results), nameShadow = anyShadow(results);
  b.table.header = {"Frame-time budget (ms)", "Most accurate by FLIP", "FLIP mean",
                    "Most accurate by image RMSE", "Image RMSE"};
  // The frontier is sorted by time with falling error: the last that fits is the best.
  auto best = [](const std::vector<Pick>& front, double budget) -> const Pick* {
    const Pick* p = nullptr;
    for (const Pick& f : front)
      if (f.ms <= budget) p = &f;
    return p;
  };
  for (double budget : budgets) {
    std::vector<Cell> row = {{"≤ " + formatSig(budget), true}};
    for (const auto* front : {&byFlip, &byRmse}) {
      const Pick* p = best(*front, budget);
      row.push_back({p ? shortTechniqueOf(*p->result, nameOit, nameShadow) : kNone});
      row.push_back(num(p ? std::optional<double>(p->error) : std::nullopt));
    }
    b.table.rows.push_back(std::move(row));
  }
  return b;
}

}  // namespace

std::string shortTechniqueOf(const json& r, bool nameOit, bool nameShadow) {
  const std::string shadow = orDefault(text(find(r, {"shadow"})), "?");
  const std::string oit = orDefault(text(find(r, {"oit"})), "none");
  if (oit == "none" && !nameOit) return shadow;
  if (shadow == "none" && (!nameShadow || oit == "none")) return oit;
  return oit + " + " + shadow;
}

bool anyTransparency(const std::vector<const json*>& results) {
  return std::any_of(results.begin(), results.end(), [](const json* r) {
    return orDefault(text(find(*r, {"oit"})), "none") != "none";
  });
}

bool anyShadow(const std::vector<const json*>& results) {
  return std::any_of(results.begin(), results.end(), [](const json* r) {
    return orDefault(text(find(*r, {"shadow"})), "none") != "none";
  });
}

std::string comparableKey(const json& r) {
  return text(find(r, {"scene", "spec"})) + " | " + sizeOf(r) + " | " + backendOf(r);
}

const json* find(const json& j, std::initializer_list<std::string_view> path) {
  const json* cur = &j;
  for (std::string_view key : path) {
    if (!cur->is_object()) return nullptr;
    auto it = cur->find(std::string(key));
    if (it == cur->end()) return nullptr;
    cur = &*it;
  }
  return cur;
}

std::optional<double> number(const json* j) {
  if (!j) return std::nullopt;
  double v = 0;
  if (j->is_number()) {
    v = j->get<double>();
  } else if (j->is_string()) {
    const std::string& s = j->get_ref<const std::string&>();
    char* end = nullptr;
    v = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size()) return std::nullopt;
  } else {
    return std::nullopt;
  }
  if (!std::isfinite(v)) return std::nullopt;
  return v;
}

std::string text(const json* j) {
  if (!j || j->is_null()) return "";
  if (j->is_string()) return j->get<std::string>();
  if (j->is_number_integer()) return j->dump();
  if (j->is_number_float()) {
    const double v = j->get<double>();
    return std::isfinite(v) ? shortest(v) : "";
  }
  return j->dump();
}

std::string shortest(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string formatSig(double v, int digits) {
  if (!std::isfinite(v)) return kNone;
  if (v == 0) return "0";
  const int magnitude = static_cast<int>(std::floor(std::log10(std::abs(v))));
  const int decimals = std::clamp(digits - 1 - magnitude, 0, 9);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string formatCount(double v) {
  if (!std::isfinite(v)) return kNone;
  const double a = std::abs(v);
  if (a < 1e3) return shortest(std::round(v * 100) / 100);
  const char* suffix = a < 1e6 ? " k" : a < 1e9 ? " M" : " G";
  const double scaled = v / (a < 1e6 ? 1e3 : a < 1e9 ? 1e6 : 1e9);
  return formatSig(scaled, 2 + (std::abs(scaled) >= 100)) + suffix;
}

std::string formatBytes(double v) {
  if (!std::isfinite(v)) return kNone;
  const double a = std::abs(v);
  if (a < 1024) return shortest(v) + " B";
  const char* suffix = a < kMiB ? " KiB" : a < 1024 * kMiB ? " MiB" : " GiB";
  const double scaled = v / (a < kMiB ? 1024 : a < 1024 * kMiB ? kMiB : 1024 * kMiB);
  return formatSig(scaled, 2 + (std::abs(scaled) >= 100)) + suffix;
}

Table costTermsTable(const CostModel& m) {
  Table t;
  t.header = {"Term", "Coefficient", "Unit"};
  for (const CostTerm& term : m.terms)
    t.rows.push_back({{term.name},
                      m.fitted ? Cell{formatSig(term.coefficient), true} : Cell{kNone, true},
                      {term.unit}});
  return t;
}

Table costCasesTable(const CostModel& m) {
  Table t;
  t.header = {"Case", "Technique", "Measured ms", "Predicted ms", "Measured / predicted", "Note"};
  for (const CostCase& c : m.cases)
    t.rows.push_back({{c.caseId},
                      {c.technique},
                      num(c.measured),
                      num(c.predicted),
                      num(c.ratio, 2),
                      {c.inefficient ? "inefficient: look at it"
                       : c.inFit     ? ""
                                     : "left out of the fit"}});
  return t;
}

std::string caseId(const json& r) { return orDefault(text(find(r, {"case", "id"})), "(no id)"); }

std::string groupOf(const json& r) { return text(find(r, {"case", "group"})); }

std::string backendOf(const json& r) {
  std::string b = text(find(r, {"backend"}));
  return b.empty() ? text(find(r, {"case", "params", "backend"})) : b;
}

std::string sizeOf(const json& r) {
  const json* s = find(r, {"size"});
  if (!s || !s->is_array() || s->size() != 2) return text(s);
  return text(&(*s)[0]) + "x" + text(&(*s)[1]);
}

std::string techniqueOf(const json& r) {
  return "shadow " + orDefault(text(find(r, {"shadow"})), "?") + ", oit " +
         orDefault(text(find(r, {"oit"})), "?");
}

std::optional<double> frameMs(const json& r) { return number(find(r, {"frame_ms", "median"})); }

std::optional<double> frameCounter(const json& r, const char* key) {
  return number(find(r, {"frame_work", key}));
}

std::optional<double> frameBytes(const json& r) {
  const auto w = frameCounter(r, "bytes_written"), rd = frameCounter(r, "bytes_read"),
             st = frameCounter(r, "bytes_storage");
  if (!w || !rd || !st) return std::nullopt;
  return *w + *rd + *st;
}

std::string failureOf(const json& r) {
  const json* f = find(r, {"failed"});
  if (!f) return "";
  const std::string why = text(find(*f, {"reason"}));
  return why.empty() ? "failed" : why;
}

std::optional<double> memoryMiB(const json& r, const char* key) {
  const std::optional<double> bytes = number(find(r, {"memory", key}));
  if (!bytes) return std::nullopt;
  return *bytes / kMiB;
}

ReportData buildReport(const json& doc) {
  if (!doc.is_object()) throw InputError("results document: expected a JSON object");
  ReportData d;
  const std::string suite = text(find(doc, {"suite", "name"}));
  d.title = "strandbench report" + (suite.empty() ? "" : ": " + suite);
  d.description = text(find(doc, {"suite", "description"}));

  if (const json* rs = find(doc, {"results"}); rs && rs->is_array())
    for (const json& r : *rs)
      if (r.is_object()) d.results.push_back(&r);

  // Context: the known keys with readable labels first, then any others.
  auto add = [&](const std::string& label, std::string value) {
    if (!value.empty()) d.context.emplace_back(label, std::move(value));
  };
  add("Suite file", text(find(doc, {"suite", "file"})));
  add("Results", std::to_string(d.results.size()));
  for (const json* r : d.results)
    if (const std::string why = failureOf(*r); !why.empty())
      d.failures.push_back({caseId(*r), why});
  if (!d.failures.empty()) add("Failed cases", std::to_string(d.failures.size()));
  const json empty = json::object();
  const json* ctx = find(doc, {"context"});
  if (!ctx || !ctx->is_object()) ctx = &empty;
  const std::vector<std::pair<const char*, const char*>> known = {
      {"date", "Date"},         {"commit", "Commit"}, {"build_type", "Build type"},
      {"compiler", "Compiler"}, {"cpu", "CPU"},       {"os", "OS"},
      {"mesa", "Mesa"}};
  for (const auto& [key, label] : known) {
    std::string v = text(find(*ctx, {key}));
    if (std::string_view(key) == "commit" && find(*ctx, {"commit_dirty"}) &&
        *find(*ctx, {"commit_dirty"}) == true)
      v += " (with uncommitted changes)";
    add(label, v);
  }
  for (const auto& [key, value] : ctx->items()) {
    const bool isKnown =
        std::any_of(known.begin(), known.end(), [&](const auto& k) { return key == k.first; });
    if (!isKnown && key != "devices" && key != "commit_dirty") add(key, text(&value));
  }
  d.devices.header = {"Backend", "Platform", "Device", "Driver", "Timing"};
  if (const json* devs = find(*ctx, {"devices"}); devs && devs->is_array()) {
    for (const json& dev : *devs) {
      std::vector<Cell> row;
      for (const char* k : {"backend", "platform", "device", "driver", "timing"})
        row.push_back({orDefault(text(find(dev, {k})), kNone)});
      d.devices.rows.push_back(std::move(row));
    }
  }

  if (const json* ts = find(doc, {"tables"}); ts && ts->is_array())
    for (const json& t : *ts) d.paperTables.push_back(buildPaperTable(t, d.results));

  // Groups in suite order, then any group that only the results name.
  std::vector<std::string> names;
  std::map<std::string, const json*> described;
  if (const json* gs = find(doc, {"groups"}); gs && gs->is_array()) {
    for (const json& g : *gs) {
      const std::string name = text(find(g, {"name"}));
      if (described.count(name)) continue;
      names.push_back(name);
      described[name] = &g;
    }
  }
  for (const json* r : d.results) {
    const std::string g = groupOf(*r);
    if (std::find(names.begin(), names.end(), g) == names.end()) names.push_back(g);
  }
  for (const std::string& name : names) {
    auto it = described.find(name);
    d.groups.push_back(buildGroup(name, it == described.end() ? nullptr : it->second, d.results));
  }

  std::vector<std::string> keys;
  std::map<std::string, std::vector<const json*>> byKey;
  for (const json* r : d.results) {
    if (!find(*r, {"error", "image", "rmse"})) continue;
    const std::string key = comparableKey(*r);
    if (!byKey.count(key)) keys.push_back(key);
    byKey[key].push_back(r);
  }
  for (const std::string& key : keys) {
    BudgetTable b = buildBudgetTable(key, byKey[key]);
    if (!b.table.rows.empty()) d.budgets.push_back(std::move(b));
  }

  d.animationTable.header = {
      "Case",          "Technique",          "Animation",      "Frames",
      "Flicker image", "Flicker visibility", "FLIP per frame", "Visibility RMSE per frame"};
  const bool nameOit = anyTransparency(d.results), nameShadow = anyShadow(d.results);
  for (const json* r : d.results) {
    const json* a = find(*r, {"animation"});
    if (!a || !a->is_object()) continue;
    Animation an{r, caseId(*r), shortTechniqueOf(*r, nameOit, nameShadow),
                 text(find(*a, {"kind"})) + ":frames=" + text(find(*a, {"frames"})) +
                     ",degrees=" + text(find(*a, {"degrees"}))};
    std::string flips, vis;
    if (const json* frames = find(*a, {"per_frame"}); frames && frames->is_array())
      for (const json& f : *frames) {
        const auto fl = number(find(f, {"image", "flip"}));
        const auto v = number(find(f, {"visibility", "rmse"}));
        // Appended piecewise: GCC 12 misreports `"" + std::string` as -Wrestrict.
        if (!flips.empty()) flips += ' ', vis += ' ';
        flips += fl ? formatSig(*fl, 2) : std::string(kNone);
        vis += v ? formatSig(*v, 2) : std::string(kNone);
      }
    d.animationTable.rows.push_back({{an.caseId},
                                     {an.technique},
                                     {text(find(*a, {"kind"}))},
                                     {text(find(*a, {"frames"})), true},
                                     num(number(find(*a, {"flicker", "image"}))),
                                     num(number(find(*a, {"flicker", "visibility"}))),
                                     {flips},
                                     {vis}});
    d.animations.push_back(std::move(an));
  }

  d.costModels = fitCostModels(d.results);

  for (const json* r : d.results) {
    if (const json* ws = find(*r, {"warnings"}); ws && ws->is_array())
      for (const json& w : *ws) d.warnings.push_back({caseId(*r), text(&w)});
  }
  return d;
}

std::vector<std::string> moreReferenceNames(const std::vector<const json*>& results) {
  std::vector<std::string> names;
  for (const json* r : results) {
    const json* error = find(*r, {"error"});
    if (!error || !error->is_object()) continue;
    for (const auto& [name, e] : error->items())
      if (e.is_object() && find(e, {"reference", "spec"}) &&
          std::find(names.begin(), names.end(), name) == names.end())
        names.push_back(name);
  }
  return names;
}

}  // namespace sb::report
