// `strandbench bench-shadows` and `bench-oit`: the papers' timing figures as ratios measured on
// one backend in one run (not a test: these machines are shared and noisy, so only ratios
// within a run are compared, their cases interleaved round by round, each ratio with its 95%
// interval; harness/measure.h). The papers' numbers and the techniques they time are read from
// the figures that reproduce them (dom-fig1, occ-fps, occ-fig2: harness/figure.h
// figurePaperTable); the benchmarks add a scene of your choice, OSM's time-per-map fit and
// the depth-peeling rows.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "cli/commands.h"
#include "harness/figure.h"
#include "harness/measure.h"
#include "harness/render.h"
#include "harness/run_options.h"
#include "reports/stats.h"

namespace sb {

namespace {

struct BenchOptions {
  RenderRequest base;
  std::vector<int> osmMaps = {1, 2, 4, 8, 16, 32};
  RepetitionOptions reps;  // the run options resolved (5 rounds by default)
};

struct Measured {
  double shadowMs = 0;  // sum of the shadow technique's pass medians (its passes by owner)
  double frameMs = 0;
  std::size_t shadowBytes = 0;
};

Measured measure(const RenderRequest& base, const std::string& shadow) {
  RenderRequest r = base;
  r.shadow = shadow;
  const RenderResult out = runRender(r);
  Measured m;
  for (const PassTimes& p : out.passes)
    if (p.owner == Owner::Shadow) m.shadowMs += summarize(p.ms).median;
  m.frameMs = summarize(out.frameMs).median;
  m.shadowBytes = out.bytesOwnedBy(Owner::Shadow);
  return m;
}

// Least-squares line through (x, y): slope, intercept and R^2.
void fitLine(const std::vector<double>& x, const std::vector<double>& y, double& slope,
             double& intercept, double& r2) {
  const double n = double(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
    syy += y[i] * y[i];
  }
  slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  intercept = (sy - slope * sx) / n;
  const double num = n * sxy - sx * sy;
  r2 = num * num / ((n * sxx - sx * sx) * (n * syy - sy * sy));
}

// "X / Y ms = R": a ratio of the paper's times (fps converted), for the printed paper side.
std::string paperRatio(const FigurePaperRow& a, const FigurePaperRow& b) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(2);
  if (!a.paperMs() || !b.paperMs()) return "no paper number";
  o << *a.paperMs() << " / " << *b.paperMs() << " ms = " << *a.paperMs() / *b.paperMs();
  return o.str();
}

// The paper's number as the paper gives it: "154 fps", or "-".
std::string paperText(const FigurePaperRow& r) {
  if (!r.paper) return "-";
  std::ostringstream o;
  o << *r.paper << " " << r.unit;
  return o.str();
}

// The paper's ordering of a over b (a faster where its time is below b's).
OrderingClaim paperOrdering(const FigurePaperRow& a, const FigurePaperRow& b) {
  const bool faster = a.paperMs() && b.paperMs() && *a.paperMs() < *b.paperMs();
  return {1.0, faster, a.label + (faster ? " faster than " : " slower than ") + b.label};
}

// Every case checked (and the device made once) before the first line is printed.
void checkCases(const RenderRequest& base, std::string RenderRequest::*technique,
                const std::vector<std::string>& specs) {
  RenderCache cache;
  bool device = true;
  for (const std::string& spec : specs) {
    RenderRequest r = base;
    r.*technique = spec;
    checkRenderRequest(r, device, &cache);
    device = false;
  }
}

// The header every benchmark prints: what is measured, how, and the machine's state.
void printHeader(const RenderRequest& base, const RepetitionOptions& reps) {
  std::cout << "scene " << base.scene << ", " << base.width << "x" << base.height << ", "
            << base.backend << "; each round renders every case once (" << base.repeat << " frame"
            << (base.repeat > 1 ? "s" : "") << " after " << base.warmup
            << " warm-up, their median is the round's sample), " << reps.minReps << ".."
            << reps.maxReps << " rounds round-robin";
  if (reps.targetCiPct > 0)
    std::cout << " until every 95% interval is within +-" << reps.targetCiPct << "%";
  std::cout << "; medians and ratios with 95% bootstrap intervals\nbefore: " << machineState()
            << "\n\n";
}

int runBench(const BenchOptions& o) {
  // The papers' numbers, kept once in the figures that reproduce them.
  const FigurePaperTable fig1 = figurePaperTable("dom-fig1");
  const FigurePaperTable occ = figurePaperTable("occ-fps");
  std::vector<const FigurePaperRow*> paperRows;
  for (const FigurePaperTable* t : {&fig1, &occ})
    for (const FigurePaperRow& r : t->rows) paperRows.push_back(&r);
  std::vector<std::string> specs;
  for (const FigurePaperRow* r : paperRows)
    if (std::find(specs.begin(), specs.end(), r->shadow) == specs.end()) specs.push_back(r->shadow);
  const std::size_t paperCases = specs.size();
  for (int maps : o.osmMaps) {
    if (maps < 1 || maps > 512)
      throw InputError("--osm-maps " + std::to_string(maps) + ": map counts must be in 1..512");
    specs.push_back("osm:passes=single,maps=" + std::to_string(maps));
  }
  if (std::set<int>(o.osmMaps.begin(), o.osmMaps.end()).size() < 2)
    throw InputError("--osm-maps needs at least two different map counts for the fit");
  checkCases(o.base, &RenderRequest::shadow, specs);
  std::cout << std::fixed << std::setprecision(2);
  printHeader(o.base, o.reps);

  // Every case of both figures in one interleaved group: the ratios compare rounds taken
  // side by side.
  std::vector<std::vector<double>> frames(specs.size());
  std::vector<std::function<double()>> cases;
  for (std::size_t i = 0; i < specs.size(); ++i)
    cases.push_back([&, i] {
      const Measured m = measure(o.base, specs[i]);
      frames[i].push_back(m.frameMs);
      return m.shadowMs;
    });
  const std::vector<Measurement> ms = measureInterleaved(cases, o.reps);
  std::map<std::string, const Measurement*> m;
  for (std::size_t i = 0; i < specs.size(); ++i) m[specs[i]] = &ms[i];

  std::cout << fig1.title << " (" << fig1.source << ") and " << occ.title << " (" << occ.source
            << ") beside ours (shadow ms, frame ms):\n";
  for (const FigurePaperRow* r : paperRows) {
    const std::size_t i = std::find(specs.begin(), specs.end(), r->shadow) - specs.begin();
    std::cout << "  " << std::left << std::setw(16) << r->shadow << std::right << " shadow "
              << describe(ms[i]) << "  frame " << median(frames[i]) << " ms  paper "
              << paperText(*r) << "\n";
  }
  std::cout << "\nratios (one backend, rounds interleaved, 95% paired bootstrap intervals):\n";
  const FigurePaperRow& none = fig1.row("none");
  const FigurePaperRow& dom3 = fig1.row("dom:layers=3");
  const FigurePaperRow& osm16 = fig1.row("osm:maps=16");
  std::string shadowPart = "no paper number";
  if (dom3.paperMs() && osm16.paperMs() && none.paperMs()) {
    std::ostringstream p;
    p << std::fixed << std::setprecision(2) << *dom3.paperMs() - *none.paperMs() << " / "
      << *osm16.paperMs() - *none.paperMs()
      << " ms = " << (*dom3.paperMs() - *none.paperMs()) / (*osm16.paperMs() - *none.paperMs());
    shadowPart = p.str();
  }
  printRatio(std::cout, "DOM(3) / OSM(16) shadow time", *m[dom3.shadow], *m[osm16.shadow],
             "paper, from fps: frames " + paperRatio(dom3, osm16) +
                 "; shadow part over 'no shadows' " + shadowPart,
             paperOrdering(dom3, osm16));
  const FigurePaperRow& occupancy = occ.row("occupancy");
  const FigurePaperRow& dom4 = occ.row("dom:layers=4");
  printRatio(std::cout, "occupancy / DOM(4) shadow time", *m[occupancy.shadow], *m[dom4.shadow],
             "occupancy paper: " + paperRatio(occupancy, dom4), paperOrdering(occupancy, dom4));

  std::cout << "\nOpacity shadow maps paper, Fig. 4: time against the number of maps "
               "(passes=single, one geometry pass per map):\n";
  std::vector<double> xs, ys;
  std::vector<const Measurement*> osm;
  for (std::size_t k = 0; k < o.osmMaps.size(); ++k) {
    const Measurement& r = ms[paperCases + k];
    osm.push_back(&r);
    xs.push_back(o.osmMaps[k]);
    ys.push_back(r.median.estimate);
    std::cout << "  maps " << std::setw(4) << o.osmMaps[k] << ": " << describe(r) << "\n";
  }
  double slope = 0, intercept = 0, r2 = 0;
  fitLine(xs, ys, slope, intercept, r2);
  // The slope's interval: the rounds resampled together, the line fitted to each resample's
  // medians (a percentile bootstrap like the ratios').
  std::vector<double> slopes;
  {
    const std::size_t rounds = osm.front()->samples.size();
    std::uint64_t state = 1;
    for (int b = 0; b < 1000; ++b) {
      std::vector<std::size_t> pick(rounds);
      for (auto& p : pick) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;  // Knuth's LCG
        p = static_cast<std::size_t>(state >> 33) % rounds;
      }
      std::vector<double> y;
      for (const Measurement* r : osm) {
        std::vector<double> v;
        for (std::size_t p : pick) v.push_back(r->samples[p]);
        y.push_back(median(v));
      }
      double s = 0, i0 = 0, q = 0;
      fitLine(xs, y, s, i0, q);
      slopes.push_back(s);
    }
  }
  std::cout << "  fit: " << slope << " ms per map [" << quantile(slopes, 0.025) << ", "
            << quantile(slopes, 0.975) << "] + " << intercept
            << " ms, R^2 = " << std::setprecision(4) << r2 << std::setprecision(2)
            << "  (paper: linear)\n";
  std::cout << "\nafter: " << machineState() << "\n";
  return 0;
}

// The depth-peeling rows, after the Fig. 2 ones: Everitt's classic peel (one
// geometry pass per layer, as the papers time it) and dual depth peeling
// (Bavoil & Myers 2008: ceil(layers/2) peel passes after one min/max pass),
// their passes from the techniques' own counters, their times against each
// other, and the classic peel against occupancy-ordered blending beside the
// occupancy paper's Fig. 2 ratio. Self-contained: one render per technique.
void printPeelingRows(const RenderRequest& base, double occupancyMs, const FigurePaperTable& fig2) {
  std::map<std::string, RenderResult> out;
  for (const char* oit : {"peel_classic", "dual_peel"}) {
    RenderRequest r = base;
    r.oit = oit;
    out[oit] = runRender(r);
  }
  const auto counter = [&](const std::string& oit, const std::string& key) {
    for (const Counter& c : out[oit].counters)
      if (c.name == key) return c.value;
    return -1.0;
  };
  const double classic = summarize(out["peel_classic"].frameMs).median;
  const double dual = summarize(out["dual_peel"].frameMs).median;
  const double layers = counter("dual_peel", "layers");
  std::cout << "\ndepth peeling (classic and dual):\n"
            << "  peel_classic " << std::setw(10) << classic << " ms   layers "
            << counter("peel_classic", "layers") << ", geometry passes "
            << counter("peel_classic", "geometry_passes") << " (Everitt: one per layer)";
  if (counter("peel_classic", "lost_ties") >= 0)
    std::cout << ", depth ties lost " << counter("peel_classic", "lost_ties");
  std::cout << "\n  dual_peel    " << std::setw(10) << dual << " ms   layers " << layers
            << ", geometry passes " << counter("dual_peel", "geometry_passes")
            << "  (Bavoil & Myers: ceil(layers/2)+1 = " << std::ceil(layers / 2.0) + 1 << ")\n"
            << "dual_peel / peel_classic time: " << dual / classic
            << "  (geometry passes: " << counter("dual_peel", "geometry_passes") << " / "
            << counter("peel_classic", "geometry_passes") << " = "
            << counter("dual_peel", "geometry_passes") / counter("peel_classic", "geometry_passes")
            << ")\n"
            << "peel_classic / occupancy-ordered time: " << classic / occupancyMs
            << "  (paper: " << paperRatio(fig2.row("peel", true), fig2.row("occupancy", true))
            << ")\n";
}

int runOitBench(const RenderRequest& base, const RepetitionOptions& reps) {
  // The paper's numbers, kept once in the figure that reproduces them; weighted blended OIT
  // (no number in the paper) beside them.
  const FigurePaperTable fig2 = figurePaperTable("occ-fig2");
  std::vector<std::string> oits;
  for (const FigurePaperRow& r : fig2.rows) oits.push_back(r.oit);
  oits.push_back("wboit");
  checkCases(base, &RenderRequest::oit, oits);
  std::cout << std::fixed << std::setprecision(2);
  std::cout << "shadow " << base.shadow << "; ";
  printHeader(base, reps);
  std::optional<DepthComplexity> eye;
  std::vector<std::function<double()>> cases;
  for (const std::string& oit : oits)
    cases.push_back([&, oit] {
      RenderRequest r = base;
      r.oit = oit;
      const RenderResult out = runRender(r);
      if (oit == "peel" && out.eyeComplexity) eye = out.eyeComplexity;
      return summarize(out.frameMs).median;
    });
  const std::vector<Measurement> ms = measureInterleaved(cases, reps);
  std::map<std::string, const Measurement*> m;
  for (std::size_t i = 0; i < oits.size(); ++i) m[oits[i]] = &ms[i];
  if (eye)
    std::cout << "eye depth complexity: max " << eye->max << ", mean " << eye->mean
              << "  (paper: " << fig2.source << ")\n\n";
  for (const std::string& oit : oits) {
    std::cout << "  " << std::left << std::setw(10) << oit << std::right << " "
              << describe(*m[oit]);
    for (const FigurePaperRow& r : fig2.rows)
      if (r.oit == oit && r.paperMs())
        std::cout << "   paper " << paperText(r) << " = " << *r.paperMs() << " ms";
    std::cout << "\n";
  }
  std::cout << "\nratios (95% paired bootstrap intervals):\n";
  const FigurePaperRow& peel = fig2.row("peel", true);
  const FigurePaperRow& occupancy = fig2.row("occupancy", true);
  const FigurePaperRow& wavg = fig2.row("wavg", true);
  printRatio(std::cout, "depth peeling / occupancy-ordered time", *m[peel.oit], *m[occupancy.oit],
             "paper: " + paperRatio(peel, occupancy), paperOrdering(peel, occupancy));
  printRatio(std::cout, "weighted average / occupancy-ordered time", *m[wavg.oit],
             *m[occupancy.oit], "paper: " + paperRatio(wavg, occupancy),
             paperOrdering(wavg, occupancy));
  printPeelingRows(base, m[occupancy.oit]->median.estimate, fig2);
  std::cout << "\nafter: " << machineState() << "\n";
  return 0;
}

// The benchmarks' rounds: 5 unless --min-reps says otherwise.
constexpr int kBenchMinReps = 5;
constexpr const char* kBenchRounds = "default 5";

// The settings the benchmarks take; the technique under test is theirs.
std::vector<std::string> benchSettings() {
  std::vector<std::string> keys = {"scene",        "backend", "platform", "size",      "primitive",
                                   "ribbon_width", "repeat",  "warmup",   "validation"};
  for (std::string& k : viewSettingKeys()) keys.push_back(std::move(k));
  return keys;
}

}  // namespace

void registerBenchCommand(CLI::App& app) {
  {
    auto* cmd = app.add_subcommand(
        "bench-oit", "the transparency paper's Fig. 2 timings as ratios in one run (a benchmark)");
    auto base = std::make_shared<RenderRequest>();
    base->scene = "clustered:strands=2000,points=8,head=0,alpha=0.2";  // complexity 125
    base->repeat = 1;
    base->width = base->height = 128;
    std::vector<std::string> keys = benchSettings();
    keys.push_back("shadow");
    auto settings = std::make_shared<CliSettings>(*cmd, keys, *base);
    auto runs = std::make_shared<CliRunOptions>(*cmd, kBenchRounds);
    cmd->callback([base, settings, runs] {
      runGuarded("bench-oit", [&] {
        settings->apply(*base);
        return runOitBench(*base, repetitions(runs->read(), kBenchMinReps));
      });
    });
  }
  auto* cmd = app.add_subcommand(
      "bench-shadows",
      "papers' shadow timing figures as ratios in one run (a benchmark, not a test)");
  auto o = std::make_shared<BenchOptions>();
  o->base.scene = "straight:strands=20000,points=16,head=0";  // 300k segments
  o->base.repeat = 1;
  auto settings = std::make_shared<CliSettings>(*cmd, benchSettings(), o->base);
  cmd->add_option("--osm-maps", o->osmMaps, "map counts for the OSM time-vs-maps fit");
  auto runs = std::make_shared<CliRunOptions>(*cmd, kBenchRounds);
  cmd->callback([o, settings, runs] {
    runGuarded("bench-shadows", [&] {
      settings->apply(o->base);
      o->reps = repetitions(runs->read(), kBenchMinReps);
      return runBench(*o);
    });
  });
}

}  // namespace sb
