// `strandbench compare-runs OLD NEW [--threshold PCT] [--alpha A] [--json]`.
//
// Rules (also in the command's help):
//  - OLD and NEW are each a results.json, a sweep folder holding results.json, or a sweep folder
//    holding only cases/*.json (an unfinished or unreported sweep). Anything else, or a file that
//    is not the documented format, is bad input: message naming the file, exit status 2.
//  - Results are matched by case.id (which includes the backend). Cases in only one run are
//    listed as "added" / "removed" and never fail the comparison. A matched case whose
//    definition differs (scene.spec, shadow, oit, size, primitive) is "definition changed" and
//    not judged: its timings measure different work.
//  - A matched case is judged on frame_ms: change = (new median - old median) / old median. Its
//    repetitions (frame_ms.samples) are compared with a one-sided Mann-Whitney U test in the
//    direction of the change (reports/stats.h: exact null distribution when there are no ties
//    and m*n <= 2500, else the normal approximation with tie and continuity correction).
//      SLOWER: change > +threshold and p < alpha   (a regression: exit status 1)
//      faster: change < -threshold and p < alpha   (information)
//      ok:     otherwise
//  - Not judged (never a regression, said so in the table):
//      "no samples": either run lacks frame_ms.samples. The summary statistics (median, min,
//        max, stddev) are not enough for a test over the repetitions, and a threshold alone
//        would flag noise, so no verdict is given; the medians and change are still shown.
//      "too few repetitions": even a complete separation of the samples could not give
//        p < alpha, i.e. 1 / C(m+n, m) >= alpha (3 vs 3 repetitions give 0.05 at best, so the
//        default alpha needs at least 3 vs 4 or 4 vs 4).
//      "old median is 0": no relative change.
//  - Passes (passes[].ms) are judged the same way and listed under their case when they are
//    slower or faster, or exist in only one run; information only (written "slower" in lower
//    case: only a case's frame time fails the comparison).
//  - Work (passes[].work) is judged apart from time and exactly: the counters are the same
//    every time a case runs, so any difference in any counter of any pass, and any pass in only
//    one run, is a change of work (compareWork). It shows, first, but fails the comparison only
//    with --fail-on-work-change: a change of work is often the intended effect of a commit.
//    Results without work (older runs) are "not counted": neither a change nor an error.
#include "reports/compare_runs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include "base/errors.h"
#include "reports/json_file.h"
#include "reports/report_data.h"
#include "reports/stats.h"

namespace sb {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

bool isFiniteNumber(const json& v) { return v.is_number() && std::isfinite(v.get<double>()); }

// Checks a timing object ({median, samples?, ...}) and fills in a missing median from the
// samples. `what` names it in messages.
void validateTiming(json& ms, const std::string& what) {
  if (!ms.is_object()) throw InputError(what + " must be an object");
  if (ms.contains("samples")) {
    const json& s = ms["samples"];
    if (!s.is_array() || !std::all_of(s.begin(), s.end(), isFiniteNumber))
      throw InputError(what + ".samples must be an array of numbers");
  }
  if (ms.contains("median")) {
    if (!isFiniteNumber(ms["median"])) throw InputError(what + ".median must be a number");
  } else if (ms.contains("samples") && !ms["samples"].empty()) {
    ms["median"] = median(ms["samples"].get<std::vector<double>>());
  } else {
    throw InputError(what + " has neither median nor samples");
  }
}

// Checks one result object; `where` names the file (and index) in messages.
void validateResult(json& r, const std::string& where) {
  if (!r.is_object()) throw InputError(where + ": a result must be an object");
  if (!r.contains("case") || !r["case"].is_object() || !r["case"].contains("id") ||
      !r["case"]["id"].is_string())
    throw InputError(where + ": a result lacks case.id");
  const std::string prefix = where + " (case " + r["case"]["id"].get<std::string>() + "): ";
  // A case a sweep recorded as failed has no timings: it is left out (shown
  // as removed or added when the other run has it).
  if (r.contains("failed")) return;
  if (!r.contains("frame_ms")) throw InputError(prefix + "no frame_ms");
  validateTiming(r["frame_ms"], prefix + "frame_ms");
  if (r.contains("passes")) {
    if (!r["passes"].is_array()) throw InputError(prefix + "passes must be an array");
    for (std::size_t i = 0; i < r["passes"].size(); ++i) {
      json& pass = r["passes"][i];
      const std::string name = prefix + "passes[" + std::to_string(i) + "]";
      if (!pass.is_object() || !pass.contains("name") || !pass["name"].is_string())
        throw InputError(name + " lacks a name");
      if (!pass.contains("ms")) throw InputError(name + " has no ms");
      validateTiming(pass["ms"], name + ".ms");
      if (pass.contains("work") && !pass["work"].is_object())
        throw InputError(name + ".work must be an object");
    }
  }
  if (r.contains("frame_work") && !r["frame_work"].is_object())
    throw InputError(prefix + "frame_work must be an object");
}

RunResults loadResultsFile(const fs::path& file) {
  RunResults run;
  run.source = file.string();
  json doc = readJsonFile(file);
  if (!doc.is_object()) throw InputError(run.source + ": not a results.json (not an object)");
  if (doc.contains("schema_version") && doc["schema_version"] != 1)
    throw InputError(run.source + ": unsupported schema_version " + doc["schema_version"].dump());
  if (!doc.contains("results") || !doc["results"].is_array())
    throw InputError(run.source + ": not a results.json (no \"results\" array)");
  if (doc.contains("context")) run.context = doc["context"];
  if (doc.contains("suite") && doc["suite"].is_object() && doc["suite"].contains("name") &&
      doc["suite"]["name"].is_string())
    run.suite = doc["suite"]["name"].get<std::string>();
  for (std::size_t i = 0; i < doc["results"].size(); ++i) {
    json& r = doc["results"][i];
    validateResult(r, run.source + ": results[" + std::to_string(i) + "]");
    if (!r.contains("failed")) run.results.push_back(std::move(r));
  }
  return run;
}

RunResults loadCaseFiles(const fs::path& folder, const fs::path& cases) {
  RunResults run;
  run.source = cases.string();
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::directory_iterator it(cases, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file(ec) && it->path().extension() == ".json") files.push_back(it->path());
  if (ec) throw InputError(run.source + ": cannot be listed (" + ec.message() + ")");
  if (files.empty())
    throw InputError(folder.string() + ": no results.json and no case files in " + run.source);
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    json r = readJsonFile(f);
    validateResult(r, f.string());
    if (!r.contains("failed")) run.results.push_back(std::move(r));
  }
  // The order of the suite, as results.json has it.
  auto index = [](const json& r) {
    const json& c = r["case"];
    return c.contains("index") && c["index"].is_number() ? c["index"].get<double>() : 1e300;
  };
  std::stable_sort(run.results.begin(), run.results.end(),
                   [&](const json& a, const json& b) { return index(a) < index(b); });
  if (fs::is_regular_file(folder / "context.json"))
    run.context = readJsonFile(folder / "context.json");
  if (fs::is_regular_file(folder / "sweep.json")) {
    const json sweep = readJsonFile(folder / "sweep.json");
    if (sweep.contains("suite") && sweep["suite"].is_object() && sweep["suite"].contains("name") &&
        sweep["suite"]["name"].is_string())
      run.suite = sweep["suite"]["name"].get<std::string>();
  }
  return run;
}

std::string caseId(const json& r) { return r["case"]["id"].get<std::string>(); }

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

std::string formatP(double p) { return p < 1e-4 ? format("%.1e", p) : format("%.3g", p); }

// Passes never fail a comparison, so their slowdowns are written in lower case.
std::string verdictText(const TimingChange& t, bool pass) {
  std::string s = pass && t.verdict == Verdict::Slower ? "slower" : verdictName(t.verdict);
  if (!t.note.empty()) s += " (" + t.note + ")";
  return s;
}

json optionalJson(const std::optional<double>& v) { return v ? json(*v) : json(); }

json timingJson(const TimingChange& t) {
  return {{"verdict", verdictName(t.verdict)},
          {"note", t.note},
          {"old_median", optionalJson(t.oldMedian)},
          {"new_median", optionalJson(t.newMedian)},
          {"change_pct", optionalJson(t.changePct)},
          {"p", optionalJson(t.p)},
          {"p_adjusted", optionalJson(t.pAdjusted)},
          {"exact", t.exact},
          {"old_samples", t.oldSamples},
          {"new_samples", t.newSamples}};
}

std::string runLabel(const RunResults& run) {
  std::string s = run.source;
  const json& c = run.context;
  if (c.is_object()) {
    std::vector<std::string> parts;
    if (c.contains("commit") && c["commit"].is_string()) {
      std::string commit = c["commit"].get<std::string>().substr(0, 10);
      if (c.value("commit_dirty", false)) commit += " (dirty)";
      parts.push_back("commit " + commit);
    }
    if (c.contains("date") && c["date"].is_string()) parts.push_back(c["date"].get<std::string>());
    if (!parts.empty()) {
      s += " [";
      for (std::size_t i = 0; i < parts.size(); ++i) s += (i ? ", " : "") + parts[i];
      s += "]";
    }
  }
  return s + ", " + std::to_string(run.results.size()) + " cases";
}

// The context keys that make timings incomparable when they differ.
std::vector<std::string> contextDifferences(const json& a, const json& b) {
  std::vector<std::string> diff;
  if (!a.is_object() || !b.is_object()) return diff;
  for (const char* key : {"cpu", "os", "mesa", "build_type", "compiler", "devices"}) {
    const json va = a.contains(key) ? a[key] : json();
    const json vb = b.contains(key) ? b[key] : json();
    if (va != vb) diff.push_back(key);
  }
  return diff;
}

// A result counts work when it has frame_work or work in a pass (runs from before the
// counters have neither).
bool countsWork(const json& r) {
  if (r.contains("frame_work") && r["frame_work"].is_object()) return true;
  if (r.contains("passes"))
    for (const json& p : r["passes"])
      if (p.contains("work") && p["work"].is_object()) return true;
  return false;
}

// The counters of a pass: every number in its work except the resource list.
std::vector<std::pair<std::string, double>> countersOf(const json& pass) {
  std::vector<std::pair<std::string, double>> out;
  if (!pass.contains("work") || !pass["work"].is_object()) return out;
  for (const auto& [key, v] : pass["work"].items())
    if (key != "resources" && isFiniteNumber(v)) out.emplace_back(key, v.get<double>());
  return out;
}

// Counters are counts: written whole (200000, not 2e+05), as render --json writes them.
bool isCount(double v) { return v == std::floor(v) && std::abs(v) < 9007199254740992.0; }
std::string counterText(double v) {
  return isCount(v) ? std::to_string(static_cast<std::int64_t>(v)) : report::shortest(v);
}
json counterJson(const std::optional<double>& v) {
  return v && isCount(*v) ? json(static_cast<std::int64_t>(*v)) : optionalJson(v);
}

// Passes by name; a name that repeats keeps its occurrences in order (k-th matches k-th).
std::map<std::string, std::vector<const json*>> passesByName(const json& r) {
  std::map<std::string, std::vector<const json*>> out;
  if (r.contains("passes"))
    for (const json& p : r["passes"]) out[p["name"].get<std::string>()].push_back(&p);
  return out;
}

}  // namespace

std::vector<std::string> definitionChanges(const json& a, const json& b) {
  static const std::vector<std::pair<std::string, json::json_pointer>> kFields = {
      {"scene", json::json_pointer("/scene/spec")},
      {"shadow", json::json_pointer("/shadow")},
      {"oit", json::json_pointer("/oit")},
      {"size", json::json_pointer("/size")},
      {"primitive", json::json_pointer("/primitive")}};
  std::vector<std::string> changed;
  for (const auto& [name, ptr] : kFields) {
    const json va = a.contains(ptr) ? a[ptr] : json();
    const json vb = b.contains(ptr) ? b[ptr] : json();
    if (va != vb) changed.push_back(name + " " + va.dump() + " -> " + vb.dump());
  }
  return changed;
}

std::optional<double> CounterChange::ratio() const {
  if (!oldValue || !newValue || *oldValue == 0) return std::nullopt;
  return *newValue / *oldValue;
}

std::optional<double> CounterChange::changePct() const {
  const auto r = ratio();
  return r ? std::optional<double>((*r - 1.0) * 100.0) : std::nullopt;
}

const char* passWorkKindName(PassWorkKind k) {
  switch (k) {
    case PassWorkKind::Changed:
      return "changed";
    case PassWorkKind::Added:
      return "added";
    case PassWorkKind::Removed:
      return "removed";
  }
  return "?";
}

const char* workStatusName(WorkStatus s) {
  switch (s) {
    case WorkStatus::Same:
      return "same";
    case WorkStatus::Changed:
      return "changed";
    case WorkStatus::NotCounted:
      return "not counted";
    case WorkStatus::NotCompared:
      return "not compared";
  }
  return "?";
}

std::size_t WorkComparison::counterCount() const {
  std::size_t n = 0;
  for (const auto& p : passes) n += p.counters.size();
  return n;
}

WorkComparison compareWork(const json& a, const json& b) {
  WorkComparison w;
  const bool oldCounts = countsWork(a), newCounts = countsWork(b);
  if (!oldCounts || !newCounts) {
    w.status = WorkStatus::NotCounted;
    w.note = !oldCounts && !newCounts ? "neither run counted work"
             : !oldCounts             ? "the old run did not count work"
                                      : "the new run did not count work";
    return w;
  }
  auto listAll = [](const json& pass, PassWorkKind kind) {
    PassWorkChange c;
    c.pass = pass["name"].get<std::string>();
    c.kind = kind;
    for (const auto& [key, v] : countersOf(pass)) {
      CounterChange cc;
      cc.counter = key;
      (kind == PassWorkKind::Added ? cc.newValue : cc.oldValue) = v;
      c.counters.push_back(std::move(cc));
    }
    return c;
  };
  const auto oldByName = passesByName(a);
  std::map<std::string, std::size_t> seen;  // occurrences of each name in NEW so far
  if (b.contains("passes")) {
    for (const json& p : b["passes"]) {
      const std::string name = p["name"].get<std::string>();
      const std::size_t k = seen[name]++;
      const auto it = oldByName.find(name);
      if (it == oldByName.end() || k >= it->second.size()) {
        w.passes.push_back(listAll(p, PassWorkKind::Added));
        continue;
      }
      const auto before = countersOf(*it->second[k]);
      const auto afterList = countersOf(p);
      const std::map<std::string, double> after(afterList.begin(), afterList.end());
      PassWorkChange c;
      c.pass = name;
      for (const auto& [key, v] : before) {
        const auto n = after.find(key);
        if (n == after.end() || n->second == v) continue;
        CounterChange cc;
        cc.counter = key;
        cc.oldValue = v;
        cc.newValue = n->second;
        c.counters.push_back(std::move(cc));
      }
      if (!c.counters.empty()) w.passes.push_back(std::move(c));
    }
  }
  for (const auto& [name, passes] : oldByName)
    for (std::size_t k = seen[name]; k < passes.size(); ++k)
      w.passes.push_back(listAll(*passes[k], PassWorkKind::Removed));
  w.status = w.passes.empty() ? WorkStatus::Same : WorkStatus::Changed;
  return w;
}

std::string describeWorkChange(const PassWorkChange& p) {
  std::string s =
      "pass " + p.pass +
      (p.kind == PassWorkKind::Changed ? "" : std::string(" ") + passWorkKindName(p.kind)) + ":";
  if (p.counters.empty()) s += " (no counters)";
  for (std::size_t i = 0; i < p.counters.size(); ++i) {
    const CounterChange& c = p.counters[i];
    s += (i ? ", " : " ") + c.counter + " ";
    if (p.kind == PassWorkKind::Added) {
      s += counterText(*c.newValue);
    } else if (p.kind == PassWorkKind::Removed) {
      s += counterText(*c.oldValue);
    } else {
      s += counterText(*c.oldValue) + " -> " + counterText(*c.newValue);
      if (const auto r = c.ratio())
        s += " (x" + report::formatSig(*r, 3) + ", " + format("%+.1f%%", *c.changePct()) + ")";
      else
        s += " (from 0)";
    }
  }
  return s;
}

json workChangesJson(const std::vector<PassWorkChange>& passes) {
  json out = json::array();
  for (const auto& p : passes) {
    json counters = json::array();
    for (const auto& c : p.counters)
      counters.push_back({{"counter", c.counter},
                          {"old", counterJson(c.oldValue)},
                          {"new", counterJson(c.newValue)},
                          {"ratio", optionalJson(c.ratio())},
                          {"change_pct", optionalJson(c.changePct())}});
    out.push_back({{"pass", p.pass}, {"change", passWorkKindName(p.kind)}, {"counters", counters}});
  }
  return out;
}

const char* verdictName(Verdict v) {
  switch (v) {
    case Verdict::Ok:
      return "ok";
    case Verdict::Slower:
      return "SLOWER";
    case Verdict::Faster:
      return "faster";
    case Verdict::NotJudged:
      return "not judged";
    case Verdict::DefinitionChanged:
      return "definition changed";
    case Verdict::Added:
      return "added";
    case Verdict::Removed:
      return "removed";
  }
  return "?";
}

RunResults loadRunResults(const std::string& path) {
  const fs::path p(path);
  std::error_code ec;
  if (!fs::exists(p, ec)) throw InputError(path + ": no such file or folder");
  RunResults run;
  if (fs::is_directory(p, ec)) {
    if (fs::is_regular_file(p / "results.json", ec)) {
      run = loadResultsFile(p / "results.json");
    } else if (fs::is_directory(p / "cases", ec)) {
      run = loadCaseFiles(p, p / "cases");
    } else {
      throw InputError(path + ": folder has neither results.json nor cases/*.json");
    }
  } else {
    run = loadResultsFile(p);
  }
  std::set<std::string> seen;
  for (const json& r : run.results)
    if (!seen.insert(caseId(r)).second)
      throw InputError(run.source + ": case " + caseId(r) + " appears more than once");
  return run;
}

RunOverlap runOverlap(const RunResults& oldRun, const RunResults& newRun) {
  RunOverlap o;
  std::set<std::string> oldIds;
  for (const json& r : oldRun.results) oldIds.insert(caseId(r));
  for (const json& r : newRun.results) o.shared += oldIds.count(caseId(r));
  auto label = [](const RunResults& run) {
    return run.source + " (" + (run.suite.empty() ? "" : "suite " + run.suite + ", ") +
           std::to_string(run.results.size()) + (run.results.size() == 1 ? " case)" : " cases)");
  };
  if (o.shared == 0 && !oldRun.results.empty() && !newRun.results.empty())
    throw InputError("the runs share no case: " + label(oldRun) + " and " + label(newRun) +
                     " have no case.id in common, so nothing can be compared (compare two "
                     "runs of the same suite)");
  if (!oldRun.suite.empty() && !newRun.suite.empty() && oldRun.suite != newRun.suite)
    o.warnings.push_back("the runs are of different suites (old " + oldRun.suite + ", new " +
                         newRun.suite + ")");
  const std::size_t larger = std::max(oldRun.results.size(), newRun.results.size());
  if (o.shared * 2 < larger)
    o.warnings.push_back("the runs share only " + std::to_string(o.shared) + " of " +
                         std::to_string(larger) +
                         " cases: the rest are cases added or removed, not compared");
  return o;
}

TimingChange compareTiming(const json& oldMs, const json& newMs, const CompareRunsOptions& opt) {
  TimingChange t;
  const double oldMedian = oldMs.at("median").get<double>();
  const double newMedian = newMs.at("median").get<double>();
  t.oldMedian = oldMedian;
  t.newMedian = newMedian;
  auto samples = [](const json& ms) {
    return ms.contains("samples") ? ms["samples"].get<std::vector<double>>()
                                  : std::vector<double>();
  };
  const std::vector<double> before = samples(oldMs), after = samples(newMs);
  t.oldSamples = static_cast<int>(before.size());
  t.newSamples = static_cast<int>(after.size());
  if (oldMedian > 0) {
    t.changePct = (newMedian - oldMedian) / oldMedian * 100.0;
  } else if (newMedian == oldMedian) {
    t.changePct = 0.0;
  } else {
    t.note = "old median is 0";
    return t;
  }
  if (before.empty() || after.empty()) {
    t.note = "no samples";
    return t;
  }
  const double best = mannWhitneyMinP(t.oldSamples, t.newSamples);
  if (best >= opt.alpha) {
    t.note = "too few repetitions: " + std::to_string(t.oldSamples) + " vs " +
             std::to_string(t.newSamples) + ", best possible p " + formatP(best);
    return t;
  }
  const bool slower = *t.changePct >= 0;
  const RankTest test =
      slower ? mannWhitneyGreater(before, after) : mannWhitneyGreater(after, before);
  t.p = test.p;
  t.exact = test.exact;
  const bool significant = test.p < opt.alpha;
  const bool beyond = std::abs(*t.changePct) > opt.thresholdPct;
  if (beyond && significant) {
    t.verdict = slower ? Verdict::Slower : Verdict::Faster;
  } else {
    t.verdict = Verdict::Ok;
    if (beyond) t.note = "not significant";
  }
  return t;
}

std::vector<CaseComparison> compareRuns(const RunResults& oldRun, const RunResults& newRun,
                                        const CompareRunsOptions& opt) {
  std::map<std::string, const json*> newById;
  for (const json& r : newRun.results) newById[caseId(r)] = &r;
  std::set<std::string> matched;
  std::vector<CaseComparison> out;
  for (const json& a : oldRun.results) {
    CaseComparison c;
    c.id = caseId(a);
    c.frame.name = c.id;
    c.frame.oldMedian = a["frame_ms"]["median"].get<double>();
    const auto it = newById.find(c.id);
    if (it == newById.end()) {
      c.verdict = c.frame.verdict = Verdict::Removed;
      c.work.note = "removed";
      out.push_back(std::move(c));
      continue;
    }
    matched.insert(c.id);
    const json& b = *it->second;
    const std::vector<std::string> changes = definitionChanges(a, b);
    if (!changes.empty()) {
      c.verdict = c.frame.verdict = Verdict::DefinitionChanged;
      c.frame.newMedian = b["frame_ms"]["median"].get<double>();
      for (std::size_t i = 0; i < changes.size(); ++i) c.frame.note += (i ? "; " : "") + changes[i];
      c.work.note = "definition changed";  // other work by definition
      out.push_back(std::move(c));
      continue;
    }
    c.frame = compareTiming(a["frame_ms"], b["frame_ms"], opt);
    c.frame.name = c.id;
    c.verdict = c.frame.verdict;
    c.work = compareWork(a, b);

    const json empty = json::array();
    const json& oldPasses = a.contains("passes") ? a["passes"] : empty;
    const json& newPasses = b.contains("passes") ? b["passes"] : empty;
    std::map<std::string, const json*> oldByName;
    for (const json& p : oldPasses) oldByName[p["name"].get<std::string>()] = &p;
    std::set<std::string> newNames;
    for (const json& p : newPasses) {
      const std::string name = p["name"].get<std::string>();
      newNames.insert(name);
      const auto op = oldByName.find(name);
      TimingChange t;
      if (op == oldByName.end()) {
        t.verdict = Verdict::Added;
        t.newMedian = p["ms"]["median"].get<double>();
      } else {
        t = compareTiming((*op->second)["ms"], p["ms"], opt);
        if (t.verdict != Verdict::Slower && t.verdict != Verdict::Faster) continue;
      }
      t.name = name;
      c.passes.push_back(std::move(t));
    }
    for (const json& p : oldPasses) {
      const std::string name = p["name"].get<std::string>();
      if (newNames.count(name)) continue;
      TimingChange t;
      t.name = name;
      t.verdict = Verdict::Removed;
      t.oldMedian = p["ms"]["median"].get<double>();
      c.passes.push_back(std::move(t));
    }
    out.push_back(std::move(c));
  }
  for (const json& b : newRun.results) {
    if (matched.count(caseId(b))) continue;
    CaseComparison c;
    c.id = c.frame.name = caseId(b);
    c.verdict = c.frame.verdict = Verdict::Added;
    c.frame.newMedian = b["frame_ms"]["median"].get<double>();
    c.work.note = "added";
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<CaseComparison> comparePairedRuns(const std::vector<RunResults>& olds,
                                              const std::vector<RunResults>& news,
                                              const CompareRunsOptions& opt) {
  if (olds.empty() || olds.size() != news.size())
    throw InputError("paired runs: as many old runs as new runs, at least one of each");
  // The first pair decides what is added, removed or redefined.
  std::vector<CaseComparison> out = compareRuns(olds[0], news[0], opt);
  auto find = [](const RunResults& run, const std::string& id) -> const json* {
    for (const json& r : run.results)
      if (caseId(r) == id) return &r;
    return nullptr;
  };
  for (CaseComparison& c : out) {
    c.passes.clear();
    if (c.verdict == Verdict::Added || c.verdict == Verdict::Removed ||
        c.verdict == Verdict::DefinitionChanged)
      continue;
    TimingChange t;
    t.name = c.id;
    std::vector<double> oldMedians, newMedians, logRatios;
    for (std::size_t i = 0; i < olds.size(); ++i) {
      const json* a = find(olds[i], c.id);
      const json* b = find(news[i], c.id);
      if (!a || !b || !definitionChanges(*a, *b).empty() ||
          !definitionChanges(*find(olds[0], c.id), *a).empty()) {
        t.note = "missing or redefined in pair " + std::to_string(i + 1);
        break;
      }
      const double o = (*a)["frame_ms"]["median"].get<double>();
      const double n = (*b)["frame_ms"]["median"].get<double>();
      oldMedians.push_back(o);
      newMedians.push_back(n);
      if (o > 0 && n > 0) logRatios.push_back(std::log(n / o));
    }
    t.oldSamples = t.newSamples = static_cast<int>(oldMedians.size());
    if (t.note.empty() && logRatios.size() != olds.size()) t.note = "a median is 0";
    if (t.note.empty()) {
      t.oldMedian = median(oldMedians);
      t.newMedian = median(newMedians);
      t.changePct = (std::exp(median(logRatios)) - 1.0) * 100.0;
      const double best = signedRankMinP(static_cast<int>(logRatios.size()));
      if (best >= opt.alpha) {
        t.note = "too few pairs: " + std::to_string(logRatios.size()) + ", best possible p " +
                 formatP(best);
      } else {
        const bool slower = *t.changePct >= 0;
        std::vector<double> d = logRatios;
        if (!slower)
          for (double& v : d) v = -v;
        const RankTest test = signedRankGreater(d);
        t.p = test.p;
        t.exact = test.exact;
        const bool beyond = std::abs(*t.changePct) > opt.thresholdPct;
        if (beyond && test.p < opt.alpha) {
          t.verdict = slower ? Verdict::Slower : Verdict::Faster;
        } else {
          t.verdict = Verdict::Ok;
          if (beyond) t.note = "not significant";
        }
      }
    }
    c.frame = t;
    c.verdict = t.verdict;
  }
  return out;
}

void applyCorrection(std::vector<CaseComparison>& cases, const CompareRunsOptions& opt) {
  if (opt.correction == Correction::None) return;
  std::vector<CaseComparison*> judged;
  for (auto& c : cases)
    if (c.frame.p) judged.push_back(&c);
  std::sort(judged.begin(), judged.end(), [](const CaseComparison* a, const CaseComparison* b) {
    return *a->frame.p < *b->frame.p;
  });
  const std::size_t m = judged.size();
  double running = 0.0;  // adjusted p-values are made monotone in the order of the raw ones
  for (std::size_t i = 0; i < m; ++i) {
    TimingChange& t = judged[i]->frame;
    running = std::max(running, std::min(1.0, static_cast<double>(m - i) * *t.p));
    t.pAdjusted = running;
    const bool beyond = std::abs(*t.changePct) > opt.thresholdPct;
    const bool wasSignificant = *t.p < opt.alpha;
    if (beyond && running < opt.alpha) {
      t.verdict = *t.changePct >= 0 ? Verdict::Slower : Verdict::Faster;
    } else {
      t.verdict = Verdict::Ok;
      if (beyond)
        t.note = wasSignificant ? "not significant over " + std::to_string(m) + " cases"
                                : "not significant";
    }
    judged[i]->verdict = t.verdict;
  }
}

int runCompareRuns(const std::string& oldPath, const std::string& newPath,
                   const CompareRunsOptions& opt, bool asJson, std::ostream& out,
                   const std::vector<std::pair<std::string, std::string>>& morePairs) {
  if (!std::isfinite(opt.thresholdPct) || opt.thresholdPct < 0)
    throw InputError("--threshold must be a percentage >= 0");
  if (!(opt.alpha > 0 && opt.alpha < 1)) throw InputError("--alpha must be between 0 and 1");
  const RunResults oldRun = loadRunResults(oldPath);
  const RunResults newRun = loadRunResults(newPath);
  const RunOverlap overlap = runOverlap(oldRun, newRun);
  std::vector<CaseComparison> cases;
  if (morePairs.empty()) {
    cases = compareRuns(oldRun, newRun, opt);
  } else {
    std::vector<RunResults> olds{oldRun}, news{newRun};
    for (const auto& [o, n] : morePairs) {
      olds.push_back(loadRunResults(o));
      news.push_back(loadRunResults(n));
    }
    cases = comparePairedRuns(olds, news, opt);
  }
  applyCorrection(cases, opt);

  std::map<Verdict, int> counts;
  std::map<WorkStatus, int> workCounts;
  std::size_t workCounters = 0;
  std::map<PassWorkKind, int> passKinds;
  for (const auto& c : cases) {
    ++counts[c.verdict];
    ++workCounts[c.work.status];
    workCounters += c.work.counterCount();
    for (const auto& p : c.work.passes) ++passKinds[p.kind];
  }
  const int workChanged = workCounts[WorkStatus::Changed];
  const int status =
      counts[Verdict::Slower] > 0 || (opt.failOnWorkChange && workChanged > 0) ? 1 : 0;
  const std::vector<std::string> contextDiff = contextDifferences(oldRun.context, newRun.context);

  if (asJson) {
    json j;
    j["old"] = oldRun.source;
    j["new"] = newRun.source;
    j["pairs"] = morePairs.empty() ? 0 : morePairs.size() + 1;  // 0: one run per side
    j["threshold_pct"] = opt.thresholdPct;
    j["alpha"] = opt.alpha;
    j["correction"] = opt.correction == Correction::Holm ? "holm" : "none";
    j["context_differs"] = contextDiff;
    j["shared_cases"] = overlap.shared;
    j["warnings"] = overlap.warnings;
    j["fail_on_work_change"] = opt.failOnWorkChange;
    // Work first, as in the text: exact changes, apart from the timing verdicts.
    json work = {{"changed_cases", workChanged},
                 {"changed_counters", workCounters},
                 {"same_cases", workCounts[WorkStatus::Same]},
                 {"not_counted_cases", workCounts[WorkStatus::NotCounted]},
                 {"not_compared_cases", workCounts[WorkStatus::NotCompared]},
                 {"cases", json::array()}};
    for (const auto& c : cases)
      if (c.work.status == WorkStatus::Changed)
        work["cases"].push_back({{"id", c.id}, {"passes", workChangesJson(c.work.passes)}});
    j["work"] = work;
    j["cases"] = json::array();
    for (const auto& c : cases) {
      json cj = timingJson(c.frame);
      cj["id"] = c.id;
      cj["work"] = workStatusName(c.work.status);
      cj["work_note"] = c.work.note;
      cj["passes"] = json::array();
      for (const auto& p : c.passes) {
        json pj = timingJson(p);
        pj["name"] = p.name;
        cj["passes"].push_back(std::move(pj));
      }
      j["cases"].push_back(std::move(cj));
    }
    json summary;
    for (Verdict v : {Verdict::Slower, Verdict::Faster, Verdict::Ok, Verdict::NotJudged,
                      Verdict::DefinitionChanged, Verdict::Added, Verdict::Removed})
      summary[verdictName(v)] = counts[v];
    j["summary"] = summary;
    j["status"] = status;
    out << j.dump(2) << "\n";
    return status;
  }

  // Two summary lines first: work (exact) and time (statistical) are separate questions.
  const int notCounted = workCounts[WorkStatus::NotCounted];
  const int compared = workCounts[WorkStatus::Same] + workChanged;
  std::string notCountedText;
  if (notCounted)
    notCountedText = std::to_string(notCounted) + " case" + (notCounted == 1 ? "" : "s") +
                     " not counted (results without work)";
  if (workChanged) {
    out << "work changed: " << workChanged << " case" << (workChanged == 1 ? "" : "s") << " ("
        << workCounters << " counter" << (workCounters == 1 ? "" : "s");
    for (PassWorkKind k : {PassWorkKind::Changed, PassWorkKind::Added, PassWorkKind::Removed})
      if (passKinds[k])
        out << "; " << passKinds[k] << " pass" << (passKinds[k] == 1 ? " " : "es ")
            << passWorkKindName(k);
    out << ") of " << compared << " compared"
        << (notCountedText.empty() ? "" : "; " + notCountedText)
        << (opt.failOnWorkChange ? "" : "; information, exit status unaffected") << "\n";
  } else {
    out << "work changed: none (" << compared << " cases compared"
        << (notCountedText.empty() ? "" : "; " + notCountedText) << ")\n";
  }
  const int judged = counts[Verdict::Slower] + counts[Verdict::Faster] + counts[Verdict::Ok];
  if (counts[Verdict::Slower] + counts[Verdict::Faster] > 0)
    out << "time changed: " << counts[Verdict::Slower] << " SLOWER, " << counts[Verdict::Faster]
        << " faster of " << judged << " judged cases\n";
  else
    out << "time changed: none (" << judged << " cases judged, " << counts[Verdict::NotJudged]
        << " not judged)\n";
  out << "old: " << runLabel(oldRun) << "\n";
  out << "new: " << runLabel(newRun) << "\n";
  if (!morePairs.empty())
    out << "paired: " << morePairs.size() + 1
        << " pairs of runs; change = median new/old ratio, p = signed-rank test over the pairs\n";
  for (const auto& w : overlap.warnings) out << "warning: " << w << "\n";
  if (!contextDiff.empty()) {
    out << "note: the runs' contexts differ in";
    for (const auto& k : contextDiff) out << " " << k;
    out << "; timings may not be comparable\n";
  }
  if (workChanged) {
    out << "work changes (exact counters, old -> new):\n";
    for (const auto& c : cases) {
      if (c.work.status != WorkStatus::Changed) continue;
      out << "  " << c.id << "\n";
      for (const auto& p : c.work.passes) out << "    " << describeWorkChange(p) << "\n";
    }
  }
  // One row per case, then its notable passes indented.
  std::vector<std::array<std::string, 7>> rows;
  rows.push_back({"case", "old ms", "new ms", "change", "p", "p Holm", "verdict"});
  auto row = [&](const std::string& name, const TimingChange& t, bool pass) {
    rows.push_back({name, t.oldMedian ? format("%.3f", *t.oldMedian) : "-",
                    t.newMedian ? format("%.3f", *t.newMedian) : "-",
                    t.changePct && t.verdict != Verdict::DefinitionChanged
                        ? format("%+.1f%%", *t.changePct)
                        : "-",
                    t.p ? formatP(*t.p) : "-", t.pAdjusted ? formatP(*t.pAdjusted) : "-",
                    verdictText(t, pass)});
  };
  for (const auto& c : cases) {
    row(c.id, c.frame, false);
    for (const auto& p : c.passes) row("  pass " + p.name, p, true);
  }
  std::array<std::size_t, 7> width{};
  for (const auto& r : rows)
    for (std::size_t i = 0; i < r.size(); ++i) width[i] = std::max(width[i], r[i].size());
  for (const auto& r : rows) {
    std::string line = r[0] + std::string(width[0] - r[0].size(), ' ');
    for (std::size_t i = 1; i < 6; ++i)
      line += "  " + std::string(width[i] - r[i].size(), ' ') + r[i];
    line += "  " + r[6];
    out << line << "\n";
  }
  out << cases.size() << " cases: " << counts[Verdict::Slower] << " slower, "
      << counts[Verdict::Faster] << " faster, " << counts[Verdict::Ok] << " ok, "
      << counts[Verdict::NotJudged] << " not judged, " << counts[Verdict::DefinitionChanged]
      << " definition changed, " << counts[Verdict::Added] << " added, " << counts[Verdict::Removed]
      << " removed (threshold " << format("%g", opt.thresholdPct) << "%, alpha "
      << format("%g", opt.alpha)
      << (opt.correction == Correction::Holm ? ", Holm-corrected over the judged cases" : "")
      << ")\n";
  return status;
}

}  // namespace sb
