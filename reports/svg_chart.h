// Small inline-SVG line and scatter charts for report.html: axes with ticks and
// labels, a legend, tooltips (<title>) and optional labels and horizontal error
// bars on points; no scripts, no external resources.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace sb {

struct ChartPoint {
  double x = 0, y = 0;
  std::string tip;    // tooltip text (plain text; escaped when drawn)
  std::string label;  // drawn beside the point (class "point-label"), not only on hover
  // A horizontal error bar from xLo to xHi (class "error-bar"); none when not finite.
  double xLo = std::numeric_limits<double>::quiet_NaN();
  double xHi = std::numeric_limits<double>::quiet_NaN();
};

struct ChartSeries {
  std::string name;
  std::vector<ChartPoint> points;  // non-finite points are skipped
  bool line = true;                // join the points in the given order
  bool markers = true;
  bool dashed = false;
  int color = -1;        // palette index; -1: the series' position in the chart
  std::string cssClass;  // class of the series' polyline (e.g. "pareto-frontier")
};

struct Chart {
  std::string title, xLabel, yLabel;
  std::string cssClass;  // class of the <svg> element
  std::vector<ChartSeries> series;
  int width = 460, plotHeight = 240;  // width grows to fit a long title
  bool autoLog = true;                // false: linear axes whatever the values
  // Ranges the axes cover besides the points' (charts shown side by side, e.g. one
  // scene on GL and on Vulkan, share their axes by giving each the union); empty
  // ranges (lo > hi) add nothing.
  double xLo = INFINITY, xHi = -INFINITY, yLo = INFINITY, yHi = -INFINITY;
};

// An axis is logarithmic when autoLog is set and all its values are positive and
// span more than kLogAxisRange (frame times from 4 to 60 ms read better on a log
// axis than squeezed at the bottom of a linear one), else linear with "nice" ticks
// (1, 2, 5 x 10^k).
//
// Point labels do not overprint: each is put at the first of a few places around
// its point that overlaps no label placed before it and no point (its box
// estimated as characters x kLabelFontSize x 0.6 wide); a label with no free place
// is left off and listed below the legend as "crowded: label — x, y" (class
// "crowded").
inline constexpr double kLogAxisRange = 10;
inline constexpr double kLabelFontSize = 9;
std::string svgChart(const Chart& chart);

// Horizontal bars, one per row, each split into its parts (e.g. a case's frame time
// into its passes' times), every part in its own colour with a legend; a part's
// tooltip gives its row, name and value. Rows share one linear value axis.
struct StackedBars {
  std::string title, valueLabel;
  std::vector<std::string> parts;  // the legend, in drawing order
  struct Row {
    std::string label;
    std::vector<double> values;  // per part; non-finite or <= 0: absent
  };
  std::vector<Row> rows;
};
std::string svgStackedBars(const StackedBars& bars);

// The points of `points` on the Pareto frontier for minimum x and minimum y
// (no other point is at least as good in both and better in one), by ascending x.
std::vector<ChartPoint> paretoFrontier(std::vector<ChartPoint> points);

// Text escaped for HTML and SVG content and attribute values.
std::string htmlEscape(const std::string& s);

}  // namespace sb
