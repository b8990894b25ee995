#include "report/svg_axes.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <utility>

#include "common/errors.h"
#include "common/number_text.h"
#include "report/svg_style.h"
#include "report/svg_text.h"

namespace imunoise::report::svg_detail {
namespace {

// -------------------------------------------------------------------------------- ranges

/// Tick text for a plain number (log axes spanning less than two decades).
std::string plain_number_text(double v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::general, 4);
  return std::string(buffer, r.ptr);
}

void check_limits(const Axis& axis, const std::string& which) {
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
}

/// The range (lo, hi) and ticks of AXIS over DATA before the ticks are cut to the range.
ResolvedAxis range_and_ticks(const Axis& axis, const Extent& data) {
  const bool log = axis.scale == Scale::log10;
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
  return out;
}

/// x of everything drawable: series points with a plottable y (or error-bar top), points.
Extent x_extent(const Plot& plot) {
  const Scale xs = plot.x.scale, ys = plot.y.scale;
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
  return x_data;
}

/// y of what lies inside X_RANGE: series points, error-bar ends, points.
Extent y_extent(const Plot& plot, const AxisMap& x_range) {
  const Scale ys = plot.y.scale;
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
  return y_data;
}

// ------------------------------------------------------------------------------ tick labels

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

/// The plot area: the SVG of WIDTH × HEIGHT less margins for the title, the tick labels of
/// RX and RY and the axis labels.
Rect plot_area(const Plot& plot, const ResolvedAxis& rx, const ResolvedAxis& ry, double width,
               double height) {
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
  return Rect{left, top, std::max(left + 40.0, width - right_margin),
              std::max(top + 40.0, height - bottom_margin)};
}

}  // namespace

bool plottable(Scale scale, double v) {
  return std::isfinite(v) && (scale == Scale::linear || v > 0.0);
}

double transformed(Scale scale, double v) { return scale == Scale::log10 ? std::log10(v) : v; }

double AxisMap::fraction(double t) const {
  const double width = t_hi - t_lo;
  double f = std::isfinite(width) ? (t - t_lo) / width
                                  : (0.5 * t - 0.5 * t_lo) / (0.5 * t_hi - 0.5 * t_lo);
  if (std::isnan(f)) f = 0.0;
  return std::clamp(f, -1e4, 1e4);
}

bool AxisMap::inside(double v) const {
  if (!plottable(v)) return false;
  const double f = fraction(transformed(scale, v));
  return f >= -1e-9 && f <= 1.0 + 1e-9;
}

ResolvedAxis resolve_axis(const Axis& axis, const Extent& data, const std::string& which) {
  check_limits(axis, which);
  ResolvedAxis out = range_and_ticks(axis, data);
  const AxisMap map(out, 0.0, 1.0);
  const auto visible = [&](std::vector<Tick> ticks) {
    std::erase_if(ticks, [&](const Tick& t) { return !map.inside(t.value); });
    return ticks;
  };
  out.ticks = visible(std::move(out.ticks));
  // A log axis spanning less than two labelled decades: label the 2..9 ticks with plain
  // numbers, or (a range inside one decade) use linear ticks.
  if (axis.scale == Scale::log10 &&
      std::count_if(out.ticks.begin(), out.ticks.end(),
                    [](const Tick& t) { return !t.text.empty(); }) < 3) {
    if (out.ticks.size() >= 3) {
      for (auto& t : out.ticks) t.text = plain_number_text(t.value);
    } else {
      out.ticks = visible(linear_ticks(out.lo, out.hi));
    }
  }
  return out;
}

Canvas lay_out(const Plot& plot) {
  const double width = std::clamp(plot.width_px, 200, 20000);
  const double height = std::clamp(plot.height_px, 200, 20000);
  const std::string clip_id = sanitized_id(plot.id) + "-area";
  const ResolvedAxis rx = resolve_axis(plot.x, x_extent(plot), "x");
  const ResolvedAxis ry = resolve_axis(plot.y, y_extent(plot, AxisMap(rx, 0.0, 1.0)), "y");
  const Rect area = plot_area(plot, rx, ry, width, height);
  const Rect clip{area.left - 2.0, area.top - 2.0, area.right + 2.0, area.bottom + 2.0};
  return Canvas{width,
                height,
                rx,
                ry,
                area,
                clip,
                AxisMap(rx, area.left, area.right),
                AxisMap(ry, area.bottom, area.top),
                clip_id,
                "url(#" + clip_id + ")"};
}

bool log_log(const Canvas& c) { return c.x.scale == Scale::log10 && c.y.scale == Scale::log10; }

void append_grid(std::string& out, const Canvas& c) {
  std::string minor, major;
  for (const Tick& t : c.x_axis.ticks) {
    const double px = c.x.px(t.value);
    std::string& d = t.major ? major : minor;
    path_point(d, 'M', px, c.area.top);
    path_length(d, 'V', c.area.bottom);
  }
  for (const Tick& t : c.y_axis.ticks) {
    const double py = c.y.px(t.value);
    std::string& d = t.major ? major : minor;
    path_point(d, 'M', c.area.left, py);
    path_length(d, 'H', c.area.right);
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

void append_frame_and_ticks(std::string& out, const Canvas& c) {
  std::string d;
  for (const Tick& t : c.x_axis.ticks) {
    path_point(d, 'M', c.x.px(t.value), c.area.bottom);
    path_length(d, 'v', t.major ? kMajorTick : kMinorTick);
  }
  for (const Tick& t : c.y_axis.ticks) {
    path_point(d, 'M', c.area.left, c.y.px(t.value));
    path_length(d, 'h', -(t.major ? kMajorTick : kMinorTick));
  }
  out.append("<g fill=\"none\" shape-rendering=\"crispEdges\"");
  attr(out, "stroke", kFrameColor);
  out.append(">\n<rect");
  attr(out, "x", c.area.left);
  attr(out, "y", c.area.top);
  attr(out, "width", c.area.right - c.area.left);
  attr(out, "height", c.area.bottom - c.area.top);
  out.append("/>\n");
  if (!d.empty()) {
    out.append("<path");
    attr_raw(out, "d", d);
    out.append("/>\n");
  }
  out.append("</g>\n");
}

void append_tick_labels(std::string& out, const Canvas& c) {
  const std::vector<Tick>& x_ticks = c.x_axis.ticks;
  const std::vector<Tick>& y_ticks = c.y_axis.ticks;
  out.append("<g");
  attr(out, "fill", kTextColor);
  out.append(">\n");
  const bool x_powers = std::any_of(x_ticks.begin(), x_ticks.end(), is_power_label);
  for (std::size_t i : visible_labels(x_ticks, c.x, true)) {
    out.append("<text");
    attr(out, "x", c.x.px(x_ticks[i].value));
    attr(out, "y", c.area.bottom + kMajorTick + 4.0 + kTickFont + (x_powers ? 2.0 : 0.0));
    out.append(" text-anchor=\"middle\">");
    append_tick_text(out, x_ticks[i]);
    out.append("</text>\n");
  }
  for (std::size_t i : visible_labels(y_ticks, c.y, false)) {
    out.append("<text");
    attr(out, "x", c.area.left - kMajorTick - 4.0);
    attr(out, "y", c.y.px(y_ticks[i].value) + 0.35 * kTickFont);
    out.append(" text-anchor=\"end\">");
    append_tick_text(out, y_ticks[i]);
    out.append("</text>\n");
  }
  out.append("</g>\n");
}

void append_axis_labels(std::string& out, const Plot& plot, const Canvas& c) {
  if (!plot.x.label.empty()) {
    out.append("<text");
    attr(out, "x", 0.5 * (c.area.left + c.area.right));
    attr(out, "y", c.height - 12.0);
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
    append_number(out, 0.5 * (c.area.top + c.area.bottom));
    out.append(") rotate(-90)\" x=\"0\" y=\"0\"");
    attr(out, "font-size", kLabelFont);
    attr(out, "fill", kTextColor);
    out.append(" text-anchor=\"middle\">");
    append_text(out, plot.y.label);
    out.append("</text>\n");
  }
}

}  // namespace imunoise::report::svg_detail
