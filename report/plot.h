/// @file
/// @brief What a plot is: axes (linear or log10, autoscaled or fixed), series with lines,
/// markers and error bars, slope guides, labelled points and a legend corner, coloured from
/// the Okabe–Ito colour-blind-safe palette. The types every figure builds and render_svg
/// (report/svg_plot.h) draws.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace imunoise::report {

enum class Scale { linear, log10 };

/// One axis. Unset limits are autoscaled from the plotted data (series points, error-bar ends,
/// point labels): log10 → the whole decades enclosing the data; linear → the enclosing
/// 1-2-5 ticks of `linear_ticks`. An empty range is widened (log: one decade each side;
/// linear: ±10 % of the value, ±1 around 0); no data at all gives 1…10 (log) or 0…1 (linear).
/// Log axes read 10^k (a superscript); with fewer than three decades in view the 2…9 ticks are
/// labelled with plain numbers, and a range inside one decade gets linear 1-2-5 ticks.
/// Overlapping tick labels are thinned to every 2nd, 3rd, … (keeping the one at 0).
struct Axis {
  std::string label;
  Scale scale = Scale::linear;
  std::optional<double> min, max;  ///< fixed limits (finite, > 0 on log10, min < max)
};

enum class Line { solid, dashed, dotted, none };
enum class Marker { none, circle, square, triangle, diamond, cross };

/// A data series. Points that cannot be plotted (NaN, ±Inf, ≤ 0 on a log10 axis) are skipped
/// and break the line there. A named series with no plottable point stays in the legend as
/// "NAME (no data)".
struct Series {
  std::string name;                   ///< legend text ("" = not in the legend)
  std::vector<double> x, y;           ///< same length
  std::vector<double> y_low, y_high;  ///< error bars: both empty, or both the length of y.
                                      ///< A low end ≤ 0 on a log10 axis is drawn from the
                                      ///< axis bottom; a bar with a non-finite end is skipped.
  int color = 0;                      ///< index into `palette_color` (wraps)
  Line line = Line::solid;
  Marker marker = Marker::none;
  double line_width = 1.5;  ///< px
  /// A filled band: empty, or as long as y — the area between fill_base and y is filled in
  /// the series colour (fill_opacity), over each run of points where x, y and fill_base are
  /// all plottable (a stacked plot: fill_base = the series below). Drawn below the line.
  std::vector<double> fill_base{};
  double fill_opacity = 0.6;  ///< 0…1
};

/// A reference line y = y0·(x/x0)^slope through (x0, y0) = (x, y): straight on log-log axes,
/// drawn as that power-law curve otherwise; light grey, dashed, clipped to the plot area, with
/// LABEL written along it (e.g. "−1/2").
struct SlopeGuide {
  double slope = 0.0;
  double x = 1.0, y = 1.0;
  std::string label;
};

/// A marked point with a short label (e.g. an IEEE-952 read-off); skipped when outside the
/// axes. Slope-guide and point labels go, of a few candidate places, to the one covering the
/// fewest data, guides, legend and earlier labels.
struct PointLabel {
  double x = 0.0, y = 0.0;
  std::string text;
  int color = 0;  ///< palette index of the marker
};

/// Where the legend goes inside the plot area; `best` takes the first of top_right, top_left,
/// bottom_left, bottom_right that covers the fewest data (markers, line segments, error bars).
enum class LegendCorner { best, top_right, top_left, bottom_left, bottom_right };

struct Plot {
  /// Prefix of every id in the SVG (clip paths); give each plot of one HTML page its own.
  /// Characters other than [A-Za-z0-9_-] become '_'.
  std::string id = "plot";
  std::string title;  ///< "" = no title
  Axis x, y;
  std::vector<Series> series;
  std::vector<SlopeGuide> guides;
  std::vector<PointLabel> points;
  int width_px = 900, height_px = 600;  ///< clamped to 200…20000
  LegendCorner legend = LegendCorner::best;
};

/// Colour (#RRGGBB) of palette INDEX: Okabe–Ito, ordered for contrast on white — blue,
/// vermillion, bluish green, reddish purple, orange, sky blue, black, yellow; wraps around.
std::string_view palette_color(int index);

}  // namespace imunoise::report
