// report.html: one self-contained page (inline CSS, inline-SVG charts, images as
// data URIs, no scripts) that a browser shows offline.
#include <algorithm>
#include <cctype>
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
td.num { text-align: right; font-variant-numeric: tabular-nums; }
.charts, .grid { display: flex; flex-wrap: wrap; gap: 16px; align-items: flex-start; }
figure { margin: 0 0 12px; }
figcaption { font-size: 12px; max-width: 520px; overflow-wrap: anywhere; }
.grid img { width: 160px; image-rendering: pixelated; border: 1px solid #ccc; margin-right: 4px; }
.note { color: #a45a00; }
nav a { margin-right: 16px; }
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

// (a) Error against frame time per scene, size and backend, with the Pareto frontier.
std::string errorTimeCharts(const ReportData& d) {
  std::vector<std::string> keys;
  std::map<std::string, std::vector<const json*>> byKey;
  for (const json* r : d.results) {
    const std::string key =
        text(find(*r, {"scene", "spec"})) + " | " + sizeOf(*r) + " | " + backendOf(*r);
    if (!byKey.count(key)) keys.push_back(key);
    byKey[key].push_back(r);
  }
  std::ostringstream o;
  for (const std::string& key : keys) {
    Chart c;
    c.title = key;
    c.xLabel = "frame ms (median)";
    c.yLabel = "RMSE";
    c.cssClass = "chart-error-time";
    c.width = 560;
    int color = 0;
    for (const char* kind : {"image", "visibility"}) {
      ChartSeries points{std::string(kind) + " RMSE"};
      points.line = false;
      points.color = color;
      for (const json* r : byKey[key]) {
        const auto ms = frameMs(*r);
        const auto err = number(find(*r, {"error", kind, "rmse"}));
        if (ms && err)
          points.points.push_back({*ms, *err,
                                   techniqueOf(*r) + "\n" + caseId(*r) + "\n" + formatSig(*ms) +
                                       " ms, " + kind + " RMSE " + formatSig(*err)});
      }
      if (points.points.empty()) continue;
      ChartSeries front{std::string(kind) + " RMSE Pareto frontier", paretoFrontier(points.points)};
      front.markers = false;
      front.dashed = true;
      front.color = color;
      front.cssClass = "pareto-frontier";
      c.series.push_back(std::move(points));
      c.series.push_back(std::move(front));
      color += 2;
    }
    if (!c.series.empty()) o << "<figure>" << svgChart(c) << "</figure>\n";
  }
  return o.str();
}

// (b), (c): frame time and memory against numeric technique options, frame time
// against segments.
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
    for (const char* kind : {"image", "reference", "heatmap", "flip"}) {
      if (const json* rel = find(*images, {kind}); rel && rel->is_string()) {
        o << embeddedImage(dir, rel->get<std::string>(), kind);
        kinds += (kinds.empty() ? "" : " / ") + std::string(kind);
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

}  // namespace

std::string renderHtml(const ReportData& d, const fs::path& dir) {
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n"
    << kHead << "<title>" << h(d.title) << "</title>\n</head>\n<body>\n";
  o << "<h1>" << h(d.title) << "</h1>\n";
  if (!d.description.empty()) o << "<p>" << h(d.description) << "</p>\n";
  o << "<nav><a href=\"#context\">Context</a><a href=\"#paper-tables\">Paper tables</a>"
       "<a href=\"#error-time\">Error vs time</a><a href=\"#groups\">Groups</a>"
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
       "<p>Per scene, image size and backend; hover a point for its technique. The dashed "
       "line is the Pareto frontier (no other technique is both faster and more accurate).</p>\n";
  const std::string errorCharts = errorTimeCharts(d);
  o << (errorCharts.empty() ? "<p>No results with an error.</p>\n"
                            : "<div class=\"charts\">\n" + errorCharts + "</div>\n");

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
