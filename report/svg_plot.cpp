#include "report/svg_plot.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "common/errors.h"
#include "common/number_text.h"
#include "report/markup_text.h"

namespace imunoise::report {
namespace {

// ------------------------------------------------------------------------------------ style
constexpr std::string_view kFontFamily = "DejaVu Sans, Helvetica, Arial, sans-serif";
constexpr double kTickFont = 12.0;
constexpr double kExponentFont = 10.0;
constexpr double kLabelFont = 14.0;
constexpr double kTitleFont = 16.0;
constexpr double kSmallFont = 12.0;  // legend, guide and point labels
constexpr double kCharWidth = 0.6;   // mean advance of the sans-serif fonts, in em
constexpr std::string_view kTextColor = "#222222";
constexpr std::string_view kFrameColor = "#444444";
constexpr std::string_view kMajorGridColor = "#d2d2d2";
constexpr std::string_view kMinorGridColor = "#ececec";
constexpr std::string_view kGuideColor = "#8c8c8c";
constexpr std::string_view kGuideTextColor = "#555555";
constexpr double kMajorTick = 5.0, kMinorTick = 3.0;  // px, outwards
constexpr double kMarkerRadius = 3.5;
constexpr double kPointRadius = 4.5;   // labelled points
constexpr double kCapHalfWidth = 3.0;  // error-bar caps
constexpr double kLegendRow = 18.0, kLegendSample = 30.0, kLegendPad = 8.0;

constexpr std::array<std::string_view, 8> kPalette = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                      "#E69F00", "#56B4E9", "#000000", "#F0E442"};

// ------------------------------------------------------------------------------ text output

/// Pixel coordinate: at most 2 decimals, trailing zeros dropped, never "-0", "nan" or "inf".
void append_number(std::string& out, double v) {
  if (!std::isfinite(v)) v = 0.0;
  v = std::clamp(v, -1e9, 1e9);
  char buffer[32];
  char* end = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::fixed, 2).ptr;
  while (end[-1] == '0') --end;  // there is always a '.' with precision 2
  if (end[-1] == '.') --end;
  const std::string_view text(buffer, static_cast<std::size_t>(end - buffer));
  out.append(text == "-0" ? "0" : text);
}

void append_text(std::string& out, std::string_view text) { append_markup_text(out, text); }

/// Number of characters (UTF-8 code points) of TEXT.
std::size_t char_count(std::string_view text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0u) != 0x80u;
  }));
}

double text_width(std::string_view text, double font_size) {
  return static_cast<double>(char_count(text)) * kCharWidth * font_size;
}

/// Appends ` NAME="V"`.
void attr(std::string& out, std::string_view name, double v) {
  out.push_back(' ');
  out.append(name);
  out.append("=\"");
  append_number(out, v);
  out.push_back('"');
}
void attr(std::string& out, std::string_view name, std::string_view v) {
  out.push_back(' ');
  out.append(name);
  out.append("=\"");
  append_text(out, v);
  out.push_back('"');
}

/// Appends ` NAME="V"` for V made by this file (path data, numbers): nothing to escape.
void attr_raw(std::string& out, std::string_view name, std::string_view v) {
  out.push_back(' ');
  out.append(name);
  out.append("=\"");
  out.append(v);
  out.push_back('"');
}

/// Path data " M X Y" / " X Y" (implicit line-to after a move) / " h W" etc.
void path_point(std::string& d, char command, double x, double y) {
  if (!d.empty()) d.push_back(' ');
  if (command != 0) d.push_back(command);
  append_number(d, x);
  d.push_back(' ');
  append_number(d, y);
}
void path_length(std::string& d, char command, double v) {
  d.push_back(' ');
  d.push_back(command);
  append_number(d, v);
}

std::string sanitized_id(std::string_view id) {
  std::string out;
  for (char c : id) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    out.push_back(ok ? c : '_');
  }
  if (out.empty() ||
      !((out[0] >= 'a' && out[0] <= 'z') || (out[0] >= 'A' && out[0] <= 'Z') || out[0] == '_')) {
    out.insert(out.begin(), 'p');
  }
  return out;
}

// ------------------------------------------------------------------------------------- axes

struct Extent {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return !(lo <= hi); }
};

struct ResolvedAxis {
  Scale scale = Scale::linear;
  double lo = 0.0, hi = 1.0;
  std::vector<Tick> ticks;  // inside [lo, hi]
};

bool plottable(Scale scale, double v) {
  return std::isfinite(v) && (scale == Scale::linear || v > 0.0);
}

double transformed(Scale scale, double v) { return scale == Scale::log10 ? std::log10(v) : v; }

/// Data → pixel along one axis.
struct AxisMap {
  Scale scale = Scale::linear;
  double t_lo = 0.0, t_hi = 1.0;    // range in transformed units (log10 or identity)
  double px_lo = 0.0, px_hi = 1.0;  // pixels of lo and hi

  AxisMap(const ResolvedAxis& axis, double pixel_lo, double pixel_hi)
      : scale(axis.scale),
        t_lo(transformed(axis.scale, axis.lo)),
        t_hi(transformed(axis.scale, axis.hi)),
        px_lo(pixel_lo),
        px_hi(pixel_hi) {}

  bool plottable(double v) const { return report::plottable(scale, v); }
  /// Fraction of the range at transformed value T (clamped far outside, never NaN).
  double fraction(double t) const {
    const double width = t_hi - t_lo;
    double f = std::isfinite(width) ? (t - t_lo) / width
                                    : (0.5 * t - 0.5 * t_lo) / (0.5 * t_hi - 0.5 * t_lo);
    if (std::isnan(f)) f = 0.0;
    return std::clamp(f, -1e4, 1e4);
  }
  double px_of_t(double t) const { return px_lo + fraction(t) * (px_hi - px_lo); }
  double px(double v) const { return px_of_t(transformed(scale, v)); }
  /// V plottable and inside the axis range (with a relative tolerance of 1e-9).
  bool inside(double v) const {
    if (!plottable(v)) return false;
    const double f = fraction(transformed(scale, v));
    return f >= -1e-9 && f <= 1.0 + 1e-9;
  }
};

/// Tick text for a plain number (log axes spanning less than two decades).
std::string plain_number_text(double v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::general, 4);
  return std::string(buffer, r.ptr);
}

ResolvedAxis resolve_axis(const Axis& axis, const Extent& data, const std::string& which) {
  const bool log = axis.scale == Scale::log10;
  for (const auto& [limit, end] : {std::pair{&axis.min, "min"}, std::pair{&axis.max, "max"}}) {
    if (!*limit) continue;
    IMUNOISE_CHECK(plottable(axis.scale, **limit), InputError,
                   "render_svg: " + which + " axis " + end + " must be finite" +
                       (log ? " and > 0" : "") + " (got " + shortest_number_text(**limit) + ")");
  }
  if (axis.min && axis.max) {
    IMUNOISE_CHECK(*axis.min < *axis.max, InputError,
                   "render_svg: " + which + " axis min must be < max (got " +
                       shortest_number_text(*axis.min) + ", " + shortest_number_text(*axis.max) +
                       ")");
  }
  ResolvedAxis out;
  out.scale = axis.scale;
  double lo = axis.min ? *axis.min : (data.empty() ? (log ? 1.0 : 0.0) : data.lo);
  double hi = axis.max ? *axis.max : (data.empty() ? (log ? 10.0 : 1.0) : data.hi);
  if (!(lo < hi) && (axis.min || axis.max)) {  // one end fixed, the data on its far side
    const double step = log ? 0.0 : (lo != 0.0 ? 0.2 * std::abs(lo) : 1.0);
    if (axis.min) {
      hi = log ? lo * 10.0 : lo + step;
    } else {
      lo = log ? hi / 10.0 : hi - step;
    }
  }
  if (log) {
    out.lo = axis.min ? *axis.min : decade_floor(lo);
    out.hi = axis.max ? *axis.max : decade_ceil(hi);
    if (!(out.lo < out.hi)) {  // a single decade value, both ends autoscaled: ± a decade
      if (out.hi < 1e308) out.hi = decade_ceil(out.hi * 10.0);
      if (out.lo > 1e-307) out.lo = decade_floor(out.lo / 10.0);
    }
    out.ticks = log10_ticks(out.lo, out.hi);
  } else {
    out.ticks = linear_ticks(lo, hi);
    if (out.ticks.empty()) {
      out.lo = axis.min ? *axis.min : lo - 1.0;
      out.hi = axis.max ? *axis.max : hi + 1.0;
    } else {
      out.lo = axis.min ? *axis.min : std::min(out.ticks.front().value, lo);
      out.hi = axis.max ? *axis.max : std::max(out.ticks.back().value, hi);
    }
  }
  const AxisMap map(out, 0.0, 1.0);
  const auto visible = [&](std::vector<Tick> ticks) {
    std::erase_if(ticks, [&](const Tick& t) { return !map.inside(t.value); });
    return ticks;
  };
  out.ticks = visible(std::move(out.ticks));
  // A log axis spanning less than two labelled decades: label the 2..9 ticks with plain
  // numbers, or (a range inside one decade) use linear ticks.
  if (log && std::count_if(out.ticks.begin(), out.ticks.end(),
                           [](const Tick& t) { return !t.text.empty(); }) < 3) {
    if (out.ticks.size() >= 3) {
      for (auto& t : out.ticks) t.text = plain_number_text(t.value);
    } else {
      out.ticks = visible(linear_ticks(out.lo, out.hi));
    }
  }
  return out;
}

bool is_power_label(const Tick& t) { return t.text.rfind("10^", 0) == 0; }

double tick_label_width(const Tick& t) {
  if (is_power_label(t)) {
    return 2.0 * kCharWidth * kTickFont +
           static_cast<double>(t.text.size() - 3) * kCharWidth * kExponentFont;
  }
  return text_width(t.text, kTickFont);
}

/// A tick label: "10^k" as 10 with a superscript k; a leading '-' as a real minus sign.
void append_tick_text(std::string& out, const Tick& t) {
  const auto minus = [&](std::string_view s) {
    if (!s.empty() && s[0] == '-') {
      out.append("&#8722;");
      s.remove_prefix(1);
    }
    append_text(out, s);
  };
  if (is_power_label(t)) {
    out.append("10<tspan dy=\"-6\" font-size=\"10\">");
    minus(std::string_view(t.text).substr(3));
    out.append("</tspan>");
  } else {
    minus(t.text);
  }
}

/// Indices of the labelled ticks to write: every STRIDE-th (keeping a label at 0 where there
/// is one), the smallest stride whose labels do not overlap along the axis.
std::vector<std::size_t> visible_labels(const std::vector<Tick>& ticks, const AxisMap& map,
                                        bool horizontal) {
  std::vector<std::size_t> labelled;
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    if (!ticks[i].text.empty()) labelled.push_back(i);
  }
  std::size_t zero = 0;
  for (std::size_t k = 0; k < labelled.size(); ++k) {
    if (ticks[labelled[k]].value == 0.0) zero = k;
  }
  for (std::size_t stride = 1; stride <= labelled.size(); ++stride) {
    std::vector<std::size_t> chosen;
    for (std::size_t k = zero % stride; k < labelled.size(); k += stride) {
      chosen.push_back(labelled[k]);
    }
    bool overlap = false;
    for (std::size_t k = 1; k < chosen.size() && !overlap; ++k) {
      const Tick& a = ticks[chosen[k - 1]];
      const Tick& b = ticks[chosen[k]];
      const double gap = std::abs(map.px(b.value) - map.px(a.value));
      const double needed =
          horizontal ? 0.5 * (tick_label_width(a) + tick_label_width(b)) + 8.0 : kTickFont + 4.0;
      overlap = gap < needed;
    }
    if (!overlap) return chosen;
  }
  return {};
}

// ---------------------------------------------------------------------------------- drawing

struct Point {
  double x, y;
};

struct Rect {
  double left, top, right, bottom;
  bool contains(Point p, double tolerance = 0.0) const {
    return p.x >= left - tolerance && p.x <= right + tolerance && p.y >= top - tolerance &&
           p.y <= bottom + tolerance;
  }
};

/// Liang–Barsky: clips segment A–B to R in place; false when nothing is left.
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

/// Polyline through POINTS (std::nullopt = a gap) clipped to CLIP, as path data with one
/// subpath per visible run.
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

void marker_path(std::string& d, Marker marker, Point p, double r) {
  switch (marker) {
    case Marker::none:
      return;
    case Marker::circle:
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

/// `<path …/>` of the markers in D: filled with a thin white outline, a cross stroked.
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

void append_line_style(std::string& out, std::string_view color, Line line, double width) {
  attr(out, "fill", "none");
  attr(out, "stroke", color);
  attr(out, "stroke-width", width);
  attr(out, "stroke-linejoin", "round");
  if (const auto dashes = dash_array(line, width); !dashes.empty()) {
    attr_raw(out, "stroke-dasharray", dashes);
  }
}

/// Text attributes shared by the labels drawn over the data: a white halo keeps them
/// readable over lines and the grid.
void append_label_style(std::string& out, std::string_view anchor, std::string_view color) {
  attr(out, "text-anchor", anchor);
  attr(out, "font-size", kSmallFont);
  attr(out, "fill", color);
  out.append(
      " stroke=\"#ffffff\" stroke-width=\"3\" stroke-linejoin=\"round\" paint-order=\"stroke\">");
}

bool overlaps(const Rect& a, const Rect& b) {
  return a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;
}

bool inside(const Rect& inner, const Rect& outer) {
  return inner.left >= outer.left && inner.right <= outer.right && inner.top >= outer.top &&
         inner.bottom <= outer.bottom;
}

/// What a label should not cover: data segments (lines, error bars) and boxes (markers,
/// legend, labels already placed).
struct Obstacles {
  std::vector<std::pair<Point, Point>> segments;
  std::vector<Rect> boxes;

  int hits(const Rect& r) const {
    int n = 0;
    for (const auto& [a0, b0] : segments) {
      Point a = a0, b = b0;
      if (clip_segment(a, b, r)) ++n;
    }
    for (const Rect& b : boxes) n += overlaps(r, b) ? 1 : 0;
    return n;
  }
  void add_polyline(const std::vector<std::optional<Point>>& points) {
    for (std::size_t i = 1; i < points.size(); ++i) {
      if (points[i - 1] && points[i]) segments.emplace_back(*points[i - 1], *points[i]);
    }
  }
};

Rect box_around(Point p, double half) { return {p.x - half, p.y - half, p.x + half, p.y + half}; }

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

void validate(const Plot& plot) {
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    const Series& series = plot.series[s];
    const std::string name = "render_svg: series " + std::to_string(s) + " '" + series.name + "': ";
    IMUNOISE_CHECK(series.x.size() == series.y.size(), InputError,
                   name + "x has " + std::to_string(series.x.size()) + " values, y has " +
                       std::to_string(series.y.size()));
    IMUNOISE_CHECK(
        (series.y_low.empty() && series.y_high.empty()) ||
            (series.y_low.size() == series.y.size() && series.y_high.size() == series.y.size()),
        InputError,
        name + "y_low and y_high must both be empty or both have " +
            std::to_string(series.y.size()) + " values (got " +
            std::to_string(series.y_low.size()) + ", " + std::to_string(series.y_high.size()) +
            ")");
  }
}

double line_width_of(const Series& s) {
  return std::isfinite(s.line_width) ? std::clamp(s.line_width, 0.25, 10.0) : 1.5;
}

}  // namespace

std::string_view palette_color(int index) {
  const int n = static_cast<int>(kPalette.size());
  return kPalette[static_cast<std::size_t>(((index % n) + n) % n)];
}

std::string render_svg(const Plot& plot) {
  validate(plot);
  const double width = std::clamp(plot.width_px, 200, 20000);
  const double height = std::clamp(plot.height_px, 200, 20000);
  const std::string id = sanitized_id(plot.id);
  const Scale xs = plot.x.scale, ys = plot.y.scale;

  // Ranges: x from everything drawable, then y from what lies inside the x range.
  Extent x_data;
  for (const Series& s : plot.series) {
    const bool bars = !s.y_low.empty();
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!plottable(xs, s.x[i])) continue;
      if (plottable(ys, s.y[i]) || (bars && plottable(ys, s.y_high[i]))) x_data.add(s.x[i]);
    }
  }
  for (const PointLabel& p : plot.points) {
    if (plottable(xs, p.x) && plottable(ys, p.y)) x_data.add(p.x);
  }
  const ResolvedAxis rx = resolve_axis(plot.x, x_data, "x");
  const AxisMap x_range(rx, 0.0, 1.0);
  Extent y_data;
  for (const Series& s : plot.series) {
    const bool bars = !s.y_low.empty();
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!x_range.inside(s.x[i])) continue;
      if (plottable(ys, s.y[i])) y_data.add(s.y[i]);
      if (bars && std::isfinite(s.y_low[i]) && plottable(ys, s.y_high[i])) {
        y_data.add(s.y_high[i]);
        if (plottable(ys, s.y_low[i])) y_data.add(s.y_low[i]);
      }
    }
  }
  for (const PointLabel& p : plot.points) {
    if (x_range.inside(p.x) && plottable(ys, p.y)) y_data.add(p.y);
  }
  const ResolvedAxis ry = resolve_axis(plot.y, y_data, "y");

  // Layout: margins from the label sizes.
  double y_label_width = 0.0;
  for (const Tick& t : ry.ticks) y_label_width = std::max(y_label_width, tick_label_width(t));
  double last_x_label = 0.0;
  for (const Tick& t : rx.ticks) {
    if (!t.text.empty()) last_x_label = tick_label_width(t);
  }
  const double left = std::round(10.0 + (plot.y.label.empty() ? 0.0 : kLabelFont + 8.0) +
                                 y_label_width + kMajorTick + 6.0);
  const double right_margin = std::round(std::max(20.0, 0.5 * last_x_label + 8.0));
  const double top = plot.title.empty() ? 18.0 : 42.0;
  const double bottom_margin = std::round(kMajorTick + 6.0 + kTickFont + 8.0 +
                                          (plot.x.label.empty() ? 0.0 : kLabelFont + 10.0));
  const Rect area{left, top, std::max(left + 40.0, width - right_margin),
                  std::max(top + 40.0, height - bottom_margin)};
  const AxisMap mx(rx, area.left, area.right);
  const AxisMap my(ry, area.bottom, area.top);
  // Lines are clipped here (plus a clipPath at the exact area), so no coordinate is huge.
  const Rect clip{area.left - 2.0, area.top - 2.0, area.right + 2.0, area.bottom + 2.0};
  const std::string clip_ref = "url(#" + id + "-area)";

  std::size_t total_points = 0;
  for (const Series& s : plot.series) total_points += s.x.size();
  std::string out;
  out.reserve(8192 + 48 * total_points);

  out.append("<svg xmlns=\"http://www.w3.org/2000/svg\"");
  attr(out, "width", width);
  attr(out, "height", height);
  out.append(" viewBox=\"0 0 ");
  append_number(out, width);
  out.push_back(' ');
  append_number(out, height);
  out.push_back('"');
  attr(out, "font-family", kFontFamily);
  attr(out, "font-size", kTickFont);
  out.append(">\n");
  if (!plot.title.empty()) {
    out.append("<title>");
    append_text(out, plot.title);
    out.append("</title>\n");
  }
  out.append("<defs><clipPath");
  attr(out, "id", id + "-area");
  out.append("><rect");
  attr(out, "x", area.left);
  attr(out, "y", area.top);
  attr(out, "width", area.right - area.left);
  attr(out, "height", area.bottom - area.top);
  out.append("/></clipPath></defs>\n");
  out.append("<rect");
  attr(out, "width", width);
  attr(out, "height", height);
  out.append(" fill=\"#ffffff\"/>\n");

  // Grid: minor (lighter) below major.
  {
    std::string minor, major;
    for (const Tick& t : rx.ticks) {
      const double px = mx.px(t.value);
      std::string& d = t.major ? major : minor;
      path_point(d, 'M', px, area.top);
      path_length(d, 'V', area.bottom);
    }
    for (const Tick& t : ry.ticks) {
      const double py = my.px(t.value);
      std::string& d = t.major ? major : minor;
      path_point(d, 'M', area.left, py);
      path_length(d, 'H', area.right);
    }
    out.append("<g fill=\"none\" stroke-width=\"1\" shape-rendering=\"crispEdges\">\n");
    for (const auto& [d, color] :
         {std::pair{&minor, kMinorGridColor}, std::pair{&major, kMajorGridColor}}) {
      if (d->empty()) continue;
      out.append("<path");
      attr(out, "stroke", color);
      attr_raw(out, "d", *d);
      out.append("/>\n");
    }
    out.append("</g>\n");
  }

  // Series geometry in pixels: drawn below, and what the labels and the legend avoid.
  struct SeriesGeometry {
    std::vector<std::optional<Point>> pts;
    std::string bars, markers, line;
    bool has_data = false;
  };
  Obstacles data;
  std::vector<SeriesGeometry> geometry(plot.series.size());
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    const Series& series = plot.series[s];
    SeriesGeometry& g = geometry[s];
    g.pts.resize(series.x.size());
    for (std::size_t i = 0; i < series.x.size(); ++i) {
      const bool x_ok = mx.plottable(series.x[i]);
      if (x_ok && my.plottable(series.y[i])) {
        g.has_data = true;
        const Point p{mx.px(series.x[i]), my.px(series.y[i])};
        g.pts[i] = p;
        if (series.marker != Marker::none && area.contains(p, 0.5)) {
          marker_path(g.markers, series.marker, p, kMarkerRadius);
          data.boxes.push_back(box_around(p, kMarkerRadius));
        }
      }
      if (series.y_low.empty() || !x_ok || !mx.inside(series.x[i])) continue;
      // Error bar: a low end ≤ 0 on a log axis is drawn from the axis bottom, without a cap.
      const double low = series.y_low[i], high = series.y_high[i];
      if (!std::isfinite(low) || !my.plottable(high)) continue;
      const bool low_cut = !my.plottable(low);
      double p_low = low_cut ? area.bottom : my.px(low);
      double p_high = my.px(high);
      if (p_low < p_high) std::swap(p_low, p_high);  // p_low: the larger pixel (lower)
      if (p_high > area.bottom || p_low < area.top) continue;
      const bool cap_low = !low_cut && p_low <= area.bottom;
      const bool cap_high = p_high >= area.top;
      p_low = std::min(p_low, area.bottom);
      p_high = std::max(p_high, area.top);
      const double px = mx.px(series.x[i]);
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
    if (series.line != Line::none) {
      g.line = polyline_path(g.pts, clip);
      data.add_polyline(g.pts);
    }
  }
  for (const PointLabel& p : plot.points) {
    if (mx.inside(p.x) && my.inside(p.y)) {
      data.boxes.push_back(box_around({mx.px(p.x), my.px(p.y)}, kPointRadius));
    }
  }

  // Legend box: the corner asked for, or (best) the first corner covering the least data.
  std::vector<std::pair<std::size_t, std::string>> entries;
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    if (plot.series[s].name.empty()) continue;
    entries.emplace_back(s, plot.series[s].name + (geometry[s].has_data ? "" : " (no data)"));
  }
  std::optional<Rect> legend_box;
  if (!entries.empty()) {
    double text_w = 0.0;
    for (const auto& e : entries) text_w = std::max(text_w, text_width(e.second, kSmallFont));
    const double box_w = kLegendPad + kLegendSample + 6.0 + text_w + kLegendPad;
    const double box_h = kLegendPad + kLegendRow * static_cast<double>(entries.size()) + 2.0;
    const auto box_at = [&](LegendCorner corner) {
      const bool right_side =
          corner == LegendCorner::top_right || corner == LegendCorner::bottom_right;
      const bool top_side = corner == LegendCorner::top_right || corner == LegendCorner::top_left;
      const double bx = right_side ? area.right - 10.0 - box_w : area.left + 10.0;
      const double by = top_side ? area.top + 10.0 : area.bottom - 10.0 - box_h;
      return Rect{bx, by, bx + box_w, by + box_h};
    };
    LegendCorner corner = plot.legend;
    if (corner == LegendCorner::best) {
      int fewest = std::numeric_limits<int>::max();
      for (LegendCorner c : {LegendCorner::top_right, LegendCorner::top_left,
                             LegendCorner::bottom_left, LegendCorner::bottom_right}) {
        const int hits = data.hits(box_at(c));
        if (hits < fewest) {
          fewest = hits;
          corner = c;
        }
      }
    }
    legend_box = box_at(corner);
  }
  Obstacles taken = data;  // + the legend and every label placed
  if (legend_box) taken.boxes.push_back(*legend_box);

  // Slope guides: y = y0·(x/x0)^slope, computed in log10 y; straight on log-log axes.
  struct GuideGeometry {
    const SlopeGuide* guide;
    std::vector<std::optional<Point>> pts;
    std::string d;
    std::optional<Point> anchor;
    Obstacles segments;
  };
  std::vector<GuideGeometry> guides;
  const bool straight = xs == Scale::log10 && ys == Scale::log10;
  for (const SlopeGuide& g : plot.guides) {
    if (!(g.x > 0.0) || !(g.y > 0.0) || !std::isfinite(g.x) || !std::isfinite(g.y) ||
        !std::isfinite(g.slope)) {
      continue;
    }
    const double lx0 = std::log10(g.x), ly0 = std::log10(g.y);
    const auto px_of = [&](double x) -> std::optional<Point> {
      if (!(x > 0.0)) return std::nullopt;
      const double ly = ly0 + g.slope * (std::log10(x) - lx0);
      if (ys == Scale::log10) return Point{mx.px(x), my.px_of_t(ly)};
      const double y = std::pow(10.0, ly);
      if (!std::isfinite(y)) return std::nullopt;
      return Point{mx.px(x), my.px(y)};
    };
    GuideGeometry geo{&g, {}, {}, px_of(g.x), {}};
    const int samples = straight ? 2 : 201;
    for (int i = 0; i < samples; ++i) {
      const double f = static_cast<double>(i) / (samples - 1);
      const double t = mx.t_lo + f * (mx.t_hi - mx.t_lo);
      geo.pts.push_back(px_of(xs == Scale::log10 ? std::pow(10.0, t) : t));
    }
    geo.d = polyline_path(geo.pts, area);
    if (geo.d.empty()) continue;
    geo.segments.add_polyline(geo.pts);
    guides.push_back(std::move(geo));
  }
  for (const GuideGeometry& g : guides) {
    out.append("<path");
    attr(out, "fill", "none");
    attr(out, "stroke", kGuideColor);
    attr(out, "stroke-width", 1.2);
    attr(out, "stroke-dasharray", "6 4");
    attr(out, "clip-path", clip_ref);
    attr_raw(out, "d", g.d);
    out.append("/>\n");
  }

  // Series: error bars and line clipped to the area, markers at points inside it.
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    const Series& series = plot.series[s];
    const SeriesGeometry& g = geometry[s];
    if (g.bars.empty() && g.line.empty() && g.markers.empty()) continue;
    const std::string_view color = palette_color(series.color);
    out.append("<g>\n");
    if (!g.bars.empty()) {
      out.append("<path");
      attr(out, "fill", "none");
      attr(out, "stroke", color);
      attr(out, "stroke-width", 1.0);
      attr(out, "clip-path", clip_ref);
      attr_raw(out, "d", g.bars);
      out.append("/>\n");
    }
    if (!g.line.empty()) {
      out.append("<path");
      append_line_style(out, color, series.line, line_width_of(series));
      attr(out, "clip-path", clip_ref);
      attr_raw(out, "d", g.line);
      out.append("/>\n");
    }
    append_marker_element(out, series.marker, color, g.markers);
    out.append("</g>\n");
  }

  // Frame and ticks.
  {
    std::string d;
    for (const Tick& t : rx.ticks) {
      path_point(d, 'M', mx.px(t.value), area.bottom);
      path_length(d, 'v', t.major ? kMajorTick : kMinorTick);
    }
    for (const Tick& t : ry.ticks) {
      path_point(d, 'M', area.left, my.px(t.value));
      path_length(d, 'h', -(t.major ? kMajorTick : kMinorTick));
    }
    out.append("<g fill=\"none\" shape-rendering=\"crispEdges\"");
    attr(out, "stroke", kFrameColor);
    out.append(">\n<rect");
    attr(out, "x", area.left);
    attr(out, "y", area.top);
    attr(out, "width", area.right - area.left);
    attr(out, "height", area.bottom - area.top);
    out.append("/>\n");
    if (!d.empty()) {
      out.append("<path");
      attr_raw(out, "d", d);
      out.append("/>\n");
    }
    out.append("</g>\n");
  }

  // Labels over the data, each at the candidate place covering the fewest data, guides,
  // legend and earlier labels (first candidate on ties; places leaving the area come last).
  const auto cost = [&](const Rect& text_box, const GuideGeometry* own) {
    const Rect box{text_box.left - 2.0, text_box.top - 1.0, text_box.right + 2.0,
                   text_box.bottom + 1.0};  // a little air around the text
    int n = taken.hits(box) + (inside(text_box, area) ? 0 : 100000);
    for (const GuideGeometry& g : guides) {
      if (&g != own) n += g.segments.hits(box);
    }
    return n;
  };
  for (const GuideGeometry& g : guides) {
    if (g.guide->label.empty()) continue;
    const double text_w = text_width(g.guide->label, kSmallFont);
    std::vector<LineLabel> candidates;
    const auto add_both_sides = [&](Point at, double dx, double dy) {
      candidates.push_back(line_label(at, dx, dy, text_w, -1));
      candidates.push_back(line_label(at, dx, dy, text_w, +1));
    };
    if (straight) {  // along the visible segment: the anchor first, then outwards from it
      Point a = *g.pts[0], b = *g.pts[1];
      if (!clip_segment(a, b, area)) continue;
      const double dx = b.x - a.x, dy = b.y - a.y;
      const double length = std::hypot(dx, dy);
      if (!(length > 0.0)) continue;
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
      for (double u : us) add_both_sides({a.x + u * dx, a.y + u * dy}, dx, dy);
    } else {  // sampled curve: near the anchor first, then every 10th sample
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
      for (std::size_t i : order) {
        add_both_sides(*g.pts[i], g.pts[i + 1]->x - g.pts[i - 1]->x,
                       g.pts[i + 1]->y - g.pts[i - 1]->y);
      }
    }
    if (candidates.empty()) continue;
    const LineLabel* best = &candidates.front();
    int best_cost = cost(best->box, &g);
    for (const LineLabel& c : candidates) {
      const int n = cost(c.box, &g);
      if (n < best_cost) {
        best_cost = n;
        best = &c;
      }
    }
    append_line_label(out, *best, g.guide->label);
    taken.boxes.push_back(best->box);
  }
  for (const PointLabel& p : plot.points) {
    if (!mx.inside(p.x) || !my.inside(p.y)) continue;
    const Point at{mx.px(p.x), my.px(p.y)};
    out.append("<circle");
    attr(out, "cx", at.x);
    attr(out, "cy", at.y);
    attr(out, "r", kPointRadius);
    attr(out, "fill", palette_color(p.color));
    out.append(" stroke=\"#ffffff\" stroke-width=\"1.2\"/>\n");
    if (p.text.empty()) continue;
    // Candidates: right-above, right-below, left-above, left-below, right, left, above, below
    // the point, close to it and then a little further away.
    const double w = text_width(p.text, kSmallFont);
    const double h = kSmallFont + 2.0;
    struct Place {
      Point text_at;
      std::string_view anchor;
      Rect box;
    };
    std::vector<Place> places;
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
    const Place* best = &places.front();
    int best_cost = cost(best->box, nullptr);
    for (const Place& c : places) {
      const int n = cost(c.box, nullptr);
      if (n < best_cost) {
        best_cost = n;
        best = &c;
      }
    }
    taken.boxes.push_back(best->box);
    out.append("<text");
    attr(out, "x", best->text_at.x);
    attr(out, "y", best->text_at.y);
    append_label_style(out, best->anchor, kTextColor);
    append_text(out, p.text);
    out.append("</text>\n");
  }

  // Tick labels.
  out.append("<g");
  attr(out, "fill", kTextColor);
  out.append(">\n");
  const bool x_powers = std::any_of(rx.ticks.begin(), rx.ticks.end(), is_power_label);
  for (std::size_t i : visible_labels(rx.ticks, mx, true)) {
    out.append("<text");
    attr(out, "x", mx.px(rx.ticks[i].value));
    attr(out, "y", area.bottom + kMajorTick + 4.0 + kTickFont + (x_powers ? 2.0 : 0.0));
    out.append(" text-anchor=\"middle\">");
    append_tick_text(out, rx.ticks[i]);
    out.append("</text>\n");
  }
  for (std::size_t i : visible_labels(ry.ticks, my, false)) {
    out.append("<text");
    attr(out, "x", area.left - kMajorTick - 4.0);
    attr(out, "y", my.px(ry.ticks[i].value) + 0.35 * kTickFont);
    out.append(" text-anchor=\"end\">");
    append_tick_text(out, ry.ticks[i]);
    out.append("</text>\n");
  }
  out.append("</g>\n");

  // Axis labels and title.
  if (!plot.x.label.empty()) {
    out.append("<text");
    attr(out, "x", 0.5 * (area.left + area.right));
    attr(out, "y", height - 12.0);
    attr(out, "font-size", kLabelFont);
    attr(out, "fill", kTextColor);
    out.append(" text-anchor=\"middle\">");
    append_text(out, plot.x.label);
    out.append("</text>\n");
  }
  if (!plot.y.label.empty()) {
    out.append("<text transform=\"translate(");
    append_number(out, 10.0 + kLabelFont);
    out.push_back(' ');
    append_number(out, 0.5 * (area.top + area.bottom));
    out.append(") rotate(-90)\" x=\"0\" y=\"0\"");
    attr(out, "font-size", kLabelFont);
    attr(out, "fill", kTextColor);
    out.append(" text-anchor=\"middle\">");
    append_text(out, plot.y.label);
    out.append("</text>\n");
  }
  if (!plot.title.empty()) {
    out.append("<text");
    attr(out, "x", 0.5 * (area.left + area.right));
    attr(out, "y", 26.0);
    attr(out, "font-size", kTitleFont);
    attr(out, "font-weight", "bold");
    attr(out, "fill", kTextColor);
    out.append(" text-anchor=\"middle\">");
    append_text(out, plot.title);
    out.append("</text>\n");
  }

  // Legend: named series, "(no data)" when nothing of them could be plotted.
  if (legend_box) {
    const Rect& box = *legend_box;
    out.append("<g>\n<rect");
    attr(out, "x", box.left);
    attr(out, "y", box.top);
    attr(out, "width", box.right - box.left);
    attr(out, "height", box.bottom - box.top);
    out.append(
        " rx=\"3\" fill=\"#ffffff\" fill-opacity=\"0.85\" stroke=\"#bbbbbb\" "
        "stroke-width=\"1\"/>\n");
    for (std::size_t k = 0; k < entries.size(); ++k) {
      const Series& series = plot.series[entries[k].first];
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
      append_text(out, entries[k].second);
      out.append("</text>\n");
    }
    out.append("</g>\n");
  }
  out.append("</svg>\n");
  return out;
}

}  // namespace imunoise::report
