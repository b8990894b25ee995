#include "report/svg_series.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "report/svg_style.h"
#include "report/svg_text.h"

namespace imunoise::report::svg_detail {
namespace {

/// stroke-dasharray of a line style scaled to WIDTH ("" = solid).
std::string dash_array(Line line, double width) {
  std::string out;
  const auto pair = [&](double on, double off) {
    append_number(out, on);
    out.push_back(' ');
    append_number(out, off);
  };
  if (line == Line::dashed) pair(4.0 * width, 2.5 * width);
  if (line == Line::dotted) pair(width, 1.5 * width);
  return out;
}

void append_circle_path(std::string& d, Point p, double r) {
  path_point(d, 'M', p.x - r, p.y);
  d.append(" a");
  append_number(d, r);
  d.push_back(' ');
  append_number(d, r);
  d.append(" 0 1 0 ");
  append_number(d, 2.0 * r);
  d.append(" 0 a");
  append_number(d, r);
  d.push_back(' ');
  append_number(d, r);
  d.append(" 0 1 0 ");
  append_number(d, -2.0 * r);
  d.append(" 0Z");
}

/// The error bar of point I of SERIES into G.bars and DATA: a low end ≤ 0 on a log axis is
/// drawn from the axis bottom, without a cap; ends outside the area are cut, without a cap.
void add_error_bar(const Series& series, std::size_t i, const Canvas& c, SeriesGeometry& g,
                   Obstacles& data) {
  const Rect& area = c.area;
  const double low = series.y_low[i], high = series.y_high[i];
  if (!std::isfinite(low) || !c.y.plottable(high)) return;
  const bool low_cut = !c.y.plottable(low);
  double p_low = low_cut ? area.bottom : c.y.px(low);
  double p_high = c.y.px(high);
  if (p_low < p_high) std::swap(p_low, p_high);  // p_low: the larger pixel (lower)
  if (p_high > area.bottom || p_low < area.top) return;
  const bool cap_low = !low_cut && p_low <= area.bottom;
  const bool cap_high = p_high >= area.top;
  p_low = std::min(p_low, area.bottom);
  p_high = std::max(p_high, area.top);
  const double px = c.x.px(series.x[i]);
  path_point(g.bars, 'M', px, p_low);
  path_length(g.bars, 'V', p_high);
  if (cap_low) {
    path_point(g.bars, 'M', px - kCapHalfWidth, p_low);
    path_length(g.bars, 'h', 2.0 * kCapHalfWidth);
  }
  if (cap_high) {
    path_point(g.bars, 'M', px - kCapHalfWidth, p_high);
    path_length(g.bars, 'h', 2.0 * kCapHalfWidth);
  }
  data.segments.emplace_back(Point{px, p_low}, Point{px, p_high});
}

/// The band of SERIES between fill_base and y (Series::fill_base) as closed polygons, one per
/// run of points where x, y and the base are plottable; clipped by the caller's clip path.
std::string fill_path(const Series& series, const Canvas& c) {
  std::string d;
  std::vector<Point> top, base;
  const auto close_run = [&] {
    if (top.size() >= 2) {
      for (std::size_t k = 0; k < top.size(); ++k)
        path_point(d, k == 0 ? 'M' : 'L', top[k].x, top[k].y);
      for (std::size_t k = base.size(); k-- > 0;) path_point(d, 'L', base[k].x, base[k].y);
      d.append("Z");
    }
    top.clear();
    base.clear();
  };
  for (std::size_t i = 0; i < series.x.size(); ++i) {
    if (!c.x.plottable(series.x[i]) || !c.y.plottable(series.y[i]) ||
        !c.y.plottable(series.fill_base[i])) {
      close_run();
      continue;
    }
    const double px = c.x.px(series.x[i]);
    top.push_back({px, c.y.px(series.y[i])});
    base.push_back({px, c.y.px(series.fill_base[i])});
  }
  close_run();
  return d;
}

SeriesGeometry one_series_geometry(const Series& series, const Canvas& c, Obstacles& data) {
  SeriesGeometry g;
  g.pts.resize(series.x.size());
  for (std::size_t i = 0; i < series.x.size(); ++i) {
    const bool x_ok = c.x.plottable(series.x[i]);
    if (x_ok && c.y.plottable(series.y[i])) {
      g.has_data = true;
      const Point p{c.x.px(series.x[i]), c.y.px(series.y[i])};
      g.pts[i] = p;
      if (series.marker != Marker::none && c.area.contains(p, 0.5)) {
        marker_path(g.markers, series.marker, p, kMarkerRadius);
        data.boxes.push_back(box_around(p, kMarkerRadius));
      }
    }
    if (series.y_low.empty() || !x_ok || !c.x.inside(series.x[i])) continue;
    add_error_bar(series, i, c, g, data);
  }
  if (!series.fill_base.empty()) g.fill = fill_path(series, c);
  if (series.line != Line::none) {
    g.line = polyline_path(g.pts, c.clip);
    data.add_polyline(g.pts);
  }
  return g;
}

/// G sampled over the x range of C: y = y0·(x/x0)^slope, computed in log10 y; straight on
/// log-log axes. Empty `d` when the guide is not visible.
GuideGeometry one_guide_geometry(const SlopeGuide& g, const Canvas& c) {
  const Scale xs = c.x.scale, ys = c.y.scale;
  const double lx0 = std::log10(g.x), ly0 = std::log10(g.y);
  const auto px_of = [&](double x) -> std::optional<Point> {
    if (!(x > 0.0)) return std::nullopt;
    const double ly = ly0 + g.slope * (std::log10(x) - lx0);
    if (ys == Scale::log10) return Point{c.x.px(x), c.y.px_of_t(ly)};
    const double y = std::pow(10.0, ly);
    if (!std::isfinite(y)) return std::nullopt;
    return Point{c.x.px(x), c.y.px(y)};
  };
  GuideGeometry geo{&g, {}, {}, px_of(g.x), {}};
  const int samples = log_log(c) ? 2 : 201;
  for (int i = 0; i < samples; ++i) {
    const double f = static_cast<double>(i) / (samples - 1);
    const double t = c.x.t_lo + f * (c.x.t_hi - c.x.t_lo);
    geo.pts.push_back(px_of(xs == Scale::log10 ? std::pow(10.0, t) : t));
  }
  geo.d = polyline_path(geo.pts, c.area);
  return geo;
}

}  // namespace

void marker_path(std::string& d, Marker marker, Point p, double r) {
  switch (marker) {
    case Marker::none:
      return;
    case Marker::circle:
      append_circle_path(d, p, r);
      return;
    case Marker::square: {
      const double s = 0.9 * r;
      path_point(d, 'M', p.x - s, p.y - s);
      path_length(d, 'h', 2.0 * s);
      path_length(d, 'v', 2.0 * s);
      path_length(d, 'h', -2.0 * s);
      d.append("Z");
      return;
    }
    case Marker::triangle:
      path_point(d, 'M', p.x, p.y - 1.2 * r);
      path_point(d, 'L', p.x + 1.05 * r, p.y + 0.7 * r);
      path_point(d, 0, p.x - 1.05 * r, p.y + 0.7 * r);
      d.append("Z");
      return;
    case Marker::diamond:
      path_point(d, 'M', p.x, p.y - 1.3 * r);
      path_point(d, 'L', p.x + r, p.y);
      path_point(d, 0, p.x, p.y + 1.3 * r);
      path_point(d, 0, p.x - r, p.y);
      d.append("Z");
      return;
    case Marker::cross:
      path_point(d, 'M', p.x - r, p.y - r);
      path_point(d, 'L', p.x + r, p.y + r);
      path_point(d, 'M', p.x - r, p.y + r);
      path_point(d, 'L', p.x + r, p.y - r);
      return;
  }
}

void append_marker_element(std::string& out, Marker marker, std::string_view color,
                           const std::string& d) {
  if (d.empty()) return;
  out.append("<path");
  if (marker == Marker::cross) {
    attr(out, "fill", "none");
    attr(out, "stroke", color);
    attr(out, "stroke-width", 1.5);
  } else {
    attr(out, "fill", color);
    attr(out, "stroke", "#ffffff");
    attr(out, "stroke-width", 0.75);
  }
  attr_raw(out, "d", d);
  out.append("/>\n");
}

void append_line_style(std::string& out, std::string_view color, Line line, double width) {
  attr(out, "fill", "none");
  attr(out, "stroke", color);
  attr(out, "stroke-width", width);
  attr(out, "stroke-linejoin", "round");
  if (const auto dashes = dash_array(line, width); !dashes.empty()) {
    attr_raw(out, "stroke-dasharray", dashes);
  }
}

double line_width_of(const Series& s) {
  return std::isfinite(s.line_width) ? std::clamp(s.line_width, 0.25, 10.0) : 1.5;
}

std::vector<SeriesGeometry> series_geometry(const Plot& plot, const Canvas& c, Obstacles& data) {
  std::vector<SeriesGeometry> geometry;
  geometry.reserve(plot.series.size());
  for (const Series& series : plot.series) geometry.push_back(one_series_geometry(series, c, data));
  return geometry;
}

std::vector<GuideGeometry> guide_geometry(const Plot& plot, const Canvas& c) {
  std::vector<GuideGeometry> guides;
  for (const SlopeGuide& g : plot.guides) {
    if (!(g.x > 0.0) || !(g.y > 0.0) || !std::isfinite(g.x) || !std::isfinite(g.y) ||
        !std::isfinite(g.slope)) {
      continue;
    }
    GuideGeometry geo = one_guide_geometry(g, c);
    if (geo.d.empty()) continue;
    geo.segments.add_polyline(geo.pts);
    guides.push_back(std::move(geo));
  }
  return guides;
}

void append_guides(std::string& out, const std::vector<GuideGeometry>& guides, const Canvas& c) {
  for (const GuideGeometry& g : guides) {
    out.append("<path");
    attr(out, "fill", "none");
    attr(out, "stroke", kGuideColor);
    attr(out, "stroke-width", 1.2);
    attr(out, "stroke-dasharray", "6 4");
    attr(out, "clip-path", c.clip_ref);
    attr_raw(out, "d", g.d);
    out.append("/>\n");
  }
}

void append_series(std::string& out, const Plot& plot, const std::vector<SeriesGeometry>& geometry,
                   const Canvas& c) {
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    const Series& series = plot.series[s];
    const SeriesGeometry& g = geometry[s];
    if (g.bars.empty() && g.line.empty() && g.markers.empty() && g.fill.empty()) continue;
    const std::string_view color = palette_color(series.color);
    out.append("<g>\n");
    if (!g.fill.empty()) {
      out.append("<path");
      attr(out, "fill", color);
      attr(out, "fill-opacity",
           std::isfinite(series.fill_opacity) ? std::clamp(series.fill_opacity, 0.0, 1.0) : 0.6);
      attr(out, "stroke", "none");
      attr(out, "clip-path", c.clip_ref);
      attr_raw(out, "d", g.fill);
      out.append("/>\n");
    }
    if (!g.bars.empty()) {
      out.append("<path");
      attr(out, "fill", "none");
      attr(out, "stroke", color);
      attr(out, "stroke-width", 1.0);
      attr(out, "clip-path", c.clip_ref);
      attr_raw(out, "d", g.bars);
      out.append("/>\n");
    }
    if (!g.line.empty()) {
      out.append("<path");
      append_line_style(out, color, series.line, line_width_of(series));
      attr(out, "clip-path", c.clip_ref);
      attr_raw(out, "d", g.line);
      out.append("/>\n");
    }
    append_marker_element(out, series.marker, color, g.markers);
    out.append("</g>\n");
  }
}

}  // namespace imunoise::report::svg_detail
