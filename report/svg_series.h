/// @file
/// @brief Data of the SVG plots in pixels (internal to report/svg_*): series (line, markers,
/// error bars) and slope guides, their clipped path data, the marker shapes and line styles,
/// and the SVG elements that draw them.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "report/plot.h"
#include "report/svg_axes.h"
#include "report/svg_geometry.h"

namespace imunoise::report::svg_detail {

/// @name Marks
/// @{
/// Appends to D the path of MARKER of size R (≈ the radius) centred on P.
void marker_path(std::string& d, Marker marker, Point p, double r);
/// `<path …/>` of the markers in D: filled with a thin white outline, a cross stroked.
/// Nothing when D is empty.
void append_marker_element(std::string& out, Marker marker, std::string_view color,
                           const std::string& d);
/// Stroke attributes of a LINE of WIDTH in COLOR (unfilled, round joins, dashes scaled to
/// WIDTH).
void append_line_style(std::string& out, std::string_view color, Line line, double width);
/// The line width of S clamped to 0.25…10 px (1.5 when not finite).
double line_width_of(const Series& s);
/// @}

/// One series in pixels: drawn below the labels, and what the labels and the legend avoid.
struct SeriesGeometry {
  std::vector<std::optional<Point>> pts;  ///< per data point; nullopt = not plottable
  std::string bars, markers, line;        ///< path data ("" = none)
  std::string fill;                       ///< path data of the filled band ("" = none)
  bool has_data = false;                  ///< some point is plottable
};

/// The geometry of every series of PLOT on C (error bars and line clipped to the area, markers
/// at points inside it); DATA gets their markers, line segments and error bars.
std::vector<SeriesGeometry> series_geometry(const Plot& plot, const Canvas& c, Obstacles& data);

/// A slope guide in pixels.
struct GuideGeometry {
  const SlopeGuide* guide;
  std::vector<std::optional<Point>> pts;  ///< samples over the x range (2 on log-log axes)
  std::string d;                          ///< path data clipped to the area
  std::optional<Point> anchor;            ///< pixel of (guide x, guide y)
  Obstacles segments;                     ///< the line, for other labels to avoid
};

/// The slope guides of PLOT that are valid and visible on C.
std::vector<GuideGeometry> guide_geometry(const Plot& plot, const Canvas& c);

/// @name Drawing
/// @{
/// The guide lines: light grey, dashed, clipped to the area.
void append_guides(std::string& out, const std::vector<GuideGeometry>& guides, const Canvas& c);
/// One `<g>` per series with something to draw: filled band, error bars, line, markers.
void append_series(std::string& out, const Plot& plot, const std::vector<SeriesGeometry>& geometry,
                   const Canvas& c);
/// @}

}  // namespace imunoise::report::svg_detail
