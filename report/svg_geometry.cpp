#include "report/svg_geometry.h"

#include <algorithm>

#include "report/svg_text.h"

namespace imunoise::report::svg_detail {

bool overlaps(const Rect& a, const Rect& b) {
  return a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;
}

bool inside(const Rect& inner, const Rect& outer) {
  return inner.left >= outer.left && inner.right <= outer.right && inner.top >= outer.top &&
         inner.bottom <= outer.bottom;
}

Rect box_around(Point p, double half) { return {p.x - half, p.y - half, p.x + half, p.y + half}; }

bool clip_segment(Point& a, Point& b, const Rect& r) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  double t0 = 0.0, t1 = 1.0;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a.x - r.left, r.right - a.x, a.y - r.top, r.bottom - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) {
      if (t > t1) return false;
      t0 = std::max(t0, t);
    } else {
      if (t < t0) return false;
      t1 = std::min(t1, t);
    }
  }
  const Point start = a;
  if (t1 < 1.0) b = {start.x + t1 * dx, start.y + t1 * dy};
  if (t0 > 0.0) a = {start.x + t0 * dx, start.y + t0 * dy};
  return true;
}

std::string polyline_path(const std::vector<std::optional<Point>>& points, const Rect& clip) {
  std::string d;
  bool pen_down = false;
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (!points[i - 1] || !points[i]) {
      pen_down = false;
      continue;
    }
    Point a = *points[i - 1], b = *points[i];
    if (!clip_segment(a, b, clip)) {
      pen_down = false;
      continue;
    }
    const bool a_moved = a.x != points[i - 1]->x || a.y != points[i - 1]->y;
    if (!pen_down || a_moved) path_point(d, 'M', a.x, a.y);
    path_point(d, 0, b.x, b.y);
    pen_down = b.x == points[i]->x && b.y == points[i]->y;
  }
  return d;
}

int Obstacles::hits(const Rect& r) const {
  int n = 0;
  for (const auto& [a0, b0] : segments) {
    Point a = a0, b = b0;
    if (clip_segment(a, b, r)) ++n;
  }
  for (const Rect& b : boxes) n += overlaps(r, b) ? 1 : 0;
  return n;
}

void Obstacles::add_polyline(const std::vector<std::optional<Point>>& points) {
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (points[i - 1] && points[i]) segments.emplace_back(*points[i - 1], *points[i]);
  }
}

}  // namespace imunoise::report::svg_detail
