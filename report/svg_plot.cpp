#include "report/svg_plot.h"

#include <array>
#include <string>
#include <utility>

#include "common/errors.h"
#include "report/svg_axes.h"
#include "report/svg_geometry.h"
#include "report/svg_labels.h"
#include "report/svg_series.h"
#include "report/svg_style.h"
#include "report/svg_text.h"

namespace imunoise::report {
namespace {

using namespace svg_detail;

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
    IMUNOISE_CHECK(series.fill_base.empty() || series.fill_base.size() == series.y.size(),
                   InputError,
                   name + "fill_base must be empty or have " + std::to_string(series.y.size()) +
                       " values (got " + std::to_string(series.fill_base.size()) + ")");
  }
}

/// The start of the document: the `<svg>` element, the title, the clipPath of the plot area
/// and the white background.
void append_svg_start(std::string& out, const Plot& plot, const Canvas& c) {
  out.append("<svg xmlns=\"http://www.w3.org/2000/svg\"");
  attr(out, "width", c.width);
  attr(out, "height", c.height);
  out.append(" viewBox=\"0 0 ");
  append_number(out, c.width);
  out.push_back(' ');
  append_number(out, c.height);
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
  attr(out, "id", c.clip_id);
  out.append("><rect");
  attr(out, "x", c.area.left);
  attr(out, "y", c.area.top);
  attr(out, "width", c.area.right - c.area.left);
  attr(out, "height", c.area.bottom - c.area.top);
  out.append("/></clipPath></defs>\n");
  out.append("<rect");
  attr(out, "width", c.width);
  attr(out, "height", c.height);
  out.append(" fill=\"#ffffff\"/>\n");
}

/// The title, bold, centred over the plot area (when set).
void append_title(std::string& out, const Plot& plot, const Canvas& c) {
  if (plot.title.empty()) return;
  out.append("<text");
  attr(out, "x", 0.5 * (c.area.left + c.area.right));
  attr(out, "y", 26.0);
  attr(out, "font-size", kTitleFont);
  attr(out, "font-weight", "bold");
  attr(out, "fill", kTextColor);
  out.append(" text-anchor=\"middle\">");
  append_text(out, plot.title);
  out.append("</text>\n");
}

std::size_t total_points(const Plot& plot) {
  std::size_t n = 0;
  for (const Series& s : plot.series) n += s.x.size();
  return n;
}

}  // namespace

std::string render_svg(const Plot& plot) {
  validate(plot);
  const Canvas canvas = lay_out(plot);
  std::string out;
  out.reserve(8192 + 48 * total_points(plot));
  append_svg_start(out, plot, canvas);
  append_grid(out, canvas);

  // Geometry in pixels: what is drawn, and what the legend and the labels avoid.
  Obstacles data;
  const std::vector<SeriesGeometry> series = series_geometry(plot, canvas, data);
  add_point_boxes(plot, canvas, data);
  const Legend legend = place_legend(plot, series, canvas.area, data);
  const std::vector<GuideGeometry> guides = guide_geometry(plot, canvas);

  // Drawn bottom to top: data, frame, labels over the data, axis texts, legend.
  append_guides(out, guides, canvas);
  append_series(out, plot, series, canvas);
  append_frame_and_ticks(out, canvas);
  LabelSpace labels{std::move(data), canvas.area, &guides};
  if (legend.box) labels.taken.boxes.push_back(*legend.box);
  append_guide_labels(out, canvas, labels);
  append_point_labels(out, plot, canvas, labels);
  append_tick_labels(out, canvas);
  append_axis_labels(out, plot, canvas);
  append_title(out, plot, canvas);
  append_legend(out, plot, legend);
  out.append("</svg>\n");
  return out;
}

}  // namespace imunoise::report
