/// @file
/// @brief Placement of the SVG plots' legend and labels off the data (internal to
/// report/svg_*): the legend corner covering the fewest data, slope-guide labels along their
/// lines and point labels beside their points, each at the candidate place covering the
/// fewest data, guides, legend and earlier labels.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "report/svg_axes.h"
#include "report/svg_geometry.h"
#include "report/plot.h"
#include "report/svg_series.h"

namespace imunoise::report::svg_detail {

/// @name Legend
/// @{
/// The legend: named series, "(no data)" after a name when nothing of it could be plotted.
struct Legend {
  std::vector<std::pair<std::size_t, std::string>> entries;  ///< series index, text
  std::optional<Rect> box;                                   ///< none without entries
};

/// The legend of PLOT in the corner asked for, or (LegendCorner::best) in the first of
/// top_right, top_left, bottom_left, bottom_right whose box inside AREA hits the fewest DATA.
Legend place_legend(const Plot& plot, const std::vector<SeriesGeometry>& geometry, const Rect& area,
                    const Obstacles& data);

/// The legend box with a line sample, marker and text per entry (nothing without a box).
void append_legend(std::string& out, const Plot& plot, const Legend& legend);
/// @}

/// @name Labels over the data
/// @{
/// Adds to DATA the markers of the labelled points of PLOT inside the axes of C.
void add_point_boxes(const Plot& plot, const Canvas& c, Obstacles& data);

/// What the labels compete for.
struct LabelSpace {
  Obstacles taken;  ///< data, legend and the labels placed so far
  Rect area;        ///< the plot area; places leaving it come last
  const std::vector<GuideGeometry>* guides;

  /// The cost of a label in TEXT_BOX: the obstacles and guide lines (other than OWN) hit by
  /// the box grown by a little air, plus 100000 when it leaves the area.
  int cost(const Rect& text_box, const GuideGeometry* own) const;
};

/// The label of every guide with one, along its visible line (upright; level on lines steeper
/// than 60°), at the cheapest candidate near the anchor; each placed box joins SPACE.taken.
void append_guide_labels(std::string& out, const Canvas& c, LabelSpace& space);

/// The labelled points of PLOT inside the axes of C: a marker, and the text at the cheapest of
/// eight places around it, close and then further away; each placed box joins SPACE.taken.
void append_point_labels(std::string& out, const Plot& plot, const Canvas& c, LabelSpace& space);
/// @}

}  // namespace imunoise::report::svg_detail
