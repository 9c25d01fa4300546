#pragma once
// Charts and raster images as inline SVG for report.html: real axes with ticks at 1-2-5
// steps, grid lines, units in the axis titles, limit lines and marks, a legend. No script:
// the page needs nothing but itself. Internal to report/.

#include <string>
#include <utility>
#include <vector>

namespace freeturn::detail {

struct ChartSeries {
  std::string label;
  std::string colour;  // CSS colour
  std::vector<std::pair<double, double>> points;
  bool dots = false;  // dots (values along a spiral's radius) or a line
};

// A horizontal line across the chart (a tolerance, a machine limit) or, vertical, a mark
// at an x (where a warning is).
struct ChartLine {
  double at = 0;
  std::string label, colour;
};

struct Chart {
  std::string id;  // the <figure>'s id
  std::string title, x_title, y_title;  // titles with their units: "r (mm)"
  std::vector<ChartSeries> series;
  std::vector<ChartLine> horizontal, vertical;
  bool y_from_zero = false;  // the y range includes 0
  int width = 560, height = 300;
};

// The ticks of [lo, hi]: about `count`, at a 1, 2 or 5 × 10^k step, and the decimals that
// write that step exactly.
struct Ticks {
  std::vector<double> values;
  double lo = 0, hi = 1;  // the axis range, widened to whole steps
  int decimals = 0;
};
Ticks nice_ticks(double lo, double hi, int count = 6);

// A number as a person reads it: `decimals` after the point, "−" for minus.
std::string readable(double value, int decimals);

// The chart as <figure id=…><svg>…</svg><figcaption>…</figcaption></figure>.
std::string svg_chart(const Chart& chart);

// HTML-escaped text (&, <, >, ").
std::string html_escape(const std::string& s);

// An image as a data: URL, from rows of 8-bit RGB (size × size × 3, top row first).
std::string bmp_rgb_data_url(const std::vector<unsigned char>& rgb, int size);
// The same from palette indices (size × size, top row first) and a palette of 256 RGB
// entries: a third of the bytes, for maps of one quantity.
std::string bmp_indexed_data_url(const std::vector<unsigned char>& index,
                                 const std::vector<unsigned char>& palette_rgb, int size);

}  // namespace freeturn::detail
