// `strandbench bench-shadows`: the self-shadowing papers' timing and memory
// figures as ratios measured on one backend in one run (not a test: these
// machines are shared and noisy, so only ratios within a run are compared).
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <set>

#include "harness/commands.h"
#include "harness/render.h"
#include "reports/stats.h"

namespace sb {

namespace {

struct BenchOptions {
  RenderRequest base;
  std::vector<int> osmMaps = {1, 2, 4, 8, 16, 32};
};

struct Measured {
  double shadowMs = 0;  // sum of the shadow technique's pass medians
  double frameMs = 0;
  std::size_t shadowBytes = 0;
};

Measured measure(const RenderRequest& base, const std::string& shadow) {
  RenderRequest r = base;
  r.shadow = shadow;
  const RenderResult out = runRender(r);
  Measured m;
  const std::string prefix = Spec::parse(shadow).name + ".";
  for (const PassTimes& p : out.passes)
    if (p.name.rfind(prefix, 0) == 0) m.shadowMs += summarize(p.ms).median;
  m.frameMs = summarize(out.frameMs).median;
  m.shadowBytes = out.bytesOwnedBy("shadow");
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

const std::vector<std::pair<std::string, std::string>> kFig1 = {
    {"none", "154 fps"},
    {"osm:maps=16", "81 fps"},
    {"osm:maps=128", "2.3 fps"},
    {"dc:clusters=4", "73-79 fps"},
    {"dom:layers=3", "114 fps"},
    {"dom:layers=4", "-"},
    {"occupancy", "(occupancy paper: 41 ms vs DOM4 33.5 ms)"}};

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

int runBench(const BenchOptions& o) {
  std::vector<std::string> specs;
  for (const auto& row : kFig1) specs.push_back(row.first);
  for (int maps : o.osmMaps) {
    if (maps < 1 || maps > 256)
      throw InputError("--osm-maps " + std::to_string(maps) + ": map counts must be in 1..256");
    specs.push_back("osm:passes=single,maps=" + std::to_string(maps));
  }
  if (std::set<int>(o.osmMaps.begin(), o.osmMaps.end()).size() < 2)
    throw InputError("--osm-maps needs at least two different map counts for the fit");
  checkCases(o.base, &RenderRequest::shadow, specs);
  std::cout << std::fixed << std::setprecision(2);
  std::cout << "scene " << o.base.scene << ", " << o.base.width << "x" << o.base.height << ", "
            << o.base.backend << ", median of " << o.base.repeat << " after " << o.base.warmup
            << " warm-up\n\n";

  std::cout << "Deep opacity maps paper, Fig. 1 (GeForce 8800, fps) beside ours (shadow ms, "
               "frame ms):\n";
  std::map<std::string, Measured> m;
  for (const auto& [spec, paper] : kFig1) {
    m[spec] = measure(o.base, spec);
    std::cout << "  " << std::left << std::setw(16) << spec << std::right << " shadow "
              << std::setw(9) << m[spec].shadowMs << " ms  frame " << std::setw(9)
              << m[spec].frameMs << " ms  paper " << paper << "\n";
  }
  std::cout << "\nratios (one backend, one run):\n"
            << "  DOM(3) / OSM(16) shadow time: "
            << m["dom:layers=3"].shadowMs / m["osm:maps=16"].shadowMs
            << "  (paper, from fps: frames 8.8 / 12.3 ms = 0.71; shadow part over 'no shadows' "
               "2.3 / 5.9 ms = 0.39)\n"
            << "  occupancy / DOM(4) shadow time: "
            << m["occupancy"].shadowMs / m["dom:layers=4"].shadowMs
            << "  (occupancy paper: 41 / 33.5 = 1.22)\n";

  std::cout << "\nOpacity shadow maps paper, Fig. 4: time against the number of maps "
               "(passes=single, one geometry pass per map):\n";
  std::vector<double> xs, ys;
  for (int maps : o.osmMaps) {
    const Measured r = measure(o.base, "osm:passes=single,maps=" + std::to_string(maps));
    xs.push_back(maps);
    ys.push_back(r.shadowMs);
    std::cout << "  maps " << std::setw(4) << maps << ": " << std::setw(9) << r.shadowMs << " ms\n";
  }
  double slope = 0, intercept = 0, r2 = 0;
  fitLine(xs, ys, slope, intercept, r2);
  std::cout << "  fit: " << slope << " ms per map + " << intercept
            << " ms, R^2 = " << std::setprecision(4) << r2 << std::setprecision(2)
            << "  (paper: linear)\n";
  return 0;
}

// Issue 14's peeling rows, after the Fig. 2 ones: Everitt's classic peel (one
// geometry pass per layer, as the papers time it) and dual depth peeling
// (Bavoil & Myers 2008: ceil(layers/2) peel passes after one min/max pass),
// their passes from the techniques' own counters, their times against each
// other, and the classic peel against occupancy-ordered blending beside the
// occupancy paper's Fig. 2 ratio. Self-contained: one render per technique.
void printPeelingRows(const RenderRequest& base, double occupancyMs) {
  std::map<std::string, RenderResult> out;
  for (const char* oit : {"peel_classic", "dual_peel"}) {
    RenderRequest r = base;
    r.oit = oit;
    out[oit] = runRender(r);
  }
  const auto counter = [&](const std::string& oit, const std::string& key) {
    const auto& c = out[oit].oitCounters;
    return c.count(key) ? c.at(key) : -1.0;
  };
  const double classic = summarize(out["peel_classic"].frameMs).median;
  const double dual = summarize(out["dual_peel"].frameMs).median;
  const double layers = counter("dual_peel", "layers");
  std::cout << "\npeeling (issue 14):\n"
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
            << "  (paper: 51 / 4.01 fps = 12.7)\n";
}

int runOitBench(const RenderRequest& base) {
  const std::vector<std::pair<std::string, double>> rows = {
      {"peel", 4.01}, {"occupancy", 51}, {"wavg", 72}, {"wboit", 0}, {"none", 120}};
  std::vector<std::string> oits;
  for (const auto& row : rows) oits.push_back(row.first);
  checkCases(base, &RenderRequest::oit, oits);
  std::cout << std::fixed << std::setprecision(2);
  std::cout << "scene " << base.scene << ", " << base.width << "x" << base.height << ", "
            << base.backend << ", shadow " << base.shadow << ", median of " << base.repeat
            << " after " << base.warmup << " warm-up\n";
  std::map<std::string, double> ms;
  for (const auto& [oit, fps] : rows) {
    RenderRequest r = base;
    r.oit = oit;
    const RenderResult out = runRender(r);
    ms[oit] = summarize(out.frameMs).median;
    if (oit == "peel" && out.eyeComplexity)
      std::cout << "eye depth complexity: max " << out.eyeComplexity->max << ", mean "
                << out.eyeComplexity->mean << "  (paper's Fig. 2 scene: 112)\n\n";
    std::cout << "  " << std::left << std::setw(10) << oit << std::right << std::setw(10) << ms[oit]
              << " ms";
    if (fps > 0) std::cout << "   paper " << fps << " fps = " << 1000.0 / fps << " ms";
    std::cout << "\n";
  }
  std::cout << "\ndepth peeling / occupancy-ordered time: " << ms["peel"] / ms["occupancy"]
            << "  (paper: 51 / 4.01 fps = 12.7)\n"
            << "weighted average / occupancy-ordered time: " << ms["wavg"] / ms["occupancy"]
            << "  (paper: 51 / 72 fps = 0.71)\n";
  printPeelingRows(base, ms["occupancy"]);
  return 0;
}

// The settings the benchmarks take; the technique under test is theirs.
const std::vector<std::string> kBenchSettings = {"scene",       "backend",        "platform",
                                                 "size",        "primitive",      "ribbon_width",
                                                 "repeat",      "warmup",         "validation",
                                                 "camera_eye",  "camera_target",  "camera_up",
                                                 "fov",         "near",           "far",
                                                 "light",       "light_position", "light_direction",
                                                 "light_color", "light_intensity"};

}  // namespace

void registerBenchCommand(CLI::App& app) {
  {
    auto* cmd = app.add_subcommand(
        "bench-oit", "the transparency paper's Fig. 2 timings as ratios in one run (a benchmark)");
    auto base = std::make_shared<RenderRequest>();
    base->scene = "clustered:strands=2000,points=8,head=0,alpha=0.2";  // complexity 125
    base->repeat = 3;
    base->width = base->height = 128;
    std::vector<std::string> keys = kBenchSettings;
    keys.push_back("shadow");
    auto settings = std::make_shared<CliSettings>(*cmd, keys, *base);
    cmd->callback([base, settings] {
      runGuarded("bench-oit", [&] {
        settings->apply(*base);
        return runOitBench(*base);
      });
    });
  }
  auto* cmd = app.add_subcommand(
      "bench-shadows",
      "papers' shadow timing figures as ratios in one run (a benchmark, not a test)");
  auto o = std::make_shared<BenchOptions>();
  o->base.scene = "straight:strands=20000,points=16,head=0";  // 300k segments
  o->base.repeat = 3;
  auto settings = std::make_shared<CliSettings>(*cmd, kBenchSettings, o->base);
  cmd->add_option("--osm-maps", o->osmMaps, "map counts for the OSM time-vs-maps fit");
  cmd->callback([o, settings] {
    runGuarded("bench-shadows", [&] {
      settings->apply(o->base);
      return runBench(*o);
    });
  });
}

}  // namespace sb
