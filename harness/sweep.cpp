#include "harness/sweep.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <new>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "backends/driver_env.h"
#include "base/fnv.h"
#include "harness/case_store.h"
#include "harness/measure.h"
#include "harness/measures/animation/animation.h"
#include "harness/measures/invariants/invariants.h"
#include "harness/measures/probe/probe.h"
#include "harness/stop.h"
#include "imaging/image.h"
#include "imaging/metrics.h"
#include "reports/files.h"
#include "reports/json_file.h"
#include "reports/report_writer.h"

namespace sb {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

namespace {

constexpr int kSchemaVersion = 1;

// The context's device list and Mesa version come from the results, since a
// device is only known once it has been created.
void addDevices(ojson& context, const std::vector<ojson>& results) {
  ojson devices = ojson::array();
  std::set<std::string> seen;
  std::string mesa;
  const std::regex mesaVersion("Mesa ([0-9]+\\.[0-9]+\\.[0-9]+)");
  for (const auto& r : results) {
    const std::string key = r.value("backend", "") + "|" + r.value("device", "");
    if (!seen.insert(key).second) continue;
    devices.push_back({{"backend", r.value("backend", "")},
                       {"platform", r.value("platform", "")},
                       {"device", r.value("device", "")},
                       {"driver", r.value("driver", "")},
                       {"timing", r.value("timing", "")}});
    std::smatch m;
    const std::string driver = r.value("driver", "");
    if (mesa.empty() && std::regex_search(driver, m, mesaVersion)) mesa = m[1];
  }
  context["devices"] = devices;
  context["mesa"] = mesa.empty() ? ojson(nullptr) : ojson(mesa);
}

// A case file that parses is a finished case (they are written by rename);
// a failed case is run again by --resume (out of memory may not last).
bool caseDone(const fs::path& file) {
  if (!fs::is_regular_file(file)) return false;
  try {
    return !readJsonFile<ojson>(file).contains("failed");
  } catch (const InputError&) {
    return false;
  }
}

// The folder the messages name (SweepOptions::shownOut).
fs::path shownDir(const SweepOptions& o) { return o.shownOut.empty() ? o.out : o.shownOut; }

fs::path caseFile(const fs::path& dir, const SweepCase& c) {
  return dir / "cases" / (c.stem + ".json");
}

// Runs a case once (its timed frames, images, errors) and writes its images; its result file
// is written by writeCaseResult, last, once the interleaved rounds have added their timings,
// so a result file means its images and timings are complete.
struct CaseRun {
  RenderResult out;  // images dropped once written
  ojson images = ojson::object();
};

CaseRun runCase(const fs::path& dir, const SweepCase& c, const RenderRequest& request,
                RenderCache& cache) {
  CaseRun run{runRender(request, &cache), ojson::object()};
  RenderResult& out = run.out;
  ojson& images = run.images;
  if (request.image) {
    const std::string base = "images/" + c.stem;
    writeImage(out.image, (dir / (base + ".png")).string());
    images["image"] = base + ".png";
    if (request.reference) {
      writeImage(out.referenceImage, (dir / (base + ".reference.png")).string());
      writeImage(diffHeatmap(out.image, out.referenceImage, 0.25),
                 (dir / (base + ".heatmap.png")).string());
      writeImage(flipErrorImage(*out.flip), (dir / (base + ".flip.png")).string());
      images["reference"] = base + ".reference.png";
      images["heatmap"] = base + ".heatmap.png";
      images["flip"] = base + ".flip.png";
      // Each further reference beside it (images/<stem>.aa.png).
      for (const RenderResult::MoreReference& m : out.moreReferences) {
        writeImage(m.referenceImage, (dir / (base + "." + m.name + ".png")).string());
        images[m.name] = base + "." + m.name + ".png";
      }
    }
    if (const AnimationResult* a = out.measure<AnimationResult>()) {
      writeImage(animationStrip(*a), (dir / (base + ".animation.png")).string());
      images["animation"] = base + ".animation.png";
    }
  }
  if (request.invariants && request.runToRun) {
    // Identical results run to run: the case again, on a fresh device.
    const RenderResult again = runRender(request, &cache);
    auto curve = [](const RenderResult& r) {
      const ProbeResult* p = r.measure<ProbeResult>();
      return p ? p->visibility : std::vector<float>{};
    };
    auto work = [](const RenderResult& r) {
      std::vector<PassWork> w;
      for (const PassTimes& p : r.passes) w.push_back(p.work);
      return w;
    };
    for (const auto& [what, same] : {std::pair{"color", again.image.pixels == out.image.pixels},
                                     std::pair{"visibility", again.visibility == out.visibility},
                                     std::pair{"probe", curve(again) == curve(out)},
                                     std::pair{"work counters", work(again) == work(out)}})
      if (!same) addInvariantFailure(out, {what, "not identical run to run"});
  }
  return run;
}

ojson writeCaseResult(const fs::path& dir, const SweepCase& c, const CaseRun& run,
                      const ojson& measurement) {
  ojson result = ojson::parse(renderJson(run.out).dump());
  if (!measurement.is_null()) result["measurement"] = measurement;
  result["case"] = {{"id", c.id}, {"group", c.group}, {"index", c.index}, {"params", c.params}};
  result["images"] = run.images;
  // The case's timed frames (every round) as a Chrome/Perfetto trace, beside its images.
  if (!run.out.timeline.empty()) {
    const std::string trace = "traces/" + c.stem + ".json";
    writeFileAtomic(dir / trace, traceJson(run.out).dump() + "\n");
    result["trace"] = trace;
  }
  writeFileAtomic(caseFile(dir, c), result.dump(1) + "\n");
  return result;
}

// A later round of an interleaved case: its timed frame only (no errors, images, probe or
// animation; a visibility-only case keeps its reference, which its timed output needs).
RenderRequest timingRequest(const RenderRequest& q) {
  RenderRequest t = q;
  t.timeline = true;
  t.repeat = 1;
  t.reference = !q.image;
  t.probe.reset();
  t.animate.reset();
  t.invariants = false;
  return t;
}

// Adds a later round's frames to the case's first run.
void appendFrames(RenderResult& into, const RenderResult& more) {
  into.frameMs.insert(into.frameMs.end(), more.frameMs.begin(), more.frameMs.end());
  into.timeline.insert(into.timeline.end(), more.timeline.begin(), more.timeline.end());
  for (const PassTimes& p : more.passes) {
    auto pass = std::find_if(into.passes.begin(), into.passes.end(),
                             [&](const PassTimes& q) { return q.name == p.name; });
    if (pass == into.passes.end()) {
      into.passes.push_back(p);
      continue;
    }
    pass->ms.insert(pass->ms.end(), p.ms.begin(), p.ms.end());
    // Work is exact: a round that did other work than the first is named.
    if (!(p.work == pass->work) && std::find(into.workVaries.begin(), into.workVaries.end(),
                                             p.name) == into.workVaries.end()) {
      into.workVaries.push_back(p.name);
      into.warnings.push_back("pass '" + p.name +
                              "' did different work in different rounds (its counters)");
    }
  }
  into.repeat += more.repeat;
}

// The result file of a case that failed, or was not run for a part this machine lacks
// (`missing`): what it was and why, so the reports list it and --resume runs it again.
ojson failedCase(const fs::path& dir, const SweepCase& c, const std::string& reason,
                 const UnavailableError* missing = nullptr) {
  const RenderRequest& q = c.request;
  ojson failed = {{"reason", reason}};
  if (missing) {
    failed["reason"] = "not run: " + reason + " (to run it: " + missing->enable + ")";
    failed["unavailable"] = true;
    failed["enable"] = missing->enable;
  }
  ojson result = {{"backend", q.backend}, {"scene", {{"spec", q.scene}}}, {"shadow", q.shadow},
                  {"oit", q.oit},         {"size", {q.width, q.height}},  {"failed", failed}};
  result["case"] = {{"id", c.id}, {"group", c.group}, {"index", c.index}, {"params", c.params}};
  result["images"] = ojson::object();
  writeFileAtomic(caseFile(dir, c), result.dump(1) + "\n");
  return result;
}

// Removes what a case that did not finish left (its images and trace): a case is there whole,
// with its result file, or not at all.
void removeCaseFiles(const fs::path& dir, const SweepCase& c) {
  std::error_code ec;
  fs::remove(dir / "traces" / (c.stem + ".json"), ec);
  std::vector<fs::path> images;
  for (fs::directory_iterator it(dir / "images", ec), end; !ec && it != end; it.increment(ec))
    if (it->path().filename().string().rfind(c.stem + ".", 0) == 0) images.push_back(it->path());
  for (const fs::path& p : images) fs::remove(p, ec);
}

// Failures of a case's invariants, one line each naming the case, technique,
// backend and pass.
std::vector<std::string> invariantFailures(const ojson& r) {
  std::vector<std::string> lines;
  if (!r.contains("invariants")) return lines;
  for (const auto& f : r["invariants"]["failures"])
    lines.push_back("invariant failed: case " + r["case"]["id"].get<std::string>() + ", shadow " +
                    r["shadow"].get<std::string>() + ", oit " + r["oit"].get<std::string>() +
                    ", backend " + r["backend"].get<std::string>() + ", pass " +
                    f["pass"].get<std::string>() + ": " + f["what"].get<std::string>());
  return lines;
}

std::string caseSummary(const ojson& r) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << "frame " << r["frame_ms"]["median"].get<double>()
    << " ms";
  if (r.contains("error")) {
    s << std::setprecision(4);
    if (r["error"].contains("image") && r["error"]["image"]["rmse"].is_number())
      s << "  rmse " << r["error"]["image"]["rmse"].get<double>();
    if (r["error"].contains("image") && r["error"]["image"].contains("flip") &&
        r["error"]["image"]["flip"]["mean"].is_number())
      s << "  flip " << r["error"]["image"]["flip"]["mean"].get<double>();
    if (r["error"]["visibility"]["rmse"].is_number())
      s << "  vis " << r["error"]["visibility"]["rmse"].get<double>();
  }
  if (r.contains("animation"))
    s << "  flicker vis " << r["animation"]["flicker"]["visibility"].get<double>();
  return s.str();
}

std::string duration(double seconds) {
  std::ostringstream s;
  const int t = static_cast<int>(seconds + 0.5);
  if (t >= 60)
    s << t / 60 << "m" << std::setw(2) << std::setfill('0') << t % 60 << "s";
  else
    s << t << "s";
  return s.str();
}

void progressLine(int done, int total, const std::string& id, double elapsed) {
  const int width = 30;
  const int filled = total ? done * width / total : width;
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(width, '.');
  std::string eta = done ? duration(elapsed / done * (total - done)) : "?";
  std::string name = id.size() > 60 ? "..." + id.substr(id.size() - 57) : id;
  std::cout << "\r\033[K[" << bar << "] " << done << "/" << total << "  eta " << eta << "  " << name
            << std::flush;
}

}  // namespace

namespace {

// The rounds of a group: --min-reps (default: the group's largest `repeat`), --max-reps
// (default: --min-reps, or 15 with --target-ci); back to back: one run of `repeat` frames.
RepetitionOptions groupRepetitions(const SweepOptions& o,
                                   const std::vector<const SweepCase*>& batch) {
  if (!o.interleave) return {1, 1, 0};
  int repeat = 1;
  for (const auto* c : batch) repeat = std::max(repeat, c->request.repeat);
  return repetitions(o.rounds, repeat);
}

// How a case's frame times were taken, with the median's bootstrap 95% interval and the
// samples Tukey's fences mark as outliers (marked, never dropped).
// `run` names the interleaved run (one per batch of cases measured together): two cases'
// ratio is a measurement of one run only where they share it (figure claims).
ojson measurementJson(const SweepOptions& o, const RenderResult& out,
                      const std::vector<double>& startS, const std::string& run) {
  const Interval ci = bootstrapMedian(out.frameMs);
  const std::vector<bool> marks = tukeyOutliers(out.frameMs);
  ojson outliers = ojson::array();
  for (std::size_t k = 0; k < marks.size(); ++k)
    if (marks[k]) outliers.push_back(k);
  ojson m = {{"mode", o.interleave ? "interleaved" : "back-to-back"},
             {"samples", out.frameMs.size()},
             {"median_ms", ci.estimate},
             {"median_ci95_ms", {ci.low, ci.high}},
             {"outliers", outliers}};
  if (o.interleave) {
    m["round_start_s"] = startS;
    m["interleaved_run"] = run;
  }
  return m;
}

}  // namespace

int runSweep(const SweepOptions& o) {
  const Suite suite = loadSuite(o.suitePath);
  if (o.out.empty()) throw InputError("--out DIR is required");
  if (!o.interleave && !runOptionTable().given(o.rounds).empty())
    throw InputError(
        "--min-reps, --max-reps and --target-ci take interleaved rounds: drop --no-interleave "
        "(back to back, a case takes its `repeat` frames)");
  if (o.shardIndex < 1 || o.shardIndex > o.shardCount) throw InputError("bad --shard");
  std::optional<std::regex> filter;
  if (!o.filter.empty()) {
    try {
      filter.emplace(o.filter);
    } catch (const std::regex_error& e) {
      throw InputError("--filter " + o.filter + ": not a valid regular expression (" + e.what() +
                       ")");
    }
  }

  std::vector<const SweepCase*> selected;
  for (const auto& c : suite.cases)
    if (c.index % o.shardCount == o.shardIndex - 1 && (!filter || std::regex_search(c.id, *filter)))
      selected.push_back(&c);
  if (selected.empty())
    throw InputError("suite " + o.suitePath + ": no case matches the filter and shard");
  // Every file the cases name is read before anything runs or is written (a child sweep's
  // parent has read them).
  if (!o.driverCasesOnly) checkSuiteFiles(o.suitePath, selected);
  const std::vector<const SweepCase*> allSelected = selected;  // this process's and children's
  std::vector<std::string> failedDrivers;  // child sweeps of other drivers that failed
  if (std::any_of(selected.begin(), selected.end(),
                  [](const SweepCase* c) { return c->request.image; }))
    loadImageModule();

  const fs::path dir = o.out;
  const fs::path sweepFile = dir / "sweep.json";
  ojson sweepDoc = {
      {"schema_version", kSchemaVersion}, {"suite_file", o.suitePath}, {"suite", suite.doc}};
  // What `merge` needs to name a missing shard: this folder's index, the count, the filter.
  sweepDoc["shard"] = {{"index", o.shardIndex}, {"count", o.shardCount}, {"filter", o.filter}};
  if (!o.shardSource.empty()) sweepDoc["shard"]["source"] = o.shardSource;
  if (fs::exists(sweepFile)) {
    if (!o.resume)
      throw InputError("--out " + o.out +
                       " already holds a sweep: add --resume to continue it, or choose another "
                       "folder");
    if (readJsonFile<ojson>(sweepFile)["suite"] != suite.doc)
      throw InputError("--resume: " + o.suitePath + " has changed since the sweep in " + o.out +
                       " started; use another folder");
  } else if (fs::exists(dir) && !fs::is_directory(dir)) {
    throw InputError("--out " + o.out + ": exists and is not a folder");
  }
  std::error_code ec;
  fs::create_directories(dir / "cases", ec);
  fs::create_directories(dir / "images", ec);
  fs::create_directories(dir / "traces", ec);
  if (ec || !fs::is_directory(dir / "traces"))
    throw InputError("--out " + o.out + ": cannot create the folder (" + ec.message() + ")");
  if (!fs::exists(sweepFile)) {
    writeFileAtomic(dir / "context.json", runContext().dump(2) + "\n");
    writeFileAtomic(sweepFile, sweepDoc.dump(2) + "\n");
  }

  // What a stop leaves, counted from the files: the cases kept, which --resume skips.
  auto stopped = [&](const std::vector<const SweepCase*>& cases) {
    const auto kept = std::count_if(cases.begin(), cases.end(), [&](const SweepCase* c) {
      return caseDone(caseFile(dir, *c));
    });
    std::cout << "stopped: " << kept << " of " << cases.size() << " cases kept in "
              << (dir / "cases").string() << "; continue with --resume (it runs the other "
              << cases.size() - static_cast<std::size_t>(kept) << ")\n"
              << std::flush;
  };
  // Cases that need a part this machine lacks, from their result files (this process's and
  // the child sweeps'): listed with what provides the part; they fail only with requireParts.
  auto notRunSummary = [&](int status) {
    std::vector<std::string> lines;
    std::vector<std::string> enable;
    for (const auto* c : allSelected) {
      if (!fs::is_regular_file(caseFile(dir, *c))) continue;
      const ojson f = readJsonFile<ojson>(caseFile(dir, *c)).value("failed", ojson::object());
      if (!f.value("unavailable", false)) continue;
      const std::string reason = f.value("reason", "");
      lines.push_back(c->id + ": " + reason.substr(0, reason.find('\n')));
      const std::string how = f.value("enable", "");
      if (std::find(enable.begin(), enable.end(), how) == enable.end()) enable.push_back(how);
    }
    if (lines.empty()) return status;
    std::cout << lines.size() << " case" << (lines.size() == 1 ? "" : "s")
              << " not run (a part this machine lacks; in results.json and the report):\n";
    for (const auto& line : lines) std::cout << "  " << line << "\n";
    for (const auto& how : enable) std::cout << "to run them: " << how << "\n";
    if (!o.requireParts) {
      std::cout << "(not a failure: --require-drivers, or CI=true, makes it one)\n";
      return status;
    }
    std::cout << "--require-drivers (or CI=true): the cases not run fail the sweep\n";
    return std::max(status, 1);
  };

  // One process, one driver: the cases of other drivers go to a child sweep per driver, or,
  // when that driver is not installed, are recorded as not run.
  std::vector<std::string> otherDrivers;
  {
    std::vector<const SweepCase*> own;
    for (const auto* c : selected) {
      const std::string& d = c->request.driver;
      if (const auto missing = missingPart(*c)) {
        // (A case an earlier run finished keeps its result.)
        if (!o.driverCasesOnly && !(o.resume && caseDone(caseFile(dir, *c))))
          failedCase(dir, *c, missing->what(), &*missing);
        continue;
      }
      const bool mine =
          o.driverCasesOnly ? !d.empty() && isCurrentDriver(d) : d.empty() || isCurrentDriver(d);
      if (mine)
        own.push_back(c);
      else if (!o.driverCasesOnly &&
               std::find(otherDrivers.begin(), otherDrivers.end(), d) == otherDrivers.end())
        otherDrivers.push_back(d);
    }
    selected = own;
  }
  for (const std::string& d : otherDrivers) {
    std::vector<std::string> args = {
        "sweep",    o.suitePath,
        "--out",    o.out,
        "--resume", "--driver",
        d,          "--driver-cases",
        "--shard",  std::to_string(o.shardIndex) + "/" + std::to_string(o.shardCount)};
    if (!o.filter.empty()) args.insert(args.end(), {"--filter", o.filter});
    if (o.failFast) args.push_back("--fail-fast");
    if (o.requireParts) args.push_back("--require-drivers");
    if (!o.interleave) args.push_back("--no-interleave");
    for (std::string& a : runOptionArguments(o.rounds)) args.push_back(std::move(a));
    std::cout << "sweep " << suite.name << ": the cases on driver " << d
              << " in a process of its own\n";
    const int status =
        childStatus(runSelfOnDriver(d, args), "the sweep of the cases on driver " + d,
                    [&] { stopped(allSelected); });
    if (status != 0)
      failedDrivers.push_back("the cases on driver " + d + " (exit status " +
                              std::to_string(status) + ", above)");
  }
  if (selected.empty() && !o.driverCasesOnly) {
    const int n = writeSweepReport(o.out);
    std::cout << "wrote " << (shownDir(o) / "results.json").string() << " (" << n << " results)\n";
    for (const auto& f : failedDrivers) std::cout << "failed: " << f << "\n";
    return notRunSummary(failedDrivers.empty() ? 0 : 1);
  }

  std::vector<const SweepCase*> todo;
  for (const auto* c : selected)
    if (!(o.resume && caseDone(caseFile(dir, *c)))) todo.push_back(c);
  // What an earlier run killed inside a case left (its images) goes before the case runs again.
  if (o.resume)
    for (const auto* c : todo)
      if (!fs::is_regular_file(caseFile(dir, *c))) removeCaseFiles(dir, *c);
  const int total = static_cast<int>(selected.size());
  int done = total - static_cast<int>(todo.size());
  std::cout << "sweep " << suite.name << ": " << total << " cases";
  if (o.shardCount > 1) std::cout << " (shard " << o.shardIndex << "/" << o.shardCount << ")";
  if (done) std::cout << ", " << done << " already done";
  std::cout << " -> " << shownDir(o).string() << "\n" << std::flush;

  RenderCache cache;
  std::vector<std::string> failures;
  std::optional<CaseStore> store;
  if (!o.cases.empty()) store.emplace(o.cases);
  int taken = 0, stored = 0;             // cases taken from the store; measured here and kept in it
  ProgressLine::enable(!o.progressBar);  // the bar is the sweep's one line
  const auto start = std::chrono::steady_clock::now();
  const int startDone = done;
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  struct StopAtFailure {};
  try {
    // A group's cases (consecutive in the suite) are measured together: round r renders every
    // case of the group once (harness/measure.h), so a drift of the machine hits them alike.
    for (std::size_t g = 0; g < todo.size();) {
      std::size_t end = g;
      while (end < todo.size() && (o.interleaveAcrossGroups || todo[end]->group == todo[g]->group))
        ++end;
      std::vector<const SweepCase*> batch(todo.begin() + long(g), todo.begin() + long(end));
      g = end;
      const RepetitionOptions reps = groupRepetitions(o, batch);
      // Cases another sweep measured for the same key: taken whole, not run again.
      std::vector<std::string> keys;
      if (store) {
        std::vector<const SweepCase*> rest;
        for (const SweepCase* c : batch) {
          const std::string key = store->key(*c, reps, o.interleave);
          const std::optional<ojson> result = store->take(key, dir, *c);
          if (!result) {
            rest.push_back(c);
            keys.push_back(key);
            continue;
          }
          writeFileAtomic(caseFile(dir, *c), result->dump(1) + "\n");
          ++taken;
          ++done;
          if (o.progressBar) std::cout << "\n";
          std::cout << "[" << done << "/" << total << "] " << c->id << "  " << caseSummary(*result)
                    << "  (measured once: taken from the case store, measured for "
                    << (*result)["shared"].value("measured_for", "?") << ")\n"
                    << std::flush;
          for (const auto& line : invariantFailures(*result)) {
            std::cout << line << "\n";
            failures.push_back(line);
          }
        }
        batch = rest;
        if (batch.empty()) continue;
      }
      // Names this batch's interleaved run in its cases' measurements.
      const std::string runText =
          suite.name + "|" + batch.front()->id + "|" + std::to_string(::getpid()) + "|" +
          std::to_string(std::chrono::system_clock::now().time_since_epoch().count());
      const std::string run = hex64(fnv1a(kFnvOffset, runText.data(), runText.size()));
      std::vector<CaseRun> runs(batch.size());
      std::vector<std::vector<double>> startS(batch.size());  // each round's start
      std::vector<bool> failed(batch.size(), false), written(batch.size(), false);
      std::vector<int> number(batch.size(), 0);        // "[number/total]" in its line
      std::vector<double> seconds(batch.size(), 0.0);  // over all its rounds
      // A case's result file is written once its rounds are done: at once when the group
      // takes one round (a stopped sweep then resumes at the case), else at the group's end,
      // or at a stop with the rounds it had. Its line is printed then, from the result: the
      // median the report shows, not the first round's time.
      auto writeResult = [&](std::size_t i, bool stoppedEarly = false) {
        ojson measurement = measurementJson(o, runs[i].out, startS[i], run);
        if (stoppedEarly) {
          const int rounds = static_cast<int>(startS[i].size());
          measurement["stopped"] = {{"rounds", rounds}, {"min_rounds", reps.minReps}};
          runs[i].out.warnings.push_back(
              "timed in " + std::to_string(rounds) + " interleaved round" +
              (rounds == 1 ? "" : "s") + " of the " + std::to_string(reps.minReps) +
              " or more its group takes: the sweep was stopped (SIGINT or SIGTERM) during it");
        }
        const ojson result = writeCaseResult(dir, *batch[i], runs[i], measurement);
        written[i] = true;
        // A case timed in fewer rounds than its key says is not kept for others.
        if (store && !stoppedEarly) {
          stored += store->put(keys[i], dir, *batch[i], result, suite.name) ? 1 : 0;
        }
        if (!o.progressBar)
          std::cout << "[" << number[i] << "/" << total << "] " << batch[i]->id << "  "
                    << caseSummary(result) << "  (" << std::fixed << std::setprecision(1)
                    << seconds[i] << " s)" << (stoppedEarly ? "  (stopped: fewer rounds)" : "")
                    << "\n"
                    << std::flush;
        for (const auto& line : invariantFailures(result)) {
          if (o.progressBar) std::cout << "\n";
          std::cout << line << "\n";
          failures.push_back(line);
        }
      };
      std::vector<std::function<double()>> rounds;
      for (std::size_t i = 0; i < batch.size(); ++i)
        rounds.push_back([&, i]() -> double {
          const SweepCase& c = *batch[i];
          const bool first = startS[i].empty();
          if (first && o.progressBar)
            progressLine(done - startDone, total - startDone, c.id, elapsed());
          const double t = elapsed();
          throwIfStopped();
          std::string reason;
          std::optional<UnavailableError> missing;
          try {
            if (first) {
              RenderRequest q = c.request;
              q.timeline = true;
              if (o.interleave) q.repeat = 1;
              runs[i] = runCase(dir, c, q, cache);
              // Written; the rounds to come need only the timings.
              runs[i].out.image = {};
              runs[i].out.referenceImage = {};
              for (auto& m : runs[i].out.moreReferences) m.referenceImage = {};
            } else {
              appendFrames(runs[i].out, runRender(timingRequest(c.request), &cache));
            }
          } catch (const UnavailableError& e) {  // a part the device lacks: not run
            missing = e;
            reason = e.what();
          } catch (const InputError& e) {  // input only running finds bad: the case fails
            reason = e.what();
          } catch (const DeviceError& e) {  // out of memory included
            reason = e.what();
          } catch (const std::bad_alloc&) {
            reason = "out of memory: a host allocation failed";
          }
          if (first) number[i] = ++done;
          seconds[i] += elapsed() - t;
          if (!reason.empty()) {
            failed[i] = true;
            removeCaseFiles(dir, c);  // a later round's failure drops the first round's images
            failedCase(dir, c, reason, missing ? &*missing : nullptr);
            if (o.progressBar) std::cout << "\n";
            // One line here; the whole message (resources, hint) is in the case file.
            const std::string line = "case " + c.id + (missing ? " not run: " : " failed: ") +
                                     reason.substr(0, reason.find('\n')) +
                                     (reason.find('\n') != std::string::npos
                                          ? " (the rest in " + caseFile(dir, c).string() + ")"
                                          : "");
            std::cout << line << "\n" << std::flush;
            if (missing) return std::numeric_limits<double>::quiet_NaN();
            failures.push_back(line);
            if (o.failFast) throw StopAtFailure{};
            return std::numeric_limits<double>::quiet_NaN();
          }
          startS[i].push_back(t);
          if (first && reps.maxReps == 1) writeResult(i);
          return runs[i].out.frameMs.empty() ? 0.0 : median(runs[i].out.frameMs);
        });
      try {
        measureInterleaved(rounds, reps, /*leastMinReps=*/1);
      } catch (const Interrupted&) {
        // Stopped inside the group: a case whose first round is done has its images and
        // errors, and is kept with the rounds it had; the others leave nothing behind.
        if (o.progressBar) std::cout << "\n";
        for (std::size_t i = 0; i < batch.size(); ++i) {
          if (failed[i] || written[i]) continue;
          if (!startS[i].empty())
            writeResult(i, /*stoppedEarly=*/true);
          else
            removeCaseFiles(dir, *batch[i]);
        }
        throw;
      }
      int measured = 0;
      for (std::size_t i = 0; i < batch.size(); ++i) {
        if (failed[i]) continue;
        ++measured;
        if (!written[i]) writeResult(i);
      }
      if (o.interleave && reps.maxReps > 1 && measured && !o.progressBar)
        std::cout << "  "
                  << (o.interleaveAcrossGroups ? "every group" : "group " + batch.front()->group)
                  << ": " << measured << " cases, " << (startS.empty() ? 0 : startS.front().size())
                  << " interleaved rounds each\n"
                  << std::flush;
    }
  } catch (const StopAtFailure&) {
    std::cout << "--fail-fast: stopping at the first failed case\n";
  } catch (const Interrupted&) {
    stopped(o.driverCasesOnly ? selected : allSelected);
    throw;
  }
  if (o.progressBar) {
    progressLine(done - startDone, total - startDone, "done in " + duration(elapsed()), elapsed());
    std::cout << "\n";
  }
  std::cout << "references rendered: " << cache.referenceRenders << "\n";
  if (store)
    std::cout << "case store " << store->dir().string() << ": " << taken
              << " taken (measured once, by an earlier sweep), " << stored
              << " measured here and kept\n";
  {
    // The load after the cases, beside the load before them (a busy machine explains noise).
    ojson context = readJsonFile<ojson>(dir / "context.json");
    context["load_after"] = loadAverage();
    writeFileAtomic(dir / "context.json", context.dump(2) + "\n");
  }
  if (o.driverCasesOnly) {  // the parent writes the reports and lists the cases not run
    if (!failures.empty()) return 1;
    const bool notRun = std::any_of(selected.begin(), selected.end(), [&](const SweepCase* c) {
      return fs::is_regular_file(caseFile(dir, *c)) && readJsonFile<ojson>(caseFile(dir, *c))
                                                           .value("failed", ojson::object())
                                                           .value("unavailable", false);
    });
    return notRun && o.requireParts ? 1 : 0;
  }
  const int n = writeSweepReport(o.out);
  std::cout << "wrote " << (shownDir(o) / "results.json").string() << " (" << n
            << " results), results.csv, passes.csv, cost_model.json, report.md, report.html\n";
  for (const auto& f : failedDrivers) failures.push_back("failed: " + f);
  // Cases done by an earlier run count too: a resumed sweep reports them.
  for (const auto* c : selected) {
    if (std::find(todo.begin(), todo.end(), c) != todo.end()) continue;
    for (const auto& line : invariantFailures(readJsonFile<ojson>(caseFile(dir, *c))))
      failures.push_back(line);
  }
  if (!failures.empty()) {
    std::cout << failures.size() << " failures (failed cases, invariants):\n";
    for (const auto& line : failures) std::cout << "  " << line << "\n";
  }
  return notRunSummary(failures.empty() ? 0 : 1);
}

int writeSweepReport(const std::string& dirText) {
  const fs::path dir = dirText;
  if (!fs::is_regular_file(dir / "sweep.json"))
    throw InputError(dirText + ": not a sweep folder (no sweep.json)");
  const ojson sweepDoc = readJsonFile<ojson>(dir / "sweep.json");
  const Suite suite = parseSuite(sweepDoc["suite"].dump(), sweepDoc.value("suite_file", "?"));
  std::vector<ojson> results;
  for (const auto& c : suite.cases) {
    const fs::path f = caseFile(dir, c);
    if (fs::is_regular_file(f)) results.push_back(readJsonFile<ojson>(f));
  }
  ojson context = fs::is_regular_file(dir / "context.json")
                      ? readJsonFile<ojson>(dir / "context.json")
                      : ojson(runContext());
  addDevices(context, results);
  ojson doc = {{"schema_version", kSchemaVersion},
               {"suite",
                {{"name", suite.name},
                 {"description", suite.description},
                 {"file", sweepDoc.value("suite_file", "")},
                 {"cases", suite.cases.size()}}},
               {"context", context},
               {"groups", suite.groups},
               {"tables", suite.doc.value("tables", ojson::array())},
               {"results", results}};
  writeFileAtomic(dir / "results.json", doc.dump(1) + "\n");
  writeReports(nlohmann::json::parse(doc.dump()), dir);
  return static_cast<int>(results.size());
}

MergeOutcome mergeSweeps(const std::string& outText, const std::vector<std::string>& inputs,
                         bool allowMissing) {
  if (inputs.empty()) throw InputError("merge: name the sweep folders to join");
  const fs::path out = outText;
  if (fs::exists(out)) throw InputError("merge: " + outText + " exists; choose a new folder");
  ojson suite;
  std::map<std::string, std::string> owner;  // case file -> input folder
  std::map<int, std::string> shardOwner;     // shard index -> input folder
  MergeOutcome outcome;
  std::string filter;
  ojson shards = ojson::array();
  for (const auto& in : inputs) {
    if (!fs::is_regular_file(fs::path(in) / "sweep.json"))
      throw InputError("merge: " + in + " is not a sweep folder (no sweep.json)");
    const ojson doc = readJsonFile<ojson>(fs::path(in) / "sweep.json");
    if (suite.is_null()) {
      suite = doc;
      suite.erase("shard");
    } else if (doc["suite"] != suite["suite"]) {
      throw InputError("merge: " + in + " ran a different suite than " + inputs.front());
    }
    // Folders from before the shard was recorded count as one shard of their own.
    const ojson shard = doc.value("shard", ojson{{"index", 1}, {"count", 1}, {"filter", ""}});
    const int index = shard.value("index", 1), count = shard.value("count", 1);
    if (doc.contains("shard")) {
      if (outcome.shardCount && count != outcome.shardCount)
        throw InputError("merge: " + in + " is shard " + std::to_string(index) + " of " +
                         std::to_string(count) + ", but an earlier folder is one of " +
                         std::to_string(outcome.shardCount));
      if (outcome.shardCount && shard.value("filter", "") != filter)
        throw InputError("merge: " + in + " ran with another --filter than the folders before");
      outcome.shardCount = count;
      filter = shard.value("filter", "");
      if (shardOwner.count(index))
        throw InputError("merge: shard " + std::to_string(index) + "/" + std::to_string(count) +
                         " is in both " + shardOwner[index] + " and " + in);
      shardOwner[index] = in;
    }
    for (const auto& e : fs::directory_iterator(fs::path(in) / "cases")) {
      if (e.path().extension() != ".json") continue;
      const std::string name = e.path().filename().string();
      if (owner.count(name))
        throw InputError("merge: case " + name + " is in both " + owner[name] + " and " + in);
      owner[name] = in;
    }
    // Each shard's own context (host, date, commit) with its devices and drivers, which
    // the shard's results.json holds once its report is written.
    ojson context = ojson::object();
    if (fs::is_regular_file(fs::path(in) / "results.json"))
      context = readJsonFile<ojson>(fs::path(in) / "results.json").value("context", context);
    else if (fs::is_regular_file(fs::path(in) / "context.json"))
      context = readJsonFile<ojson>(fs::path(in) / "context.json");
    shards.push_back({{"dir", in}, {"shard", shard}, {"context", context}});
  }
  // What is missing: shards never merged, and cases of the (filtered) suite no folder holds.
  for (int i = 1; i <= outcome.shardCount; ++i)
    if (!shardOwner.count(i)) outcome.missingShards.push_back(i);
  const Suite parsed = parseSuite(suite["suite"].dump(), suite.value("suite_file", "?"));
  std::optional<std::regex> filterRe;
  if (!filter.empty()) filterRe.emplace(filter);
  for (const auto& c : parsed.cases)
    if ((!filterRe || std::regex_search(c.id, *filterRe)) && !owner.count(c.stem + ".json"))
      outcome.missingCases.push_back(c.id);
  if (!outcome.missingCases.empty() && !allowMissing) return outcome;

  // Built beside the target and renamed: a failed merge leaves nothing behind.
  const fs::path tmp = out.string() + ".tmp-merge";
  std::error_code ec;
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp / "images", ec);
  fs::create_directories(tmp / "cases", ec);
  fs::create_directories(tmp / "traces", ec);
  if (ec) throw InputError("merge: cannot create " + tmp.string() + " (" + ec.message() + ")");
  try {
    for (const auto& [name, in] : owner) {
      const ojson result = readJsonFile<ojson>(fs::path(in) / "cases" / name);
      const ojson images = result.value("images", ojson::object());
      for (const auto& [kind, rel] : images.items())
        fs::copy_file(fs::path(in) / rel.get<std::string>(), tmp / rel.get<std::string>());
      if (result.contains("trace") && fs::exists(fs::path(in) / result["trace"].get<std::string>()))
        fs::copy_file(fs::path(in) / result["trace"].get<std::string>(),
                      tmp / result["trace"].get<std::string>());
      fs::copy_file(fs::path(in) / "cases" / name, tmp / "cases" / name);
    }
    ojson context = readJsonFile<ojson>(fs::path(inputs.front()) / "context.json");
    context["merged_from"] = inputs;
    context["shards"] = shards;
    if (!outcome.missingCases.empty())
      context["missing"] = {{"shards", outcome.missingShards}, {"cases", outcome.missingCases}};
    writeFileAtomic(tmp / "context.json", context.dump(2) + "\n");
    writeFileAtomic(tmp / "sweep.json", suite.dump(2) + "\n");
    fs::rename(tmp, out);
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(tmp, ec);
    throw InputError(std::string("merge: ") + e.what());
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
  outcome.written = true;
  outcome.results = writeSweepReport(outText);
  return outcome;
}

}  // namespace sb
