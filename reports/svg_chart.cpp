#include "reports/svg_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace sb {

namespace {

// Tableau 10: distinct in colour and in lightness.
const char* const kPalette[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                                "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"};
constexpr int kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);

// Margins around the plot area, in pixels.
constexpr int kLeft = 72, kRight = 16, kTop = 30, kBottom = 46, kLegendRow = 16, kInset = 6;

struct Axis {
  double lo = 0, hi = 1;
  bool log = false;
  double step = 1;  // linear tick spacing (for the label precision)
  std::vector<double> ticks;

  // Position of v along the axis, 0 at lo and 1 at hi.
  double frac(double v) const {
    if (log) return (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
    return (v - lo) / (hi - lo);
  }

  std::string label(double v) const {
    char buf[32];
    if (log) {
      // Ticks are 1, 2 or 5 x 10^e: as many decimals as the leading digit needs.
      const int e = static_cast<int>(std::floor(std::log10(v) + 1e-9));
      if (e >= -3 && e <= 5)
        std::snprintf(buf, sizeof buf, "%.*f", std::max(0, -e), v);
      else
        std::snprintf(buf, sizeof buf, "%g", v);
    } else if (step >= 1e6 || step < 1e-6) {
      std::snprintf(buf, sizeof buf, "%g", v);
    } else {
      const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
      std::snprintf(buf, sizeof buf, "%.*f", decimals, std::abs(v) < step * 1e-9 ? 0.0 : v);
    }
    return buf;
  }
};

double niceStep(double raw) {
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / p;
  return (f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10) * p;
}

Axis makeAxis(double min, double max, bool autoLog) {
  Axis a;
  if (autoLog && min > 0 && max / min > kLogAxisRange) {
    a.log = true;
    const int e0 = static_cast<int>(std::floor(std::log10(min)));
    const int e1 = static_cast<int>(std::ceil(std::log10(max)));
    // Up to three decades, ticks at 1, 2 and 5 x 10^k and the ends at the nearest of
    // them, so a range of 15x does not sit in a corner of two bare decades.
    const bool fine = e1 - e0 <= 3;
    std::vector<double> steps;
    for (int e = e0; e <= e1; ++e)
      for (double m : {1.0, 2.0, 5.0})
        if (fine || m == 1.0) steps.push_back(m * std::pow(10.0, e));
    a.lo = steps.front();
    a.hi = steps.back();
    for (double t : steps)
      if (t <= min * (1 + 1e-12)) a.lo = t;
    for (auto it = steps.rbegin(); it != steps.rend(); ++it)
      if (*it >= max * (1 - 1e-12)) a.hi = *it;
    for (double t : steps)
      if (t >= a.lo && t <= a.hi) a.ticks.push_back(t);
    return a;
  }
  if (max == min) {  // one value: centre it in a small range
    const double pad = min == 0 ? 1 : std::abs(min) * 0.1;
    min -= pad;
    max += pad;
  }
  a.step = niceStep((max - min) / 5);
  a.lo = std::floor(min / a.step) * a.step;
  a.hi = std::ceil(max / a.step) * a.step;
  const int n = static_cast<int>(std::lround((a.hi - a.lo) / a.step));
  for (int i = 0; i <= n; ++i) a.ticks.push_back(a.lo + a.step * i);
  return a;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

bool finite(const ChartPoint& p) { return std::isfinite(p.x) && std::isfinite(p.y); }
bool hasBar(const ChartPoint& p) { return std::isfinite(p.xLo) && std::isfinite(p.xHi); }

constexpr int kCrowdedRow = 14;
constexpr double kMarkerRadius = 3.5;

struct Box {
  double x0, y0, x1, y1;
  bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  bool inside(const Box& o) const { return x0 >= o.x0 && x1 <= o.x1 && y0 >= o.y0 && y1 <= o.y1; }
};

struct PlacedLabel {
  double x, y;  // text-anchor start, baseline
  std::string text;
  double px, py;  // the point
  bool far;       // placed on the outer ring: drawn with a leader line to its point
  Box box;
};

struct LabelLayout {
  std::vector<PlacedLabel> placed;
  std::vector<std::string> crowded;  // "label — x, y"
};

std::string g3(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// Greedy placement in series and point order: the first candidate place around the
// point whose box stays in the plot and overlaps no marker and no label placed so far.
template <class PX, class PY>
LabelLayout placeLabels(const Chart& chart, PX px, PY py, Box plot) {
  std::vector<Box> taken;
  for (const ChartSeries& s : chart.series) {
    if (!s.markers) continue;
    for (const ChartPoint& p : s.points)
      if (finite(p))
        taken.push_back({px(p.x) - kMarkerRadius, py(p.y) - kMarkerRadius, px(p.x) + kMarkerRadius,
                         py(p.y) + kMarkerRadius});
  }
  const double fs = kLabelFontSize;
  LabelLayout out;
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    for (const ChartPoint& p : chart.series[i].points) {
      if (!finite(p) || p.label.empty()) continue;
      const double x = px(p.x), y = py(p.y);
      const double w = static_cast<double>(p.label.size()) * fs * 0.6;
      bool done = false;
      // Near the point first (up right, as a reader looks), then two rings farther out;
      // above and below also with the label's end or start over the point, for points
      // near the plot's edges.
      for (double d : {5.0, 16.0, 28.0}) {
        const std::pair<double, double> spots[] = {
            {x + d, y - d},          {x + d, y + d + fs},         {x - d - w, y - d},
            {x - d - w, y + d + fs}, {x + d + 1, y + fs / 2},     {x - d - 1 - w, y + fs / 2},
            {x - w / 2, y - d - 1},  {x - w / 2, y + d + 1 + fs}, {x + 3 - w, y - d - 1},
            {x - 3, y - d - 1},      {x + 3 - w, y + d + 1 + fs}, {x - 3, y + d + 1 + fs}};
        for (const auto& [tx, ty] : spots) {
          const Box b{tx, ty - fs, tx + w, ty + 2};  // 2 px for descenders
          if (!b.inside(plot) ||
              std::any_of(taken.begin(), taken.end(), [&](const Box& t) { return t.overlaps(b); }))
            continue;
          taken.push_back(b);
          out.placed.push_back({tx, ty, p.label, x, y, d > 5, b});
          done = true;
          break;
        }
        if (done) break;
      }
      if (!done) out.crowded.push_back(p.label + " — " + g3(p.x) + ", " + g3(p.y));
    }
  }
  return out;
}

// The crowded labels as lines of "crowded: a — x, y; b — x, y" that fit `width` at
// the chart's 11 px font (about 6.6 px a character).
std::vector<std::string> wrapCrowded(const std::vector<std::string>& items, int width) {
  std::vector<std::string> lines;
  const std::size_t chars = static_cast<std::size_t>(std::max(20, width / 7));
  std::string line = "crowded (x, y): ";
  bool first = true;
  for (const std::string& item : items) {
    if (!first && line.size() + 2 + item.size() > chars) {
      lines.push_back(line + ";");
      line = "  ";
      first = true;
    }
    line += (first ? "" : "; ") + item;
    first = false;
  }
  if (!items.empty()) lines.push_back(line);
  return lines;
}

}  // namespace

std::string svgStackedBars(const StackedBars& b) {
  constexpr int kLabelWidth = 230, kBarWidth = 360, kRowHeight = 16, kTop = 24;
  double most = 0;
  for (const auto& row : b.rows) {
    double sum = 0;
    for (double v : row.values)
      if (std::isfinite(v) && v > 0) sum += v;
    most = std::max(most, sum);
  }
  const Axis ax = makeAxis(0, most > 0 ? most : 1, false);
  const int legendRows = static_cast<int>((b.parts.size() + 2) / 3);
  const int plotBottom = kTop + kRowHeight * static_cast<int>(b.rows.size());
  const int height = plotBottom + 36 + 14 * legendRows;
  const int width = kLabelWidth + kBarWidth + 20;
  auto xOf = [&](double v) { return kLabelWidth + kBarWidth * (v - ax.lo) / (ax.hi - ax.lo); };
  std::ostringstream o;
  o << "<svg class=\"stacked-bars\" width=\"" << width << "\" height=\"" << height
    << "\" viewBox=\"0 0 " << width << " " << height
    << "\" font-family=\"sans-serif\" font-size=\"10\">\n"
    << "<text x=\"4\" y=\"14\" font-weight=\"bold\">" << htmlEscape(b.title) << "</text>\n";
  for (double t : ax.ticks)
    o << "<line x1=\"" << fmt(xOf(t)) << "\" y1=\"" << kTop << "\" x2=\"" << fmt(xOf(t))
      << "\" y2=\"" << plotBottom << "\" stroke=\"#ddd\"/><text x=\"" << fmt(xOf(t)) << "\" y=\""
      << plotBottom + 12 << "\" text-anchor=\"middle\">" << ax.label(t) << "</text>\n";
  o << "<text x=\"" << kLabelWidth + kBarWidth / 2 << "\" y=\"" << plotBottom + 26
    << "\" text-anchor=\"middle\">" << htmlEscape(b.valueLabel) << "</text>\n";
  for (std::size_t r = 0; r < b.rows.size(); ++r) {
    const auto& row = b.rows[r];
    const int y = kTop + kRowHeight * static_cast<int>(r);
    o << "<text x=\"" << kLabelWidth - 4 << "\" y=\"" << y + 11 << "\" text-anchor=\"end\">"
      << htmlEscape(row.label) << "</text>\n";
    double at = 0;
    for (std::size_t p = 0; p < row.values.size() && p < b.parts.size(); ++p) {
      const double v = row.values[p];
      if (!std::isfinite(v) || v <= 0) continue;
      o << "<rect x=\"" << fmt(xOf(at)) << "\" y=\"" << y + 2 << "\" width=\""
        << fmt(xOf(at + v) - xOf(at)) << "\" height=\"" << kRowHeight - 4 << "\" fill=\""
        << kPalette[p % kPaletteSize] << "\"><title>" << htmlEscape(row.label) << "\n"
        << htmlEscape(b.parts[p]) << ": " << g3(v) << "</title></rect>\n";
      at += v;
    }
  }
  for (std::size_t p = 0; p < b.parts.size(); ++p) {
    const int x = 4 + 200 * static_cast<int>(p % 3), y = plotBottom + 36 + 14 * int(p / 3);
    o << "<rect x=\"" << x << "\" y=\"" << y - 8 << "\" width=\"10\" height=\"10\" fill=\""
      << kPalette[p % kPaletteSize] << "\"/><text x=\"" << x + 14 << "\" y=\"" << y << "\">"
      << htmlEscape(b.parts[p]) << "</text>\n";
  }
  o << "</svg>";
  return o.str();
}

std::string htmlEscape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::vector<ChartPoint> paretoFrontier(std::vector<ChartPoint> points) {
  std::erase_if(points, [](const ChartPoint& p) { return !finite(p); });
  std::stable_sort(points.begin(), points.end(), [](const ChartPoint& a, const ChartPoint& b) {
    return a.x != b.x ? a.x < b.x : a.y < b.y;
  });
  std::vector<ChartPoint> front;
  double best = std::numeric_limits<double>::infinity();
  for (const ChartPoint& p : points) {
    if (p.y < best) {
      front.push_back(p);
      best = p.y;
    }
  }
  return front;
}

std::string svgChart(const Chart& chart) {
  double x0 = chart.xLo, x1 = chart.xHi, y0 = chart.yLo, y1 = chart.yHi;
  for (const ChartSeries& s : chart.series) {
    for (const ChartPoint& p : s.points) {
      if (!finite(p)) continue;
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
      y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
      if (hasBar(p)) x0 = std::min(x0, p.xLo), x1 = std::max(x1, p.xHi);
    }
  }
  const bool empty = !(x0 <= x1);
  const Axis ax = empty ? Axis{} : makeAxis(x0, x1, chart.autoLog);
  const Axis ay = empty ? Axis{} : makeAxis(y0, y1, chart.autoLog);

  // About 7 px per character of the 13 px title.
  const int width = std::max(chart.width, 7 * static_cast<int>(chart.title.size()) + 16);
  const int plotW = width - kLeft - kRight, plotH = chart.plotHeight;
  // Data are mapped inset from the frame so that points on the range ends stay visible.
  auto px = [&](double x) { return kLeft + kInset + ax.frac(x) * (plotW - 2 * kInset); };
  auto py = [&](double y) { return kTop + kInset + (1 - ay.frac(y)) * (plotH - 2 * kInset); };
  const LabelLayout labels = empty ? LabelLayout{}
                                   : placeLabels(chart, px, py,
                                                 Box{double(kLeft), double(kTop),
                                                     double(kLeft + plotW), double(kTop + plotH)});
  const std::vector<std::string> crowdedLines = wrapCrowded(labels.crowded, width - kLeft);
  const int height = kTop + plotH + kBottom + kLegendRow * static_cast<int>(chart.series.size()) +
                     kCrowdedRow * static_cast<int>(crowdedLines.size()) + 4;

  std::ostringstream o;
  o << "<svg class=\"" << htmlEscape(chart.cssClass.empty() ? "chart" : chart.cssClass)
    << "\" width=\"" << width << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << " "
    << height << "\" role=\"img\" aria-label=\"" << htmlEscape(chart.title)
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  o << "<text x=\"" << width / 2 << "\" y=\"16\" text-anchor=\"middle\" font-size=\"13\">"
    << htmlEscape(chart.title) << "</text>\n";
  o << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << plotW << "\" height=\""
    << plotH << "\" fill=\"#fff\" stroke=\"#888\"/>\n";
  if (empty) {
    o << "<text x=\"" << kLeft + plotW / 2 << "\" y=\"" << kTop + plotH / 2
      << "\" text-anchor=\"middle\" fill=\"#888\">no data</text>\n</svg>\n";
    return o.str();
  }

  // Grid lines and tick labels.
  for (double t : ax.ticks) {
    const std::string x = fmt(px(t));
    o << "<line x1=\"" << x << "\" x2=\"" << x << "\" y1=\"" << kTop << "\" y2=\"" << kTop + plotH
      << "\" stroke=\"#e4e4e4\"/><text x=\"" << x << "\" y=\"" << kTop + plotH + 14
      << "\" text-anchor=\"middle\">" << ax.label(t) << "</text>\n";
  }
  for (double t : ay.ticks) {
    const std::string y = fmt(py(t));
    o << "<line x1=\"" << kLeft << "\" x2=\"" << kLeft + plotW << "\" y1=\"" << y << "\" y2=\"" << y
      << "\" stroke=\"#e4e4e4\"/><text x=\"" << kLeft - 4 << "\" y=\"" << y
      << "\" text-anchor=\"end\" dominant-baseline=\"middle\">" << ay.label(t) << "</text>\n";
  }
  o << "<text x=\"" << kLeft + plotW / 2 << "\" y=\"" << kTop + plotH + 32
    << "\" text-anchor=\"middle\">" << htmlEscape(chart.xLabel) << (ax.log ? " (log)" : "")
    << "</text>\n";
  o << "<text transform=\"translate(14," << kTop + plotH / 2
    << ") rotate(-90)\" text-anchor=\"middle\">" << htmlEscape(chart.yLabel)
    << (ay.log ? " (log)" : "") << "</text>\n";

  // Series, then the legend below the plot.
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const ChartSeries& s = chart.series[i];
    const char* color = kPalette[(s.color >= 0 ? s.color : static_cast<int>(i)) % kPaletteSize];
    const std::string dash = s.dashed ? " stroke-dasharray=\"6,3\"" : "";
    std::vector<const ChartPoint*> pts;
    for (const ChartPoint& p : s.points)
      if (finite(p)) pts.push_back(&p);
    if (s.line && pts.size() >= 2) {
      o << "<polyline";
      if (!s.cssClass.empty()) o << " class=\"" << htmlEscape(s.cssClass) << "\"";
      o << " fill=\"none\" stroke=\"" << color << "\" stroke-width=\"1.5\"" << dash << " points=\"";
      for (const ChartPoint* p : pts) o << fmt(px(p->x)) << "," << fmt(py(p->y)) << " ";
      o << "\"/>\n";
    }
    for (const ChartPoint* p : pts) {
      if (!hasBar(*p)) continue;
      const std::string y = fmt(py(p->y)), lo = fmt(px(p->xLo)), hi = fmt(px(p->xHi));
      const std::string top = fmt(py(p->y) - 4), bottom = fmt(py(p->y) + 4);
      o << "<path class=\"error-bar\" stroke=\"" << color << "\" fill=\"none\" d=\"M" << lo << ","
        << y << "H" << hi << "M" << lo << "," << top << "V" << bottom << "M" << hi << "," << top
        << "V" << bottom << "\"/>\n";
    }
    if (s.markers) {
      o << "<g fill=\"" << color << "\">";
      for (const ChartPoint* p : pts) {
        o << "<circle cx=\"" << fmt(px(p->x)) << "\" cy=\"" << fmt(py(p->y)) << "\" r=\"3.5\">";
        if (!p->tip.empty()) o << "<title>" << htmlEscape(p->tip) << "</title>";
        o << "</circle>";
      }
      o << "</g>\n";
    }
    const int ly = kTop + plotH + kBottom + kLegendRow * static_cast<int>(i) + 8;
    o << "<line x1=\"" << kLeft << "\" x2=\"" << kLeft + 20 << "\" y1=\"" << ly << "\" y2=\"" << ly
      << "\" stroke=\"" << color << "\" stroke-width=\"" << (s.line ? "1.5" : "0") << "\"" << dash
      << "/>";
    if (s.markers)
      o << "<circle cx=\"" << kLeft + 10 << "\" cy=\"" << ly << "\" r=\"3.5\" fill=\"" << color
        << "\"/>";
    o << "<text x=\"" << kLeft + 26 << "\" y=\"" << ly << "\" dominant-baseline=\"middle\">"
      << htmlEscape(s.name) << "</text>\n";
  }
  // Labels over every series, with a white halo, so that no line runs through them.
  for (const PlacedLabel& l : labels.placed) {
    if (l.far) {
      // From the marker's edge to the nearest point of the label's box.
      const double ex = std::clamp(l.px, l.box.x0, l.box.x1),
                   ey = std::clamp(l.py, l.box.y0, l.box.y1);
      const double len = std::hypot(ex - l.px, ey - l.py);
      if (len > kMarkerRadius + 1)
        o << "<line class=\"label-leader\" x1=\"" << fmt(l.px + (ex - l.px) * kMarkerRadius / len)
          << "\" y1=\"" << fmt(l.py + (ey - l.py) * kMarkerRadius / len) << "\" x2=\"" << fmt(ex)
          << "\" y2=\"" << fmt(ey) << "\" stroke=\"#999\" stroke-width=\"0.75\"/>\n";
    }
    o << "<text class=\"point-label\" x=\"" << fmt(l.x) << "\" y=\"" << fmt(l.y)
      << "\" font-size=\"" << kLabelFontSize
      << "\" fill=\"#333\" stroke=\"#fff\" stroke-width=\"2.5\" paint-order=\"stroke\">"
      << htmlEscape(l.text) << "</text>\n";
  }
  for (std::size_t k = 0; k < crowdedLines.size(); ++k)
    o << "<text class=\"crowded\" x=\"" << kLeft << "\" y=\""
      << kTop + plotH + kBottom + kLegendRow * static_cast<int>(chart.series.size()) +
             kCrowdedRow * static_cast<int>(k) + 8
      << "\" dominant-baseline=\"middle\" fill=\"#555\">" << htmlEscape(crowdedLines[k])
      << "</text>\n";
  o << "</svg>\n";
  return o.str();
}

}  // namespace sb
