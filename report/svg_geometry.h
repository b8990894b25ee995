/// @file
/// @brief Pixel geometry of the SVG plots (internal to report/svg_*): points and rectangles,
/// Liang–Barsky segment clipping, clipped polylines as path data, and the obstacles a label
/// counts when it looks for a free place.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace imunoise::report::svg_detail {

/// A position in SVG pixels (y grows downwards).
struct Point {
  double x, y;
};

/// An axis-aligned rectangle in SVG pixels (top < bottom).
struct Rect {
  double left, top, right, bottom;
  /// P inside, or on the edge, of the rectangle grown by TOLERANCE on every side.
  bool contains(Point p, double tolerance = 0.0) const {
    return p.x >= left - tolerance && p.x <= right + tolerance && p.y >= top - tolerance &&
           p.y <= bottom + tolerance;
  }
};

/// A and B share interior (touching edges do not overlap).
bool overlaps(const Rect& a, const Rect& b);
/// INNER lies within OUTER (edges may coincide).
bool inside(const Rect& inner, const Rect& outer);
/// The square of half-side HALF centred on P.
Rect box_around(Point p, double half);

/// Liang–Barsky (Liang & Barsky 1984, "A new concept and method for line clipping", ACM TOG
/// 3(1)): clips segment A–B to R in place; false when nothing is left. An end inside R is not
/// moved.
bool clip_segment(Point& a, Point& b, const Rect& r);

/// Polyline through POINTS (std::nullopt = a gap) clipped to CLIP, as path data with one
/// subpath per visible run ("" when nothing is visible).
std::string polyline_path(const std::vector<std::optional<Point>>& points, const Rect& clip);

/// What a label should not cover: data segments (lines, error bars) and boxes (markers,
/// legend, labels already placed).
struct Obstacles {
  std::vector<std::pair<Point, Point>> segments;
  std::vector<Rect> boxes;

  /// How many segments cross R plus how many boxes overlap it.
  int hits(const Rect& r) const;
  /// Adds the segments between consecutive present POINTS.
  void add_polyline(const std::vector<std::optional<Point>>& points);
};

}  // namespace imunoise::report::svg_detail
