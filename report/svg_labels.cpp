#include "report/svg_labels.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

#include "report/svg_style.h"
#include "report/svg_text.h"

namespace imunoise::report::svg_detail {
namespace {

/// The first of CANDIDATES (not empty) with the lowest COST.
template <class Candidate, class Cost>
const Candidate& cheapest(const std::vector<Candidate>& candidates, const Cost& cost) {
  const Candidate* best = &candidates.front();
  int best_cost = cost(*best);
  for (const Candidate& c : candidates) {
    const int n = cost(c);
    if (n < best_cost) {
      best_cost = n;
      best = &c;
    }
  }
  return *best;
}

// ------------------------------------------------------------------------------ line labels

/// A label for a line through AT with direction (DX, DY): written along it, kept upright,
/// above (SIDE < 0) or below it; on lines steeper than 60° written level, left (SIDE < 0) or
/// right of it. BOX is its axis-aligned bounding box.
struct LineLabel {
  Point at;  // the origin of the text frame
  double angle_deg = 0.0;
  double baseline = 0.0;  // y of the baseline in the text frame
  Rect box{};
};

LineLabel line_label(Point at, double dx, double dy, double text_w, int side) {
  constexpr double kPi = 3.14159265358979323846;
  double angle = std::atan2(dy, dx) * 180.0 / kPi;
  if (angle > 90.0) angle -= 180.0;
  if (angle <= -90.0) angle += 180.0;
  LineLabel label;
  const double h = kSmallFont;
  if (std::abs(angle) > 60.0) {
    const double centre_x = at.x + (side < 0 ? -1.0 : 1.0) * (0.5 * text_w + 6.0);
    label.at = {centre_x, at.y + 0.35 * h};
    label.box = {centre_x - 0.5 * text_w, at.y - 0.5 * h, centre_x + 0.5 * text_w, at.y + 0.5 * h};
    return label;
  }
  label.at = at;
  label.angle_deg = angle;
  label.baseline = side < 0 ? -5.0 : 5.0 + 0.75 * h;
  const double centre = label.baseline - 0.35 * h;  // of the text, in the text frame
  const double s = std::sin(angle * kPi / 180.0), c = std::cos(angle * kPi / 180.0);
  const Point mid{at.x - s * centre, at.y + c * centre};
  const double hx = 0.5 * (std::abs(c) * text_w + std::abs(s) * h);
  const double hy = 0.5 * (std::abs(s) * text_w + std::abs(c) * h);
  label.box = {mid.x - hx, mid.y - hy, mid.x + hx, mid.y + hy};
  return label;
}

void append_line_label(std::string& out, const LineLabel& label, std::string_view text) {
  out.append("<text");
  if (label.angle_deg != 0.0) {
    out.append(" transform=\"translate(");
    append_number(out, label.at.x);
    out.push_back(' ');
    append_number(out, label.at.y);
    out.append(") rotate(");
    append_number(out, label.angle_deg);
    out.append(")\" x=\"0\"");
    attr(out, "y", label.baseline);
  } else {
    attr(out, "x", label.at.x);
    attr(out, "y", label.at.y + label.baseline);
  }
  append_label_style(out, "middle", kGuideTextColor);
  append_text(out, text);
  out.append("</text>\n");
}

/// Both sides of the line through AT with direction (DX, DY), appended to CANDIDATES.
void add_both_sides(std::vector<LineLabel>& candidates, Point at, double dx, double dy,
                    double text_w) {
  candidates.push_back(line_label(at, dx, dy, text_w, -1));
  candidates.push_back(line_label(at, dx, dy, text_w, +1));
}

/// Candidates along the visible part of straight guide G: the anchor first, then outwards
/// from it in tenths of the segment, kept clear of its ends.
std::vector<LineLabel> straight_guide_candidates(const GuideGeometry& g, const Rect& area,
                                                 double text_w) {
  std::vector<LineLabel> candidates;
  Point a = *g.pts[0], b = *g.pts[1];
  if (!clip_segment(a, b, area)) return candidates;
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double length = std::hypot(dx, dy);
  if (!(length > 0.0)) return candidates;
  const double half = 0.5 * text_w + 6.0;
  const auto clamp_u = [&](double u) {
    return length > 2.0 * half ? std::clamp(u, half / length, 1.0 - half / length) : 0.5;
  };
  const double u0 =
      clamp_u(((g.anchor->x - a.x) * dx + (g.anchor->y - a.y) * dy) / (length * length));
  std::vector<double> us{u0};
  for (int k = 1; k <= 9; ++k) us.push_back(clamp_u(0.1 * k));
  std::stable_sort(us.begin() + 1, us.end(),
                   [&](double p, double q) { return std::abs(p - u0) < std::abs(q - u0); });
  for (double u : us) add_both_sides(candidates, {a.x + u * dx, a.y + u * dy}, dx, dy, text_w);
  return candidates;
}

/// Candidates along the sampled curve of guide G: the sample inside AREA nearest the anchor
/// first, then every 10th sample.
std::vector<LineLabel> curved_guide_candidates(const GuideGeometry& g, const Rect& area,
                                               double text_w) {
  std::vector<std::size_t> order;
  std::size_t nearest = 0;
  double nearest_distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i + 1 < g.pts.size(); ++i) {
    if (!g.pts[i - 1] || !g.pts[i] || !g.pts[i + 1] || !area.contains(*g.pts[i])) continue;
    if (i % 10 == 0) order.push_back(i);
    if (g.anchor) {
      const double dist = std::hypot(g.pts[i]->x - g.anchor->x, g.pts[i]->y - g.anchor->y);
      if (dist < nearest_distance) {
        nearest_distance = dist;
        nearest = i;
      }
    }
  }
  if (nearest != 0) order.insert(order.begin(), nearest);
  std::vector<LineLabel> candidates;
  for (std::size_t i : order) {
    add_both_sides(candidates, *g.pts[i], g.pts[i + 1]->x - g.pts[i - 1]->x,
                   g.pts[i + 1]->y - g.pts[i - 1]->y, text_w);
  }
  return candidates;
}

// ----------------------------------------------------------------------------- point labels

/// A place for a point label: where its text starts, how it is anchored, and its box.
struct PointPlace {
  Point text_at;
  std::string_view anchor;
  Rect box;
};

/// Right-above, right-below, left-above, left-below, right, left, above, below the point AT,
/// close to it and then a little further away.
std::vector<PointPlace> point_label_places(Point at, std::string_view text) {
  const double w = text_width(text, kSmallFont);
  const double h = kSmallFont + 2.0;
  std::vector<PointPlace> places;
  for (const double gap : {8.0, 18.0}) {
    for (const auto& [dx, dy] :
         {std::pair{1, -1}, {1, 1}, {-1, -1}, {-1, 1}, {1, 0}, {-1, 0}, {0, -1}, {0, 1}}) {
      const double left = dx > 0 ? at.x + gap : (dx < 0 ? at.x - gap - w : at.x - 0.5 * w);
      const double lift = dx == 0 ? gap : 0.6 * gap;
      const double top = dy < 0 ? at.y - lift - h : (dy > 0 ? at.y + lift : at.y - 0.5 * h);
      const double text_x = dx > 0 ? left : (dx < 0 ? left + w : at.x);
      places.push_back({{text_x, top + 0.85 * kSmallFont},
                        dx > 0 ? "start" : (dx < 0 ? "end" : "middle"),
                        {left, top, left + w, top + h}});
    }
  }
  return places;
}

// ----------------------------------------------------------------------------------- legend

/// The legend box of BOX_W × BOX_H in CORNER of AREA, 10 px from its edges.
Rect legend_box_at(LegendCorner corner, const Rect& area, double box_w, double box_h) {
  const bool right_side = corner == LegendCorner::top_right || corner == LegendCorner::bottom_right;
  const bool top_side = corner == LegendCorner::top_right || corner == LegendCorner::top_left;
  const double bx = right_side ? area.right - 10.0 - box_w : area.left + 10.0;
  const double by = top_side ? area.top + 10.0 : area.bottom - 10.0 - box_h;
  return Rect{bx, by, bx + box_w, by + box_h};
}

/// Entry K of the legend in BOX: a line sample (solid for a series with neither line nor
/// marker), the marker, the text.
void append_legend_entry(std::string& out, const Series& series, std::size_t k,
                         std::string_view text, const Rect& box) {
  const std::string_view color = palette_color(series.color);
  const double cy = box.top + kLegendPad + kLegendRow * (static_cast<double>(k) + 0.5);
  const double x0 = box.left + kLegendPad;
  const Line line =
      series.line == Line::none && series.marker == Marker::none ? Line::solid : series.line;
  if (line != Line::none) {
    out.append("<path");
    append_line_style(out, color, line, line_width_of(series));
    std::string d;
    path_point(d, 'M', x0, cy);
    path_length(d, 'h', kLegendSample);
    attr_raw(out, "d", d);
    out.append("/>\n");
  }
  std::string marker;
  marker_path(marker, series.marker, {x0 + 0.5 * kLegendSample, cy}, kMarkerRadius);
  append_marker_element(out, series.marker, color, marker);
  out.append("<text");
  attr(out, "x", x0 + kLegendSample + 6.0);
  attr(out, "y", cy + 0.35 * kSmallFont);
  attr(out, "font-size", kSmallFont);
  attr(out, "fill", kTextColor);
  out.push_back('>');
  append_text(out, text);
  out.append("</text>\n");
}

}  // namespace

Legend place_legend(const Plot& plot, const std::vector<SeriesGeometry>& geometry, const Rect& area,
                    const Obstacles& data) {
  Legend legend;
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    if (plot.series[s].name.empty()) continue;
    legend.entries.emplace_back(s,
                                plot.series[s].name + (geometry[s].has_data ? "" : " (no data)"));
  }
  if (legend.entries.empty()) return legend;
  double text_w = 0.0;
  for (const auto& e : legend.entries) text_w = std::max(text_w, text_width(e.second, kSmallFont));
  const double box_w = kLegendPad + kLegendSample + 6.0 + text_w + kLegendPad;
  const double box_h = kLegendPad + kLegendRow * static_cast<double>(legend.entries.size()) + 2.0;
  LegendCorner corner = plot.legend;
  if (corner == LegendCorner::best) {
    int fewest = std::numeric_limits<int>::max();
    for (LegendCorner c : {LegendCorner::top_right, LegendCorner::top_left,
                           LegendCorner::bottom_left, LegendCorner::bottom_right}) {
      const int hits = data.hits(legend_box_at(c, area, box_w, box_h));
      if (hits < fewest) {
        fewest = hits;
        corner = c;
      }
    }
  }
  legend.box = legend_box_at(corner, area, box_w, box_h);
  return legend;
}

void append_legend(std::string& out, const Plot& plot, const Legend& legend) {
  if (!legend.box) return;
  const Rect& box = *legend.box;
  out.append("<g>\n<rect");
  attr(out, "x", box.left);
  attr(out, "y", box.top);
  attr(out, "width", box.right - box.left);
  attr(out, "height", box.bottom - box.top);
  out.append(
      " rx=\"3\" fill=\"#ffffff\" fill-opacity=\"0.85\" stroke=\"#bbbbbb\" "
      "stroke-width=\"1\"/>\n");
  for (std::size_t k = 0; k < legend.entries.size(); ++k) {
    const auto& [s, text] = legend.entries[k];
    append_legend_entry(out, plot.series[s], k, text, box);
  }
  out.append("</g>\n");
}

void add_point_boxes(const Plot& plot, const Canvas& c, Obstacles& data) {
  for (const PointLabel& p : plot.points) {
    if (c.x.inside(p.x) && c.y.inside(p.y)) {
      data.boxes.push_back(box_around({c.x.px(p.x), c.y.px(p.y)}, kPointRadius));
    }
  }
}

int LabelSpace::cost(const Rect& text_box, const GuideGeometry* own) const {
  const Rect box{text_box.left - 2.0, text_box.top - 1.0, text_box.right + 2.0,
                 text_box.bottom + 1.0};  // a little air around the text
  int n = taken.hits(box) + (inside(text_box, area) ? 0 : 100000);
  for (const GuideGeometry& g : *guides) {
    if (&g != own) n += g.segments.hits(box);
  }
  return n;
}

void append_guide_labels(std::string& out, const Canvas& c, LabelSpace& space) {
  for (const GuideGeometry& g : *space.guides) {
    if (g.guide->label.empty()) continue;
    const double text_w = text_width(g.guide->label, kSmallFont);
    const std::vector<LineLabel> candidates = log_log(c)
                                                  ? straight_guide_candidates(g, c.area, text_w)
                                                  : curved_guide_candidates(g, c.area, text_w);
    if (candidates.empty()) continue;
    const LineLabel& best =
        cheapest(candidates, [&](const LineLabel& l) { return space.cost(l.box, &g); });
    append_line_label(out, best, g.guide->label);
    space.taken.boxes.push_back(best.box);
  }
}

void append_point_labels(std::string& out, const Plot& plot, const Canvas& c, LabelSpace& space) {
  for (const PointLabel& p : plot.points) {
    if (!c.x.inside(p.x) || !c.y.inside(p.y)) continue;
    const Point at{c.x.px(p.x), c.y.px(p.y)};
    out.append("<circle");
    attr(out, "cx", at.x);
    attr(out, "cy", at.y);
    attr(out, "r", kPointRadius);
    attr(out, "fill", palette_color(p.color));
    out.append(" stroke=\"#ffffff\" stroke-width=\"1.2\"/>\n");
    if (p.text.empty()) continue;
    const std::vector<PointPlace> places = point_label_places(at, p.text);
    const PointPlace& best =
        cheapest(places, [&](const PointPlace& place) { return space.cost(place.box, nullptr); });
    space.taken.boxes.push_back(best.box);
    out.append("<text");
    attr(out, "x", best.text_at.x);
    attr(out, "y", best.text_at.y);
    append_label_style(out, best.anchor, kTextColor);
    append_text(out, p.text);
    out.append("</text>\n");
  }
}

}  // namespace imunoise::report::svg_detail
