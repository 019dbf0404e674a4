#include "reports/history.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>

#include "base/errors.h"
#include "reports/files.h"
#include "reports/svg_chart.h"

namespace sb {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::string percent(double fraction) {
  std::ostringstream s;
  s << std::showpos << std::fixed << std::setprecision(1) << fraction * 100 << "%";
  return s.str();
}

std::string number(double v, int precision = 3) {
  std::ostringstream s;
  s << std::setprecision(precision) << v;
  return s.str();
}

// "run 3 of 5 (date): pass a: ...; pass b added: ..."
std::string workStepText(const CaseHistory& c, const WorkStep& w) {
  std::string s = "run " + std::to_string(w.index + 1) + " of " + std::to_string(c.points.size()) +
                  " (" + c.points[std::size_t(w.index)].date + "): ";
  for (std::size_t i = 0; i < w.passes.size(); ++i)
    s += (i ? "; " : "") + describeWorkChange(w.passes[i]);
  return s;
}

}  // namespace

History buildHistory(const std::vector<RunResults>& runs, const HistoryOptions& o) {
  History h;
  std::map<std::string, CaseHistory> byId;
  std::vector<std::string> order;               // first appearance
  std::map<std::string, const json*> previous;  // each case's result in the last run that had it
  for (const RunResults& run : runs) {
    h.runs.push_back(run.source);
    const std::string date = run.context.is_object() ? run.context.value("date", "") : "";
    for (const json& r : run.results) {
      if (!r.contains("frame_ms") || r.contains("failed")) continue;
      const std::string id = r["case"]["id"].get<std::string>();
      const json& ms = r["frame_ms"];
      std::vector<double> samples;
      if (ms.contains("samples")) samples = ms["samples"].get<std::vector<double>>();
      HistoryPoint p;
      p.run = run.source;
      p.date = date;
      p.samples = static_cast<int>(samples.size());
      p.median = samples.empty() ? Interval{ms.value("median", 0.0), ms.value("median", 0.0),
                                            ms.value("median", 0.0)}
                                 : bootstrapMedian(samples);
      if (!byId.count(id)) order.push_back(id);
      CaseHistory& c = byId[id];
      c.id = id;
      c.points.push_back(p);
      const auto prev = previous.find(id);
      if (prev != previous.end() && definitionChanges(*prev->second, r).empty()) {
        WorkComparison w = compareWork(*prev->second, r);
        if (w.status == WorkStatus::Changed)
          c.workChanges.push_back({static_cast<int>(c.points.size()) - 1, std::move(w.passes)});
      }
      previous[id] = &r;
    }
  }
  ChangePointOptions cp;
  cp.alpha = o.alpha;
  cp.permutations = o.permutations;
  for (const std::string& id : order) {
    CaseHistory c = byId[id];
    std::vector<double> series;
    for (const auto& p : c.points) series.push_back(p.median.estimate);
    c.changes = findChangePoints(series, cp);
    const int n = static_cast<int>(series.size());
    if (c.changes.empty()) {
      c.verdict = "no change (" + std::to_string(n) + " runs)";
    } else {
      const ChangePoint& last = c.changes.back();
      c.alarm = last.size * 100 > o.thresholdPct && last.index >= n - o.recent;
      c.verdict = std::string(last.size > 0 ? "slower" : "faster") + " by " + percent(last.size) +
                  " from run " + std::to_string(last.index + 1) + " of " + std::to_string(n) +
                  " (" + c.points[std::size_t(last.index)].date + "), p = " + number(last.p, 2) +
                  (c.alarm ? "  ALARM" : "");
    }
    if (!c.workChanges.empty())
      c.verdict += "; work changed at run " + std::to_string(c.workChanges.back().index + 1);
    h.alarms += c.alarm;
    h.workChanged += !c.workChanges.empty();
    h.cases.push_back(std::move(c));
  }
  std::stable_sort(h.cases.begin(), h.cases.end(), [](const CaseHistory& a, const CaseHistory& b) {
    return std::abs(a.latestChange()) > std::abs(b.latestChange());
  });
  return h;
}

json historyJson(const History& h, const HistoryOptions& o) {
  json doc = {{"method",
               "change points: binary segmentation with Pettitt's standardized rank statistic, "
               "permutation p-value (reports/stats.h findChangePoints); medians' 95% intervals: "
               "percentile bootstrap over the repetitions"},
              {"alpha", o.alpha},
              {"threshold_pct", o.thresholdPct},
              {"recent", o.recent},
              {"permutations", o.permutations},
              {"runs", h.runs},
              {"alarms", h.alarms},
              {"work_changed", h.workChanged},
              {"cases", json::array()}};
  for (const auto& c : h.cases) {
    json work = json::array();
    for (const auto& w : c.workChanges)
      work.push_back({{"index", w.index},
                      {"run", c.points[std::size_t(w.index)].run},
                      {"date", c.points[std::size_t(w.index)].date},
                      {"passes", workChangesJson(w.passes)}});
    json points = json::array(), changes = json::array();
    for (const auto& p : c.points)
      points.push_back({{"run", p.run},
                        {"date", p.date},
                        {"median", p.median.estimate},
                        {"ci95", {p.median.low, p.median.high}},
                        {"samples", p.samples}});
    for (const auto& ch : c.changes)
      changes.push_back({{"index", ch.index},
                         {"run", c.points[std::size_t(ch.index)].run},
                         {"date", c.points[std::size_t(ch.index)].date},
                         {"before", ch.before},
                         {"after", ch.after},
                         {"size", ch.size},
                         {"p", ch.p}});
    doc["cases"].push_back({{"id", c.id},
                            {"points", points},
                            {"changes", changes},
                            {"work_changes", work},
                            {"alarm", c.alarm},
                            {"verdict", c.verdict}});
  }
  return doc;
}

namespace {

// One small chart: the medians joined by a line, each with its interval as a vertical bar,
// a dashed vertical line at each change point (red for a slowdown, green for a speed-up).
std::string caseChart(const CaseHistory& c) {
  const double w = 420, hgt = 120, left = 48, right = 8, top = 8, bottom = 18;
  double lo = 1e300, hi = -1e300;
  for (const auto& p : c.points) {
    lo = std::min({lo, p.median.low, p.median.estimate});
    hi = std::max({hi, p.median.high, p.median.estimate});
  }
  if (!(hi > lo)) hi = lo + 1;
  const double pad = 0.05 * (hi - lo);
  lo -= pad;
  hi += pad;
  const std::size_t n = c.points.size();
  auto x = [&](std::size_t i) {
    return left + (n > 1 ? double(i) / double(n - 1) : 0.5) * (w - left - right);
  };
  auto y = [&](double v) { return top + (hi - v) / (hi - lo) * (hgt - top - bottom); };
  std::ostringstream s;
  s << std::fixed << std::setprecision(1);
  s << "<svg class=\"history\" width=\"" << w << "\" height=\"" << hgt << "\" viewBox=\"0 0 " << w
    << " " << hgt << "\">";
  s << "<line x1=\"" << left << "\" y1=\"" << top << "\" x2=\"" << left << "\" y2=\""
    << hgt - bottom << "\" stroke=\"#888\"/>";
  s << "<text x=\"2\" y=\"" << top + 8 << "\" font-size=\"9\">" << number(hi - pad)
    << "</text><text x=\"2\" y=\"" << hgt - bottom << "\" font-size=\"9\">" << number(lo + pad)
    << "</text><text x=\"" << left << "\" y=\"" << hgt - 4
    << "\" font-size=\"9\">run 1</text><text x=\"" << w - right - 40 << "\" y=\"" << hgt - 4
    << "\" font-size=\"9\">run " << n << "</text>";
  for (const auto& ch : c.changes) {
    const double cx = 0.5 * (x(std::size_t(ch.index)) + x(std::size_t(ch.index) - 1));
    s << "<line class=\"change\" x1=\"" << cx << "\" y1=\"" << top << "\" x2=\"" << cx << "\" y2=\""
      << hgt - bottom << "\" stroke=\"" << (ch.size > 0 ? "#c00" : "#080")
      << "\" stroke-dasharray=\"4 3\"><title>" << htmlEscape(percent(ch.size)) << ", p "
      << number(ch.p, 2) << "</title></line>";
  }
  for (const auto& wc : c.workChanges) {
    const double cx = 0.5 * (x(std::size_t(wc.index)) + x(std::size_t(wc.index) - 1));
    s << "<line class=\"work\" x1=\"" << cx << "\" y1=\"" << top << "\" x2=\"" << cx << "\" y2=\""
      << hgt - bottom
      << "\" stroke=\"#888\" stroke-dasharray=\"1 2\"><title>work changed</title></line>";
  }
  s << "<polyline fill=\"none\" stroke=\"#36c\" points=\"";
  for (std::size_t i = 0; i < n; ++i) s << x(i) << "," << y(c.points[i].median.estimate) << " ";
  s << "\"/>";
  for (std::size_t i = 0; i < n; ++i) {
    const auto& p = c.points[i];
    s << "<line x1=\"" << x(i) << "\" x2=\"" << x(i) << "\" y1=\"" << y(p.median.low) << "\" y2=\""
      << y(p.median.high) << "\" stroke=\"#36c\" stroke-opacity=\"0.5\"/>"
      << "<circle cx=\"" << x(i) << "\" cy=\"" << y(p.median.estimate)
      << "\" r=\"2\" fill=\"#36c\"><title>" << htmlEscape(p.date + "  " + p.run) << ": "
      << number(p.median.estimate) << " ms [" << number(p.median.low) << ", "
      << number(p.median.high) << "]</title></circle>";
  }
  s << "</svg>";
  return s.str();
}

}  // namespace

std::string historyHtml(const History& h, const HistoryOptions& o) {
  std::ostringstream s;
  s << "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>strandbench history</title>"
       "<style>body{font:13px sans-serif;margin:16px}.case{display:inline-block;margin:6px;"
       "vertical-align:top}.alarm h3,li.alarm{color:#c00}h3{font-size:12px;margin:2px 0}"
       "p.v{margin:0;font-size:11px;color:#444}</style></head><body>";
  s << "<h1>Frame time over " << h.runs.size() << " runs</h1>";
  // Work first: exact, so each entry is a fact; then the time changes, which are judgments.
  s << "<h2>Work changed</h2>";
  if (h.workChanged == 0) {
    s << "<p>None: every case counted the same work as in its previous run (or did not count "
         "work).</p>";
  } else {
    s << "<ul class=\"work\">";
    for (const auto& c : h.cases)
      for (const auto& w : c.workChanges)
        s << "<li><b>" << htmlEscape(c.id) << "</b>: " << htmlEscape(workStepText(c, w)) << "</li>";
    s << "</ul>";
  }
  s << "<h2>Time changed</h2>";
  bool anyTime = false;
  for (const auto& c : h.cases)
    if (!c.changes.empty()) {
      s << (anyTime ? "" : "<ul class=\"time\">") << "<li" << (c.alarm ? " class=\"alarm\"" : "")
        << "><b>" << htmlEscape(c.id) << "</b>: " << htmlEscape(c.verdict) << "</li>";
      anyTime = true;
    }
  s << (anyTime ? "</ul>" : "<p>None: no change points.</p>");
  s << "<p>" << h.cases.size() << " cases, " << h.alarms
    << " alarms. Each point: the frame_ms median of a run with its 95% bootstrap interval. "
       "Dashed lines: change points (binary segmentation, Pettitt's rank statistic with a "
       "permutation p-value, alpha "
    << o.alpha << "); red a slowdown, green a speed-up. Alarm: a slowdown above " << o.thresholdPct
    << "% starting within the newest " << o.recent
    << " runs. Dotted grey lines: work changes. Sorted by the size of the latest change.</p>";
  for (const auto& c : h.cases)
    s << "<div class=\"case" << (c.alarm ? " alarm" : "") << "\"><h3>" << htmlEscape(c.id)
      << "</h3>" << caseChart(c) << "<p class=\"v\">" << htmlEscape(c.verdict) << "</p></div>";
  s << "</body></html>\n";
  return s.str();
}

int runHistory(const std::vector<std::string>& paths, const std::string& out,
               const HistoryOptions& o, std::ostream& log) {
  if (o.alpha <= 0 || o.alpha >= 1) throw InputError("--alpha: must be in (0, 1)");
  if (!(o.thresholdPct >= 0)) throw InputError("--threshold: must be a percentage >= 0");
  if (o.recent < 1) throw InputError("--recent: must be at least 1");
  std::vector<std::string> expanded;
  for (const std::string& p : paths) {
    std::error_code ec;
    const fs::path dir(p);
    if (fs::is_directory(dir, ec) && !fs::exists(dir / "results.json", ec) &&
        !fs::exists(dir / "cases", ec)) {
      // A folder of nightly runs: every sub-folder that is a run.
      std::vector<std::string> inner;
      for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.is_directory() &&
            (fs::exists(e.path() / "results.json") || fs::exists(e.path() / "cases")))
          inner.push_back(e.path().string());
      if (inner.empty())
        throw InputError(p + ": neither a run (results.json, cases/) nor a folder of runs");
      std::sort(inner.begin(), inner.end());
      expanded.insert(expanded.end(), inner.begin(), inner.end());
    } else {
      expanded.push_back(p);
    }
  }
  std::vector<RunResults> runs;
  for (const std::string& p : expanded) {
    RunResults r = loadRunResults(p);
    if (!r.context.is_object() || !r.context.contains("date") || !r.context["date"].is_string())
      throw InputError(p + ": no context.date (history orders runs by their date)");
    runs.push_back(std::move(r));
  }
  if (runs.size() < 2) throw InputError("history: needs at least two runs");
  std::stable_sort(runs.begin(), runs.end(), [](const RunResults& a, const RunResults& b) {
    return a.context["date"].get<std::string>() < b.context["date"].get<std::string>();
  });
  const History h = buildHistory(runs, o);
  const fs::path dir(out);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw InputError("--out " + out + ": cannot create the folder");
  writeFileAtomic(dir / "history.json", historyJson(h, o).dump(1) + "\n");
  writeFileAtomic(dir / "history.html", historyHtml(h, o));
  if (h.workChanged == 0) {
    log << "work changed: none\n";
  } else {
    log << "work changed: " << h.workChanged << " case" << (h.workChanged == 1 ? "" : "s") << "\n";
    for (const auto& c : h.cases)
      for (const auto& w : c.workChanges) log << "  " << c.id << ": " << workStepText(c, w) << "\n";
  }
  int timeChanged = 0;
  for (const auto& c : h.cases) timeChanged += !c.changes.empty();
  if (timeChanged == 0) {
    log << "time changed: none (" << h.alarms << " alarms)\n";
  } else {
    log << "time changed: " << timeChanged << " case" << (timeChanged == 1 ? "" : "s") << ", "
        << h.alarms << " alarm" << (h.alarms == 1 ? "" : "s") << "\n";
    for (const auto& c : h.cases)
      if (!c.changes.empty()) log << "  " << c.id << ": " << c.verdict << "\n";
  }
  log << "history of " << h.cases.size() << " cases over " << h.runs.size() << " runs ("
      << runs.front().context["date"].get<std::string>() << " .. "
      << runs.back().context["date"].get<std::string>() << ")\n";
  log << "wrote " << (dir / "history.json").string() << ", history.html; " << h.alarms << " alarm"
      << (h.alarms == 1 ? "" : "s") << "\n";
  return h.alarms ? 1 : 0;
}

}  // namespace sb
