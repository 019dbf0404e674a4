// report.html: one self-contained page (inline CSS, inline-SVG charts, images as
// data URIs, no scripts) that a browser shows offline.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>

#include "reports/report_data.h"
#include "reports/svg_chart.h"

namespace sb::report {

namespace {

namespace fs = std::filesystem;

std::string h(const std::string& s) { return htmlEscape(s); }

// The page may load nothing from anywhere (a report that needs the network is
// broken offline); a violation shows up in the browser console.
constexpr const char* kHead = R"(<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; img-src data:; style-src 'unsafe-inline'; script-src 'unsafe-inline'">
<style>
body { font-family: sans-serif; margin: 24px; color: #222; background: #fff; }
h2 { border-bottom: 1px solid #ccc; padding-bottom: 4px; margin-top: 32px; }
table { border-collapse: collapse; margin: 8px 0 16px; font-size: 13px; }
th, td { border: 1px solid #ccc; padding: 3px 8px; text-align: left; }
th { background: #f3f3f3; }
td { overflow-wrap: anywhere; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
.cost-cases td:last-child { white-space: nowrap; }
.charts, .grid { display: flex; flex-wrap: wrap; gap: 16px; align-items: flex-start; }
figure { margin: 0 0 12px; }
figcaption { font-size: 12px; max-width: 520px; overflow-wrap: anywhere; }
.grid img { width: 160px; image-rendering: pixelated; border: 1px solid #ccc; margin-right: 4px; }
.note { color: #a45a00; }
nav a { margin-right: 16px; }
.metric-choice { border: 1px solid #ddd; padding: 6px; }
.metric-choice .choice { display: none; }
.metric-choice .pick-0:checked ~ .choice-0, .metric-choice .pick-1:checked ~ .choice-1,
.metric-choice .pick-2:checked ~ .choice-2 { display: block; }
details { margin: 4px 0; }
details.passes { overflow-x: auto; }
details.passes table { font-size: 12px; }
summary { cursor: pointer; }
.strip img { width: auto; max-width: 100%; image-rendering: pixelated; border: 1px solid #ccc; }
</style>
)";

std::string base64(const std::string& bytes) {
  static const char* const kDigits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k)
      v = (v << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? kDigits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

void htmlTable(std::ostream& o, const Table& t) {
  o << "<table><thead><tr>";
  for (const std::string& c : t.header) o << "<th>" << h(c) << "</th>";
  o << "</tr></thead><tbody>\n";
  for (const auto& row : t.rows) {
    o << "<tr>";
    for (const Cell& c : row)
      o << (c.number ? "<td class=\"num\">" : "<td>") << h(c.text) << "</td>";
    o << "</tr>\n";
  }
  o << "</tbody></table>\n";
}

// "k=v, k=v" over the given params of a result (a series name); "all" when none.
std::string paramsLabel(const json& r, const std::vector<std::string>& keys) {
  std::string s;
  for (const std::string& k : keys)
    s += (s.empty() ? "" : ", ") + k + "=" + text(find(r, {"case", "params", k}));
  return s.empty() ? "all" : s;
}

std::vector<std::string> without(std::vector<std::string> keys,
                                 const std::vector<std::string>& drop) {
  std::erase_if(keys, [&](const std::string& k) {
    return std::find(drop.begin(), drop.end(), k) != drop.end();
  });
  return keys;
}

// Series of y against x, one per distinct `seriesOf` label in order of appearance,
// points sorted by x.
template <class X, class Y, class S>
std::vector<ChartSeries> seriesBy(const std::vector<const json*>& results, X x, Y y, S seriesOf) {
  std::vector<ChartSeries> out;
  for (const json* r : results) {
    const std::optional<double> xv = x(*r), yv = y(*r);
    if (!xv || !yv) continue;
    const std::string name = seriesOf(*r);
    auto it = std::find_if(out.begin(), out.end(), [&](const auto& s) { return s.name == name; });
    if (it == out.end()) it = out.insert(out.end(), ChartSeries{name});
    it->points.push_back({*xv, *yv, caseId(*r) + ": " + formatSig(*yv)});
  }
  for (ChartSeries& s : out)
    std::stable_sort(s.points.begin(), s.points.end(),
                     [](const ChartPoint& a, const ChartPoint& b) { return a.x < b.x; });
  return out;
}

// The error metrics a reader chooses between on the error-against-time charts.
struct ErrorMetric {
  const char* id;     // CSS class suffix
  const char* label;  // axis and radio label
  std::optional<double> (*value)(const json& r);
};
const ErrorMetric kErrorMetrics[] = {
    {"image-rmse", "image RMSE",
     [](const json& r) {
       return number(find(r, {"error", "image", "rmse"}));
     }},
    {"visibility-rmse", "visibility RMSE",
     [](const json& r) {
       return number(find(r, {"error", "visibility", "rmse"}));
     }},
    {"flip", "FLIP mean",
     [](const json& r) {
       return number(find(r, {"error", "image", "flip", "mean"}));
     }},
};

// (a) Error against frame time per scene, size and backend, with the Pareto
// frontier: one chart per error metric, chosen by radio buttons (CSS only, no
// Each case's frame as its passes' median times, stacked: where a technique spends its
// frame, at a glance, above the group's table of passes.
std::string passBars(const Group& g) {
  StackedBars b{g.name + ": frame time by pass", "ms (median per pass)", {}, {}};
  const bool nameOit = anyTransparency(g.results), nameShadow = anyShadow(g.results);
  for (const json* r : g.results) {
    const json* passes = find(*r, {"passes"});
    if (!passes || !passes->is_array()) continue;
    StackedBars::Row row{shortTechniqueOf(*r, nameOit, nameShadow) + ", " + backendOf(*r), {}};
    for (const json& p : *passes) {
      const std::string name = text(find(p, {"name"}));
      const auto at = std::find(b.parts.begin(), b.parts.end(), name) - b.parts.begin();
      if (at == static_cast<long>(b.parts.size())) b.parts.push_back(name);
      row.values.resize(b.parts.size(), NAN);
      row.values[at] = number(find(p, {"ms", "median"})).value_or(NAN);
    }
    b.rows.push_back(std::move(row));
  }
  return b.rows.empty() ? "" : "<figure>" + svgStackedBars(b) + "</figure>\n";
}

// script); every point labelled with its technique, its frame time's spread
// over the repetitions (min to max) as an error bar.
std::string errorTimeCharts(const ReportData& d) {
  std::vector<std::string> keys;
  std::map<std::string, std::vector<const json*>> byKey;
  for (const json* r : d.results) {
    const std::string key = comparableKey(*r);
    if (!byKey.count(key)) keys.push_back(key);
    byKey[key].push_back(r);
  }
  // One scene and size on several backends: their charts share their axes, so that
  // GL's and Vulkan's side by side compare at a glance (per metric: x0, x1, y0, y1).
  std::map<std::string, std::array<std::array<double, 4>, std::size(kErrorMetrics)>> shared;
  auto sceneAndSize = [](const json& r) {
    return text(find(r, {"scene", "spec"})) + " | " + sizeOf(r);
  };
  for (const json* r : d.results) {
    auto [it, added] = shared.try_emplace(sceneAndSize(*r));
    if (added)
      for (auto& span : it->second) span = {INFINITY, -INFINITY, INFINITY, -INFINITY};
    const auto ms = frameMs(*r);
    const auto lo = number(find(*r, {"frame_ms", "min"})),
               hi = number(find(*r, {"frame_ms", "max"}));
    for (std::size_t m = 0; m < std::size(kErrorMetrics); ++m) {
      const auto err = kErrorMetrics[m].value(*r);
      if (!ms || !err) continue;
      auto& span = it->second[m];
      span[0] = std::min({span[0], *ms, lo.value_or(*ms)});
      span[1] = std::max({span[1], *ms, hi.value_or(*ms)});
      span[2] = std::min(span[2], *err);
      span[3] = std::max(span[3], *err);
    }
  }
  std::ostringstream o;
  int chooser = 0;
  for (const std::string& key : keys) {
    std::ostringstream charts, radios;
    int shown = 0;
    const bool nameOit = anyTransparency(byKey[key]), nameShadow = anyShadow(byKey[key]);
    for (std::size_t m = 0; m < std::size(kErrorMetrics); ++m) {
      const ErrorMetric& metric = kErrorMetrics[m];
      Chart c;
      c.title = key + ": " + metric.label;
      c.xLabel = "frame ms (median; bar: min to max)";
      c.yLabel = metric.label;
      c.cssClass = "chart-error-time";
      c.width = 560;
      const auto& span = shared.at(sceneAndSize(*byKey[key].front()))[m];
      c.xLo = span[0], c.xHi = span[1], c.yLo = span[2], c.yHi = span[3];
      ChartSeries points{metric.label};
      points.line = false;
      points.color = 2 * static_cast<int>(m);
      for (const json* r : byKey[key]) {
        const auto ms = frameMs(*r);
        const auto err = metric.value(*r);
        if (!ms || !err) continue;
        ChartPoint p{*ms, *err,
                     techniqueOf(*r) + "\n" + caseId(*r) + "\n" + formatSig(*ms) + " ms, " +
                         metric.label + " " + formatSig(*err),
                     shortTechniqueOf(*r, nameOit, nameShadow)};
        const auto lo = number(find(*r, {"frame_ms", "min"}));
        const auto hi = number(find(*r, {"frame_ms", "max"}));
        if (lo && hi) p.xLo = *lo, p.xHi = *hi;
        points.points.push_back(p);
      }
      if (points.points.empty()) continue;
      ChartSeries front{std::string(metric.label) + " Pareto frontier",
                        paretoFrontier(points.points)};
      for (ChartPoint& p : front.points) p.label.clear(), p.xLo = p.xHi = NAN;  // drawn once
      front.markers = false;
      front.dashed = true;
      front.color = points.color;
      front.cssClass = "pareto-frontier";
      c.series.push_back(std::move(points));
      c.series.push_back(std::move(front));
      const std::string id = "errc" + std::to_string(chooser) + "-" + metric.id;
      radios << "<input type=\"radio\" name=\"errc" << chooser << "\" id=\"" << id << "\""
             << (shown == 0 ? " checked" : "") << " class=\"pick-" << m << "\"><label for=\"" << id
             << "\">" << h(metric.label) << "</label>\n";
      charts << "<figure class=\"choice choice-" << m << " metric-" << metric.id << "\">"
             << svgChart(c) << "</figure>\n";
      ++shown;
    }
    if (shown == 0) continue;
    o << "<div class=\"metric-choice\">\n" << radios.str() << charts.str() << "</div>\n";
    ++chooser;
  }
  return o.str();
}

// Error against eye depth complexity: per scene and size, one chart per
// technique, one series per backend (FLIP mean per bucket of eye layers, or
// the visibility error where there is no image).
std::string depthComplexityCharts(const ReportData& d) {
  std::vector<std::string> keys;
  std::map<std::string, std::vector<const json*>> byKey;
  const bool nameOit = anyTransparency(d.results), nameShadow = anyShadow(d.results);
  for (const json* r : d.results) {
    const json* buckets = find(*r, {"error", "by_eye_layers"});
    if (!buckets || !buckets->is_array()) continue;
    const std::string key = text(find(*r, {"scene", "spec"})) + " | " + sizeOf(*r) + " | " +
                            shortTechniqueOf(*r, nameOit, nameShadow);
    if (!byKey.count(key)) keys.push_back(key);
    byKey[key].push_back(r);
  }
  std::ostringstream o;
  for (const std::string& key : keys) {
    const bool image = find(*byKey[key][0], {"error", "image", "flip"}) != nullptr;
    const char* metric = image ? "flip_mean" : "visibility_mean_abs";
    Chart c{key, "eye layers (bucket's first)", image ? "mean FLIP" : "mean |visibility error|"};
    c.cssClass = "chart-depth-complexity";
    // A series per case: its backend, and what else tells it from the key's other cases
    // (the legend names each once: not "gl, vulkan, gl").
    std::vector<std::string> differ;
    for (const json* r : byKey[key])
      if (const json* params = find(*r, {"case", "params"}); params && params->is_object())
        for (const auto& [k, v] : params->items())
          if (k != "backend" && std::find(differ.begin(), differ.end(), k) == differ.end() &&
              std::any_of(byKey[key].begin(), byKey[key].end(),
                          [&, &k = k, &v = v](const json* other) {
                            const json* ov = find(*other, {"case", "params", k});
                            return !ov || *ov != v;
                          }))
            differ.push_back(k);
    std::sort(differ.begin(), differ.end());
    std::map<std::string, int> named;
    for (const json* r : byKey[key]) {
      std::string name = backendOf(*r);
      if (!differ.empty()) name += ", " + paramsLabel(*r, differ);
      if (const int n = ++named[name]; n > 1) name += " (" + std::to_string(n) + ")";
      ChartSeries s{name};
      for (const json& b : *find(*r, {"error", "by_eye_layers"})) {
        const json* layers = find(b, {"layers"});
        if (!layers || !layers->is_array() || layers->size() != 2) continue;
        const auto lo = number(&(*layers)[0]), hi = number(&(*layers)[1]);
        const auto e = number(find(b, {metric}));
        if (!lo || !hi || !e || *lo < 1) continue;  // pixels without hair: not on a log axis
        s.points.push_back({*lo, *e,
                            shortest(*lo) + "-" + shortest(*hi) + " layers, " +
                                text(find(b, {"pixels"})) + " pixels: " + formatSig(*e)});
      }
      if (!s.points.empty()) c.series.push_back(std::move(s));
    }
    if (!c.series.empty()) o << "<figure>" << svgChart(c) << "</figure>\n";
  }
  return o.str();
}

// Error against frame index for each animated case, beside its strip.
std::string animationSection(const ReportData& d, const fs::path& dir);

// (b), (c): frame time, memory and image error against numeric technique options,
// frame time against segments.
std::string groupCharts(const Group& g) {
  std::ostringstream o;
  for (const std::string& axis : g.params) {
    if (!axis.starts_with("shadow.") && !axis.starts_with("oit.")) continue;
    bool numeric = !g.results.empty();
    for (const json* r : g.results)
      numeric &= number(find(*r, {"case", "params", axis})).has_value();
    if (!numeric) continue;
    const std::vector<std::string> others = without(g.params, {axis});
    auto x = [&](const json& r) { return number(find(r, {"case", "params", axis})); };
    auto series = [&](const json& r) { return paramsLabel(r, others); };
    Chart time{g.name + ": frame time vs " + axis, axis, "frame ms (median)"};
    time.series = seriesBy(g.results, x, frameMs, series);
    Chart memory{g.name + ": memory vs " + axis, axis, "memory MiB (total)"};
    memory.series = seriesBy(
        g.results, x, [](const json& r) { return memoryMiB(r); }, series);
    o << "<figure>" << svgChart(time) << "</figure><figure>" << svgChart(memory) << "</figure>\n";
    // Error beside time: an axis such as compute_raster's LOD share trades one for the other.
    Chart error{g.name + ": " + kErrorMetrics[0].label + " vs " + axis, axis,
                kErrorMetrics[0].label};
    error.series = seriesBy(g.results, x, kErrorMetrics[0].value, series);
    const bool anyError = std::any_of(error.series.begin(), error.series.end(),
                                      [](const ChartSeries& s) { return !s.points.empty(); });
    if (anyError) o << "<figure>" << svgChart(error) << "</figure>\n";
  }
  const bool sized = std::count(g.params.begin(), g.params.end(), "scene.strands") ||
                     std::count(g.params.begin(), g.params.end(), "scene.points");
  if (sized) {
    const std::vector<std::string> others = without(g.params, {"scene.strands", "scene.points"});
    Chart c{g.name + ": frame time vs segments", "scene segments", "frame ms (median)"};
    c.series = seriesBy(
        g.results,
        [](const json& r) {
          return number(find(r, {"scene", "segments"}));
        },
        frameMs, [&](const json& r) { return paramsLabel(r, others); });
    o << "<figure>" << svgChart(c) << "</figure>\n";
  }
  return o.str();
}

// (d) The exact visibility and the technique's along the probed light ray.
std::string probeCharts(const Group& g) {
  std::ostringstream o;
  for (const json* r : g.results) {
    const json* depth = find(*r, {"probe", "light_depth"});
    if (!depth || !depth->is_array()) continue;
    Chart c{"visibility along a light ray: " + caseId(*r), "light depth", "visibility"};
    c.autoLog = false;  // visibility falls to 0 along the ray: a log axis hides the shape
    for (const char* curve : {"exact", "visibility"}) {
      ChartSeries s{curve};
      s.markers = false;
      const json* ys = find(*r, {"probe", curve});
      if (ys && ys->is_array())
        for (std::size_t i = 0; i < std::min(depth->size(), ys->size()); ++i) {
          const auto xv = number(&(*depth)[i]), yv = number(&(*ys)[i]);
          if (xv && yv) s.points.push_back({*xv, *yv, {}});
        }
      c.series.push_back(std::move(s));
    }
    o << "<figure>" << svgChart(c) << "</figure>\n";
  }
  return o.str();
}

// An <img> with the file embedded, or a note saying why it is not there.
std::string embeddedImage(const fs::path& dir, const std::string& rel, const std::string& alt) {
  std::string ext = fs::path(rel).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  const char* mime = ext == ".png"                       ? "image/png"
                     : (ext == ".jpg" || ext == ".jpeg") ? "image/jpeg"
                                                         : nullptr;
  if (!mime)
    return "<span class=\"note\">" + h(alt) + ": " + h(rel) +
           " (not a browser image format)</span>";
  std::ifstream f(dir / rel, std::ios::binary);
  std::ostringstream bytes;
  bytes << f.rdbuf();
  if (!f || bytes.str().empty())
    return "<span class=\"note\">" + h(alt) + ": " + h(rel) + " is missing</span>";
  return "<img src=\"data:" + std::string(mime) + ";base64," + base64(bytes.str()) + "\" alt=\"" +
         h(alt) + "\" title=\"" + h(alt + ": " + rel) + "\">";
}

// (e) image / reference / heatmap thumbnails per case.
std::string imageGrid(const Group& g, const fs::path& dir) {
  std::ostringstream o;
  for (const json* r : g.results) {
    const json* images = find(*r, {"images"});
    if (!images || !images->is_object() || images->empty()) continue;
    o << "<figure>";
    std::string kinds;
    // The further references' images (aa) after the four of every case.
    std::vector<std::string> all = {"image", "reference", "heatmap", "flip"};
    for (const std::string& name : moreReferenceNames({r}))
      if (find(*images, {name})) all.push_back(name);
    for (const std::string& kind : all) {
      if (const json* rel = find(*images, {kind}); rel && rel->is_string()) {
        o << embeddedImage(dir, rel->get<std::string>(), kind);
        kinds += (kinds.empty() ? "" : " / ") + kind;
      }
    }
    std::string caption = caseId(*r);
    const auto rmse = number(find(*r, {"error", "image", "rmse"}));
    const auto flip = number(find(*r, {"error", "image", "flip", "mean"}));
    if (rmse || flip)
      caption += std::string(" (image") + (rmse ? " RMSE " + formatSig(*rmse) : "") +
                 (rmse && flip ? "," : "") + (flip ? " FLIP " + formatSig(*flip) : "") + ")";
    o << "<figcaption>" << h(caption) << "<br>" << h(kinds) << "</figcaption></figure>\n";
  }
  const std::string grid = o.str();
  return grid.empty() ? "" : "<div class=\"grid\">\n" + grid + "</div>\n";
}

std::string animationSection(const ReportData& d, const fs::path& dir) {
  std::ostringstream o;
  for (const Animation& a : d.animations) {
    const json& r = *a.result;
    Chart c{a.caseId + " (" + a.spec + ")", "frame", "error against the frame's reference"};
    c.cssClass = "chart-animation";
    c.autoLog = false;
    const json* frames = find(r, {"animation", "per_frame"});
    for (const auto& [label, path] :
         {std::pair{"image RMSE", std::vector<std::string>{"image", "rmse"}},
          std::pair{"FLIP mean", std::vector<std::string>{"image", "flip"}},
          std::pair{"visibility RMSE", std::vector<std::string>{"visibility", "rmse"}}}) {
      ChartSeries s{label};
      if (frames && frames->is_array())
        for (const json& f : *frames) {
          const auto x = number(find(f, {"frame"}));
          const auto y = number(find(f, {path[0], path[1]}));
          if (x && y)
            s.points.push_back(
                {*x, *y, "frame " + shortest(*x) + ": " + label + " " + formatSig(*y)});
        }
      if (!s.points.empty()) c.series.push_back(std::move(s));
    }
    auto shown = [](std::optional<double> v) { return v ? formatSig(*v) : std::string(kNone); };
    o << "<figure>" << svgChart(c) << "<figcaption>" << h(a.technique) << ": flicker image "
      << h(shown(number(find(r, {"animation", "flicker", "image"})))) << ", visibility "
      << h(shown(number(find(r, {"animation", "flicker", "visibility"}))))
      << "</figcaption></figure>\n";
    if (const json* strip = find(r, {"images", "animation"}); strip && strip->is_string())
      o << "<figure class=\"strip\">"
        << embeddedImage(dir, strip->get<std::string>(), "animation strip") << "<figcaption>"
        << h(a.caseId)
        << ": frames side by side, the technique above, the reference "
           "below</figcaption></figure>\n";
  }
  return o.str();
}

}  // namespace

std::string renderHtml(const ReportData& d, const fs::path& dir) {
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n"
    << kHead << "<title>" << h(d.title) << "</title>\n</head>\n<body>\n";
  o << "<h1>" << h(d.title) << "</h1>\n";
  if (!d.description.empty()) o << "<p>" << h(d.description) << "</p>\n";
  o << "<nav><a href=\"#context\">Context</a><a href=\"#paper-tables\">Paper tables</a>"
       "<a href=\"#error-time\">Error vs time</a><a href=\"#budgets\">Budgets</a>"
       "<a href=\"#depth-complexity\">Error vs depth complexity</a>"
       "<a href=\"#animation\">Animation</a><a href=\"#groups\">Groups</a>"
       "<a href=\"#passes\">Passes</a><a href=\"#cost-model\">Cost model</a>"
       "<a href=\"#warnings\">Warnings</a></nav>\n";

  o << "<h2 id=\"context\">Context</h2>\n<table><tbody>\n";
  for (const auto& [label, value] : d.context)
    o << "<tr><th>" << h(label) << "</th><td>" << h(value) << "</td></tr>\n";
  o << "</tbody></table>\n";
  if (!d.devices.rows.empty()) htmlTable(o, d.devices);

  o << "<h2 id=\"paper-tables\">Paper tables</h2>\n";
  if (d.paperTables.empty()) o << "<p>None in this suite.</p>\n";
  for (const PaperTable& t : d.paperTables) {
    o << "<h3>" << h(t.title) << "</h3>\n<p>" << h(t.about) << "</p>\n";
    htmlTable(o, t.table);
    for (const std::string& n : t.notes) o << "<p class=\"note\">Note: " << h(n) << "</p>\n";
  }

  o << "<h2 id=\"error-time\">Error against frame time</h2>\n"
       "<p>Per scene, image size and backend, with the error to show chosen above each chart "
       "(image RMSE, visibility RMSE or FLIP). Each point is labelled with its technique (hover "
       "for the case); the bar is the frame time's spread over the repetitions (min to max). "
       "The dashed line is the Pareto frontier (no other technique is both faster and more "
       "accurate).</p>\n";
  const std::string errorCharts = errorTimeCharts(d);
  o << (errorCharts.empty() ? "<p>No results with an error.</p>\n"
                            : "<div class=\"charts\">\n" + errorCharts + "</div>\n");

  o << "<h2 id=\"budgets\">Which technique within which budget</h2>\n"
       "<p>Per scene, size and backend, from the Pareto frontiers: for each frame-time budget, "
       "the most accurate technique that fits it, by FLIP and by image RMSE.</p>\n";
  if (d.budgets.empty()) o << "<p>No results with an image error.</p>\n";
  for (const BudgetTable& b : d.budgets) {
    o << "<h3>" << h(b.key) << "</h3>\n<div class=\"budget\">";
    htmlTable(o, b.table);
    o << "</div>\n";
  }

  o << "<h2 id=\"depth-complexity\">Error against depth complexity</h2>\n"
       "<p>Per technique, the mean error over the pixels whose eye depth complexity (hair "
       "fragments in the reference) falls in each bucket of layers (1, 2-3, 4-7, ...): where "
       "each technique breaks.</p>\n";
  const std::string complexity = depthComplexityCharts(d);
  o << (complexity.empty() ? "<p>No results with errors per depth complexity.</p>\n"
                           : "<div class=\"charts\">\n" + complexity + "</div>\n");

  o << "<h2 id=\"animation\">Error under animation</h2>\n"
       "<p>Error against frame index and a strip of frames per animated case; flicker is the "
       "mean over frames and pixels of |(T_t - T_{t-1}) - (R_t - R_{t-1})|.</p>\n";
  if (d.animations.empty()) {
    o << "<p>No animated cases.</p>\n";
  } else {
    htmlTable(o, d.animationTable);
    o << "<div class=\"charts\">\n" << animationSection(d, dir) << "</div>\n";
  }

  o << "<h2 id=\"groups\">Groups</h2>\n";
  if (d.groups.empty()) o << "<p>No results.</p>\n";
  for (std::size_t i = 0; i < d.groups.size(); ++i) {
    const Group& g = d.groups[i];
    o << "<h3 id=\"group-" << i << "\">" << h(g.name.empty() ? "(no group)" : g.name) << "</h3>\n";
    if (!g.description.empty()) o << "<p>" << h(g.description) << "</p>\n";
    if (g.results.empty()) {
      o << "<p>No results.</p>\n";
      continue;
    }
    htmlTable(o, g.table);
    const std::string charts = groupCharts(g) + probeCharts(g);
    if (!charts.empty()) o << "<div class=\"charts\">\n" << charts << "</div>\n";
    o << imageGrid(g, dir);
  }

  o << "<h2 id=\"passes\">Passes: time and work</h2>\n<p>" << h(kPassesAbout) << "</p>\n";
  bool anyPasses = false;
  for (const Group& g : d.groups) {
    if (g.passes.rows.empty()) continue;
    anyPasses = true;
    o << passBars(g);
    // Collapsed: a row per pass of every case would bury the rest of the page.
    o << "<details class=\"passes\"><summary>" << h(g.name.empty() ? "(no group)" : g.name) << " ("
      << g.passes.rows.size() << " passes of " << g.results.size() << " cases)</summary>\n";
    htmlTable(o, g.passes);
    o << "</details>\n";
  }
  if (!anyPasses) o << "<p>No results with passes.</p>\n";

  o << "<h2 id=\"cost-model\">Cost model</h2>\n<p>" << h(kCostModelAbout) << "</p>\n";
  if (d.costModels.empty()) o << "<p>No results with work counters.</p>\n";
  for (const CostModel& m : d.costModels) {
    o << "<h3>" << h(costModelTitle(m)) << "</h3>\n<p>" << h(costModelSummary(m)) << "</p>\n";
    if (m.fitted) htmlTable(o, costTermsTable(m));
    if (m.cases.empty()) continue;
    Table cases = costCasesTable(m);
    o << "<details class=\"cost-cases\"" << (m.fitted ? " open" : "") << "><summary>"
      << cases.rows.size() << " cases by measured / predicted";
    const auto flagged = std::count_if(m.cases.begin(), m.cases.end(),
                                       [](const CostCase& c) { return c.inefficient; });
    if (flagged) o << ", " << flagged << " marked inefficient";
    o << "</summary>\n";
    htmlTable(o, cases);
    o << "</details>\n";
  }

  if (!d.failures.empty()) {
    o << "<h2 id=\"failed\">Failed cases</h2>\n<ul>\n";
    for (const Warning& f : d.failures)
      o << "<li><code>" << h(f.caseId) << "</code>: failed: " << h(f.message) << "</li>\n";
    o << "</ul>\n";
  }
  o << "<h2 id=\"warnings\">Warnings</h2>\n";
  if (d.warnings.empty())
    o << "<p>None.</p>\n";
  else {
    o << "<ul>\n";
    for (const Warning& w : d.warnings)
      o << "<li><code>" << h(w.caseId) << "</code>: " << h(w.message) << "</li>\n";
    o << "</ul>\n";
  }
  o << "</body>\n</html>\n";
  return o.str();
}

}  // namespace sb::report
