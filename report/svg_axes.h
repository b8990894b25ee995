/// @file
/// @brief Axes of the SVG plots (internal to report/svg_*): the axis ranges from the data and
/// the fixed limits, their ticks, the data → pixel maps, the plot area inside the margins, and
/// the grid, frame, tick labels and axis labels.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "report/axis_ticks.h"
#include "report/svg_geometry.h"
#include "report/plot.h"

namespace imunoise::report::svg_detail {

/// The range [lo, hi] of the values added; empty until one is.
struct Extent {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return !(lo <= hi); }
};

/// An axis with its range settled (autoscaled or fixed) and its ticks.
struct ResolvedAxis {
  Scale scale = Scale::linear;
  double lo = 0.0, hi = 1.0;
  std::vector<Tick> ticks;  ///< inside [lo, hi]
};

/// V can be drawn on a SCALE axis: finite, and > 0 on log10.
bool plottable(Scale scale, double v);

/// V in the units the axis is linear in: log10(V) on a log10 axis, V otherwise.
double transformed(Scale scale, double v);

/// Data → pixel along one axis.
struct AxisMap {
  Scale scale = Scale::linear;
  double t_lo = 0.0, t_hi = 1.0;    ///< range in transformed units (log10 or identity)
  double px_lo = 0.0, px_hi = 1.0;  ///< pixels of lo and hi

  AxisMap(const ResolvedAxis& axis, double pixel_lo, double pixel_hi)
      : scale(axis.scale),
        t_lo(transformed(axis.scale, axis.lo)),
        t_hi(transformed(axis.scale, axis.hi)),
        px_lo(pixel_lo),
        px_hi(pixel_hi) {}

  bool plottable(double v) const { return svg_detail::plottable(scale, v); }
  /// Fraction of the range at transformed value T (clamped far outside, never NaN).
  double fraction(double t) const;
  double px_of_t(double t) const { return px_lo + fraction(t) * (px_hi - px_lo); }
  double px(double v) const { return px_of_t(transformed(scale, v)); }
  /// V plottable and inside the axis range (with a relative tolerance of 1e-9).
  bool inside(double v) const;
};

/// AXIS with its range and ticks resolved as `Axis` documents, autoscaled from DATA; WHICH
/// ("x" or "y") names it in errors. Throws InputError for bad fixed limits.
ResolvedAxis resolve_axis(const Axis& axis, const Extent& data, const std::string& which);

/// Where a plot is drawn: the SVG size, the resolved axes, the plot area inside the margins
/// (sized from the tick and axis labels) and the data → pixel maps onto it.
struct Canvas {
  double width, height;  ///< of the whole SVG [px]
  ResolvedAxis x_axis, y_axis;
  Rect area;             ///< the plot area (the frame)
  Rect clip;             ///< lines are clipped here (area + 2 px), so no coordinate is huge
  AxisMap x, y;          ///< data → pixel within `area`
  std::string clip_id;   ///< id of the clipPath at the exact area
  std::string clip_ref;  ///< "url(#clip_id)"
};

/// The canvas of PLOT: x autoscaled from everything drawable, then y from what lies inside the
/// x range; the margins from the label sizes. Throws InputError for bad fixed axis limits.
Canvas lay_out(const Plot& plot);

/// Both scales are log10 (slope guides are then straight lines).
bool log_log(const Canvas& c);

/// @name Drawing
/// @{
/// The grid lines of every tick: minor (lighter) below major.
void append_grid(std::string& out, const Canvas& c);
/// The frame of the plot area and the tick marks, outwards.
void append_frame_and_ticks(std::string& out, const Canvas& c);
/// The tick labels, thinned to every 2nd, 3rd, … where they would overlap.
void append_tick_labels(std::string& out, const Canvas& c);
/// The x axis label under the plot and the y axis label rotated left of it (when set).
void append_axis_labels(std::string& out, const Plot& plot, const Canvas& c);
/// @}

}  // namespace imunoise::report::svg_detail
