// SVG plot writer: golden files for three typical plots (Allan-like log-log,
// drift-like linear, PSD-like log-log with unplottable values), well-formed XML for every
// output including the degenerate cases, determinism, escaping, errors; and the test-side XML
// checker itself.
//
// Golden files: tests/report/golden/<name>.svg. After an intended change of the output,
// regenerate with IMUNOISE_UPDATE_GOLDEN=1 and look at the pictures before committing them.

#include "report/svg_plot.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.h"
#include "test_support.h"
#include "xml_check.h"

namespace imunoise::report {
namespace {

using test::check_xml;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// ------------------------------------------------------------------------------ the plots

/// An Allan-deviation-like plot: three axes with error bars, a dashed model, two slope
/// guides, two read-off points.
Plot allan_plot() {
  Plot p;
  p.id = "allan";
  p.title = "Gyro Allan deviation";
  p.x = {"averaging time τ [s]", Scale::log10, {}, {}};
  p.y = {"Allan deviation σ(τ) [rad/s]", Scale::log10, {}, {}};
  const double n[3] = {1.2e-4, 1.5e-4, 0.9e-4};
  const double k[3] = {2e-6, 3e-6, 1.5e-6};
  const double b[3] = {4e-6, 5e-6, 3.5e-6};
  const Marker markers[3] = {Marker::circle, Marker::square, Marker::triangle};
  const char* names[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    Series s;
    s.name = std::string("gyro ") + names[a];
    s.color = a;
    s.marker = markers[a];
    for (int i = 0; i <= 20; ++i) {
      const double tau = 0.02 * std::pow(2.0, i);
      const double sigma =
          std::sqrt(n[a] * n[a] / tau + k[a] * k[a] * tau / 3.0 + 0.44 * b[a] * b[a]);
      const double edf = 1e5 / tau;
      s.x.push_back(tau);
      s.y.push_back(sigma);
      s.y_low.push_back(sigma * (1.0 - 1.0 / std::sqrt(edf)));
      s.y_high.push_back(sigma * (1.0 + 1.2 / std::sqrt(edf)));
    }
    p.series.push_back(std::move(s));
  }
  Series model;
  model.name = "fitted model (x)";
  model.color = 6;
  model.line = Line::dashed;
  model.line_width = 1.2;
  for (int i = 0; i <= 40; ++i) {
    const double tau = 0.02 * std::pow(2.0, 0.5 * i);
    model.x.push_back(tau);
    model.y.push_back(std::sqrt(n[0] * n[0] / tau + k[0] * k[0] * tau / 3.0 + 0.44 * b[0] * b[0]));
  }
  p.series.push_back(std::move(model));
  p.guides.push_back({-0.5, 1.0, n[0], "−1/2"});
  p.guides.push_back({0.5, 3.0, k[0], "+1/2"});
  p.points.push_back({1.0, n[0], "N at τ = 1 s", 0});
  p.points.push_back({1500.0, 0.664 * b[0], "B floor", 1});
  return p;
}

/// A drift-like plot on linear axes: predicted 1σ and 3σ, a Monte Carlo envelope and the
/// actual segments as markers.
Plot drift_plot() {
  Plot p;
  p.id = "drift";
  p.title = "Horizontal position drift";
  p.x = {"time since alignment [s]", Scale::linear, {}, {}};
  p.y = {"horizontal error [m]", Scale::linear, {}, {}};
  p.legend = LegendCorner::top_left;
  Series one{"predicted 1σ", {}, {}, {}, {}, 0, Line::solid, Marker::none, 2.0};
  Series three{"predicted 3σ", {}, {}, {}, {}, 0, Line::dashed, Marker::none, 1.5};
  Series mc{"Monte Carlo 68 %", {}, {}, {}, {}, 2, Line::dotted, Marker::none, 1.5};
  for (int i = 0; i <= 60; ++i) {
    const double t = 10.0 * i;
    const double sigma = 0.004 * t * std::sqrt(t) / 60.0;
    one.x.push_back(t);
    one.y.push_back(sigma);
    three.x.push_back(t);
    three.y.push_back(3.0 * sigma);
    mc.x.push_back(t);
    mc.y.push_back(sigma * (1.0 + 0.05 * ((i % 7) - 3) / 3.0));
  }
  Series actual{"segments (actual)", {}, {}, {}, {}, 1, Line::none, Marker::diamond, 1.5};
  const double ends[6] = {0.3, 0.9, 1.4, 0.5, 2.1, 0.2};
  for (int s = 0; s < 6; ++s) {
    actual.x.push_back(600.0);
    actual.y.push_back(ends[s]);
  }
  p.series = {one, three, mc, actual};
  return p;
}

/// A PSD-like log-log plot whose series contains a zero frequency, zero, negative, NaN and
/// infinite values, and error bars reaching below zero.
Plot psd_plot() {
  Plot p;
  p.id = "psd";
  p.title = "Gyro z: one-sided PSD";
  p.x = {"frequency [Hz]", Scale::log10, {}, {}};
  p.y = {"PSD [(rad/s)²/Hz]", Scale::log10, {}, {}};
  p.legend = LegendCorner::bottom_left;
  Series welch{"Welch, log-binned", {}, {}, {}, {}, 1, Line::solid, Marker::circle, 1.0};
  for (int i = 0; i < 30; ++i) {
    const double f = i == 0 ? 0.0 : 1e-3 * std::pow(10.0, i / 7.0);
    double s = 2.0 * 1.2e-4 * 1.2e-4 + 1e-12 / (f * f + 1e-9);
    if (i == 5) s = 0.0;
    if (i == 9) s = -3e-9;
    if (i == 13) s = kNaN;
    if (i == 17) s = kInf;
    welch.x.push_back(f);
    welch.y.push_back(s);
    welch.y_low.push_back(i % 4 == 0 ? -1e-9 : 0.5 * s);
    welch.y_high.push_back(1.8 * s);
  }
  Series model{"model", {}, {}, {}, {}, 6, Line::dashed, Marker::none, 1.2};
  for (int i = 0; i <= 60; ++i) {
    const double f = 1e-3 * std::pow(10.0, i / 14.0);
    model.x.push_back(f);
    model.y.push_back(2.0 * 1.2e-4 * 1.2e-4 + 1e-12 / (f * f + 1e-9));
  }
  Series empty{"all ≤ 0", {1.0, 2.0}, {0.0, -1.0}, {}, {}, 3, Line::solid, Marker::square, 1.5};
  p.series = {welch, model, empty};
  p.guides.push_back({-2.0, 0.01, 1e-8, "−2"});
  return p;
}

/// Degenerate and hostile inputs, each must still give a well-formed SVG.
std::vector<std::pair<std::string, Plot>> edge_case_plots() {
  std::vector<std::pair<std::string, Plot>> out;
  for (Scale scale : {Scale::linear, Scale::log10}) {
    const std::string tag = scale == Scale::log10 ? " (log)" : " (linear)";
    Plot empty;
    empty.x.scale = empty.y.scale = scale;
    out.emplace_back("empty plot" + tag, empty);

    Plot single;
    single.x.scale = single.y.scale = scale;
    single.series.push_back({"one point", {3.0}, {7.0}, {}, {}, 0, Line::solid, Marker::circle});
    out.emplace_back("single point" + tag, single);

    Plot equal;
    equal.x.scale = equal.y.scale = scale;
    equal.series.push_back(
        {"constant", {1.0, 1.0, 1.0}, {1.0, 1.0, 1.0}, {}, {}, 1, Line::solid, Marker::square});
    out.emplace_back("all equal" + tag, equal);

    Plot zero;
    zero.x.scale = zero.y.scale = scale;
    zero.series.push_back({"zeros", {0.0, 0.0}, {0.0, 0.0}, {}, {}, 2, Line::solid, Marker::none});
    out.emplace_back("all zero" + tag, zero);

    Plot extreme;
    extreme.x.scale = extreme.y.scale = scale;
    extreme.series.push_back({"extremes",
                              {1e-300, 1.0, 1e300},
                              {1e300, 1.0, 1e-300},
                              {},
                              {},
                              3,
                              Line::dotted,
                              Marker::cross});
    extreme.guides.push_back({1.0, 1.0, 1.0, "1"});
    out.emplace_back("1e-300..1e300" + tag, extreme);

    Plot tiny;
    tiny.x.scale = tiny.y.scale = scale;
    tiny.series.push_back(
        {"tiny", {1e-300, 2e-300, 3e-300}, {1e-300, 3e-300, 2e-300}, {}, {}, 4, Line::solid});
    out.emplace_back("tiny values" + tag, tiny);

    Plot huge;
    huge.x.scale = huge.y.scale = scale;
    huge.series.push_back({"huge", {1e300, 2e300}, {-1e308, 1.7e308}, {}, {}, 5});
    out.emplace_back("huge values" + tag, huge);

    Plot nonfinite;
    nonfinite.x.scale = nonfinite.y.scale = scale;
    nonfinite.series.push_back({"non-finite only",
                                {kNaN, kInf, -kInf},
                                {1.0, kNaN, 2.0},
                                {kNaN, 0.0, 1.0},
                                {kInf, 2.0, kNaN},
                                0,
                                Line::solid,
                                Marker::diamond});
    out.emplace_back("non-finite" + tag, nonfinite);

    Plot clipped;  // fixed limits far inside the data: everything clipped, nothing huge
    clipped.x = {"x", scale, 2.0, 3.0};
    clipped.y = {"y", scale, 2.0, 3.0};
    clipped.series.push_back({"far",
                              {1.0, 1e200, 2.5, 1e-200, 2.2},
                              {1e250, 2.5, 1e-250, 2.7, 2.9},
                              {1e-300, 1.0, 1.0, 1.0, -5.0},
                              {1e300, 10.0, 1.0, 2.8, 2.95},
                              1,
                              Line::solid,
                              Marker::circle});
    clipped.guides.push_back({-3.0, 2.5, 2.5, "steep"});
    clipped.points.push_back({2.5, 2.5, "inside", 2});
    clipped.points.push_back({25.0, 2.5, "outside", 2});
    out.emplace_back("clipped" + tag, clipped);

    Plot text;
    text.x = {"<x> & \"quotes\" 'apostrophes'", scale, {}, {}};
    text.y = {"y </svg>", scale, {}, {}};
    text.title = "Title <with> & \"markup\" ]]> \x01 bad \xFF\xFE utf-8 \xE2\x82";
    text.series.push_back({"a<b & c>\"d\"", {1.0, 2.0}, {1.0, 2.0}, {}, {}, 0});
    text.guides.push_back({1.0, 1.5, 1.5, "&lt; not an entity"});
    text.points.push_back({1.5, 1.5, "<point & label>", 1});
    text.id = "9 bad id\"<";
    out.emplace_back("text escaping" + tag, text);
  }
  Plot tiny_canvas = allan_plot();
  tiny_canvas.width_px = 10;
  tiny_canvas.height_px = -5;
  out.emplace_back("tiny canvas", tiny_canvas);
  Plot sub_decade;
  sub_decade.x = {"x", Scale::log10, 2.0, 5.0};
  sub_decade.y = {"y", Scale::log10, 0.03, 0.07};
  sub_decade.series.push_back({"s", {2.0, 3.0, 4.0}, {0.04, 0.05, 0.06}, {}, {}, 0});
  out.emplace_back("log axis inside one decade", sub_decade);
  return out;
}

std::filesystem::path golden_dir() {
  return std::filesystem::path(IMUNOISE_SOURCE_DIR) / "tests" / "report" / "golden";
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Every number written in TEXT (digit runs with an optional sign and decimals).
std::vector<double> numbers_in(const std::string& text) {
  std::vector<double> out;
  for (std::size_t i = 0; i < text.size();) {
    const bool starts =
        (text[i] >= '0' && text[i] <= '9') ||
        (text[i] == '-' && i + 1 < text.size() && text[i + 1] >= '0' && text[i + 1] <= '9');
    if (!starts || (i > 0 && (std::isalnum(static_cast<unsigned char>(text[i - 1])) ||
                              text[i - 1] == '#' || text[i - 1] == '.'))) {
      ++i;
      continue;
    }
    double v = 0.0;
    const auto r =
        std::from_chars(text.data() + i, text.data() + text.size(), v, std::chars_format::fixed);
    out.push_back(v);
    i = static_cast<std::size_t>(r.ptr - text.data()) + (r.ptr == text.data() + i ? 1 : 0);
  }
  return out;
}

void expect_sane_svg(const std::string& svg, const std::string& what) {
  SCOPED_TRACE(what);
  const auto xml = check_xml(svg);
  EXPECT_TRUE(xml.ok) << xml.message;
  EXPECT_EQ(xml.root, "svg");
  EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  std::string lower = svg;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  EXPECT_EQ(lower.find("nan"), std::string::npos);
  EXPECT_EQ(lower.find("inf"), std::string::npos);
  for (double v : numbers_in(svg)) {
    EXPECT_LT(std::abs(v), 1e5) << "a coordinate far outside the canvas";
  }
}

// ----------------------------------------------------------------------------- golden files

TEST(SvgPlot, GoldenFiles) {
  const bool update = std::getenv("IMUNOISE_UPDATE_GOLDEN") != nullptr;
  for (const auto& [name, plot] :
       {std::pair{"allan_loglog", allan_plot()}, std::pair{"drift_linear", drift_plot()},
        std::pair{"psd_unplottable", psd_plot()}}) {
    const std::string svg = render_svg(plot);
    expect_sane_svg(svg, name);
    const auto path = golden_dir() / (std::string(name) + ".svg");
    if (update) {
      std::filesystem::create_directories(golden_dir());
      std::ofstream(path, std::ios::binary) << svg;
      continue;
    }
    ASSERT_TRUE(std::filesystem::exists(path))
        << path << " missing: run with IMUNOISE_UPDATE_GOLDEN=1 and look at it";
    EXPECT_EQ(svg, read_file(path)) << "differs from " << path;
  }
}

TEST(SvgPlot, GoldenFilesParseAsXml) {
  for (const char* name : {"allan_loglog", "drift_linear", "psd_unplottable"}) {
    const auto path = golden_dir() / (std::string(name) + ".svg");
    if (!std::filesystem::exists(path)) continue;  // reported by GoldenFiles
    const auto xml = check_xml(read_file(path));
    EXPECT_TRUE(xml.ok) << path << ": " << xml.message;
  }
}

TEST(SvgPlot, ContentOfTheAllanPlot) {
  const std::string svg = render_svg(allan_plot());
  EXPECT_NE(svg.find("viewBox=\"0 0 900 600\""), std::string::npos);
  EXPECT_NE(svg.find("<clipPath id=\"allan-area\">"), std::string::npos);
  EXPECT_NE(svg.find("clip-path=\"url(#allan-area)\""), std::string::npos);
  EXPECT_NE(svg.find("10<tspan dy=\"-6\" font-size=\"10\">&#8722;2</tspan>"), std::string::npos);
  for (const char* text : {">gyro x<", ">gyro y<", ">gyro z<", ">fitted model (x)<", ">−1/2<",
                           ">+1/2<", ">N at τ = 1 s<", ">B floor<", "Gyro Allan deviation"}) {
    EXPECT_NE(svg.find(text), std::string::npos) << text;
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_NE(svg.find("stroke=\"" + std::string(palette_color(c)) + "\""), std::string::npos);
  }
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  EXPECT_NE(svg.find("stroke=\"#ececec\""), std::string::npos);  // minor grid
  EXPECT_EQ(svg.find("<?xml"), std::string::npos);
}

TEST(SvgPlot, UnplottableSeriesIsInTheLegendAsNoData) {
  const std::string svg = render_svg(psd_plot());
  EXPECT_NE(svg.find(">all ≤ 0 (no data)<"), std::string::npos);
  EXPECT_NE(svg.find(">Welch, log-binned<"), std::string::npos);
  EXPECT_EQ(svg.find("Welch, log-binned (no data)"), std::string::npos);
}

TEST(SvgPlot, EdgeCasesAreWellFormed) {
  for (const auto& [name, plot] : edge_case_plots()) {
    std::string svg;
    ASSERT_NO_THROW(svg = render_svg(plot)) << name;
    expect_sane_svg(svg, name);
  }
}

TEST(SvgPlot, TextIsEscaped) {
  for (const auto& [name, plot] : edge_case_plots()) {
    if (name.rfind("text escaping", 0) != 0) continue;
    const std::string svg = render_svg(plot);
    EXPECT_NE(svg.find("Title &lt;with&gt; &amp; &quot;markup&quot; ]]&gt;"), std::string::npos);
    EXPECT_NE(svg.find("a&lt;b &amp; c&gt;&quot;d&quot;"), std::string::npos);
    EXPECT_NE(svg.find("&amp;lt; not an entity"), std::string::npos);
    EXPECT_NE(svg.find("\xEF\xBF\xBD"), std::string::npos);  // invalid UTF-8 → U+FFFD
    EXPECT_NE(svg.find("id=\"p9_bad_id__-area\""), std::string::npos);
    EXPECT_EQ(svg.find('\x01'), std::string::npos);
  }
}

TEST(SvgPlot, Deterministic) {
  for (const Plot& p : {allan_plot(), drift_plot(), psd_plot()}) {
    EXPECT_EQ(render_svg(p), render_svg(p));
  }
}

TEST(SvgPlot, IdsDifferBetweenPlots) {
  Plot a = drift_plot(), b = drift_plot();
  a.id = "fig-1";
  b.id = "fig-2";
  const std::string sa = render_svg(a), sb = render_svg(b);
  EXPECT_NE(sa.find("id=\"fig-1-area\""), std::string::npos);
  EXPECT_NE(sb.find("id=\"fig-2-area\""), std::string::npos);
  EXPECT_EQ(sa.find("fig-2"), std::string::npos);
}

TEST(SvgPlot, AutoscaleAndFixedLimits) {
  Plot p;
  p.x = {"x", Scale::log10, {}, {}};
  p.y = {"y", Scale::linear, -1.0, 4.0};
  p.series.push_back({"s", {0.3, 2.0, 45.0}, {1.0, 2.0, 3.0}, {}, {}, 0});
  const std::string svg = render_svg(p);
  // x autoscaled to the enclosing decades 0.1 … 100; y fixed at −1 … 4
  EXPECT_NE(svg.find(">10<tspan dy=\"-6\" font-size=\"10\">&#8722;1</tspan>"), std::string::npos);
  EXPECT_NE(svg.find(">10<tspan dy=\"-6\" font-size=\"10\">2</tspan>"), std::string::npos);
  EXPECT_EQ(svg.find(">10<tspan dy=\"-6\" font-size=\"10\">3</tspan>"), std::string::npos);
  EXPECT_NE(svg.find(">&#8722;1</text>"), std::string::npos);
  EXPECT_NE(svg.find(">4</text>"), std::string::npos);
  EXPECT_EQ(svg.find(">5</text>"), std::string::npos);
}

/// x of the legend box (the rounded rect), or -1 when there is none.
double legend_x(const std::string& svg) {
  const auto at = svg.find("<g>\n<rect x=\"");
  if (at == std::string::npos) return -1.0;
  return std::stod(svg.substr(at + 13, 12));
}

TEST(SvgPlot, LegendBestCornerAvoidsTheData) {
  Plot p;
  p.x = {"x", Scale::linear, {}, {}};
  p.y = {"y", Scale::linear, {}, {}};
  Series rising{"rising to the top right", {}, {}, {}, {}, 0, Line::solid, Marker::circle};
  for (int i = 0; i <= 50; ++i) {
    rising.x.push_back(i);
    rising.y.push_back(i * i);
  }
  p.series.push_back(rising);
  EXPECT_EQ(p.legend, LegendCorner::best);
  EXPECT_LT(legend_x(render_svg(p)), 450.0);  // top right is taken: top left
  p.legend = LegendCorner::top_right;
  EXPECT_GT(legend_x(render_svg(p)), 450.0);
  p.series[0].name.clear();
  EXPECT_EQ(legend_x(render_svg(p)), -1.0);  // nothing named: no legend
}

TEST(SvgPlot, BadInputsThrow) {
  Plot p;
  p.series.push_back({"s", {1.0, 2.0}, {1.0}, {}, {}, 0});
  test::expect_throw_containing<InputError>([&] { render_svg(p); }, "x has 2 values, y has 1");
  p.series[0].y = {1.0, 2.0};
  p.series[0].y_low = {0.5, 1.5};
  test::expect_throw_containing<InputError>([&] { render_svg(p); }, "y_low and y_high");
  p.series[0].y_high = {1.5, 2.5};
  EXPECT_NO_THROW(render_svg(p));
  p.series[0].fill_base = {0.0};
  test::expect_throw_containing<InputError>([&] { render_svg(p); },
                                            "fill_base must be empty or have 2 values (got 1)");
  p.series[0].fill_base.clear();
  p.x = {"x", Scale::log10, 0.0, {}};
  test::expect_throw_containing<InputError>([&] { render_svg(p); },
                                            "x axis min must be finite and > 0");
  p.x = {"x", Scale::linear, 2.0, 1.0};
  test::expect_throw_containing<InputError>([&] { render_svg(p); }, "x axis min must be < max");
  p.x = {"x", Scale::linear, {}, {}};
  p.y = {"y", Scale::linear, {}, kNaN};
  test::expect_throw_containing<InputError>([&] { render_svg(p); }, "y axis max must be finite");
}

TEST(SvgPlot, FilledBandIsOnePolygonPerPlottableRunUnderItsLine) {
  // A band from fill_base up to y: a NaN breaks it into two closed polygons (the top edge
  // forward, the base edge back), drawn before the line and clipped to the area; on a log y
  // axis a base of 0 is not plottable, so nothing of that point is filled.
  Plot p;
  p.id = "band";
  p.x = {"t", Scale::linear, 0.0, 10.0};
  p.y = {"share", Scale::linear, 0.0, 100.0};
  Series s;
  s.name = "stacked";
  s.x = {1, 2, 3, 5, 6, 7};
  s.y = {50, 60, 70, kNaN, 80, 90};
  s.fill_base = {10, 20, 30, 40, 40, 40};
  s.fill_opacity = 0.5;
  p.series.push_back(s);
  const std::string svg = render_svg(p);
  EXPECT_TRUE(check_xml(svg).ok);
  const std::size_t fill = svg.find("fill-opacity=\"0.5\"");
  ASSERT_NE(fill, std::string::npos);
  const std::size_t end = svg.find("/>", fill);
  const std::string band = svg.substr(fill, end - fill);
  EXPECT_NE(band.find("clip-path=\"url(#band-area)\""), std::string::npos);
  EXPECT_EQ(std::count(band.begin(), band.end(), 'M'), 2);
  EXPECT_EQ(std::count(band.begin(), band.end(), 'Z'), 2);
  EXPECT_LT(fill, svg.find("stroke-linejoin"));  // the band below the line
  p.y = {"share", Scale::log10, {}, {}};
  p.series[0].fill_base = {0, 0, 0, 0, 0, 0};
  EXPECT_EQ(render_svg(p).find("fill-opacity=\"0.5\""), std::string::npos);
}

TEST(SvgPlot, LargeSeriesRendersFast) {
  Plot p;
  p.x = {"t", Scale::log10, {}, {}};
  p.y = {"v", Scale::log10, {}, {}};
  Series s{"10 000 points", {}, {}, {}, {}, 0, Line::solid, Marker::circle};
  for (int i = 1; i <= 10000; ++i) {
    s.x.push_back(i * 0.01);
    s.y.push_back(1.0 + 0.5 * std::sin(i * 0.01));
    s.y_low.push_back(s.y.back() * 0.9);
    s.y_high.push_back(s.y.back() * 1.1);
  }
  p.series.push_back(std::move(s));
  const auto start = std::chrono::steady_clock::now();
  const std::string svg = render_svg(p);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 1.0);  // ~10 ms in Release; generous for sanitizer builds
  EXPECT_LT(svg.size(), 10000u * 200u);
  EXPECT_TRUE(check_xml(svg).ok);
}

TEST(SvgPlot, PaletteIsOkabeItoAndWraps) {
  EXPECT_EQ(palette_color(0), "#0072B2");
  EXPECT_EQ(palette_color(1), "#D55E00");
  EXPECT_EQ(palette_color(7), "#F0E442");
  EXPECT_EQ(palette_color(8), palette_color(0));
  EXPECT_EQ(palette_color(-1), palette_color(7));
}

TEST(SvgPlot, RendersWithRsvgConvert) {
  if (std::system("command -v rsvg-convert >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "rsvg-convert not on PATH (Debian: librsvg2-bin): PNG rendering not checked";
  }
  const auto dir = test::make_temp_dir("svg");
  for (const auto& [name, plot] :
       {std::pair{"allan", allan_plot()}, std::pair{"psd", psd_plot()}}) {
    const auto svg_path = dir / (std::string(name) + ".svg");
    const auto png_path = dir / (std::string(name) + ".png");
    std::ofstream(svg_path, std::ios::binary) << render_svg(plot);
    const std::string command = "rsvg-convert -w 900 '" + svg_path.string() + "' -o '" +
                                png_path.string() + "' 2>/dev/null";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    EXPECT_GT(std::filesystem::file_size(png_path), 1000u);
  }
  std::filesystem::remove_all(dir);
}

// ------------------------------------------------------------------------- the XML checker

TEST(XmlCheck, AcceptsWellFormedDocuments) {
  for (const char* doc : {
           "<a/>",
           "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!-- c --><a x='1' y=\"2\">t</a>\n",
           "<!DOCTYPE svg [<!ENTITY x \"y\">]><svg><g><g/></g><text>&amp;&lt;&gt;&quot;&apos;"
           "&#8722;&#x3C4;</text><![CDATA[ <raw> & ]]><?pi data?></svg>",
           "\xEF\xBB\xBF<r>τ &#65; <!----></r>",
       }) {
    const auto r = check_xml(doc);
    EXPECT_TRUE(r.ok) << doc << "\n" << r.message;
  }
  const auto r = check_xml("<svg><g/><g><path/></g></svg>");
  EXPECT_EQ(r.root, "svg");
  EXPECT_EQ(r.elements, 4u);
}

TEST(XmlCheck, ReportsMalformedDocumentsWithPosition) {
  struct Case {
    const char* doc;
    const char* fragment;
    std::size_t line, column;
  };
  for (const Case& c : {
           Case{"<a>\n  <b></a>", "</a> does not close <b>", 2, 6},
           Case{"<a><b></b>", "unclosed element <a>", 1, 11},
           Case{"<a x=1/>", "attribute value must be quoted", 1, 6},
           Case{"<a>\n &nbsp;</a>", "unknown entity &nbsp;", 2, 2},
           Case{"<a>fish & chips</a>", "'&' not starting a reference", 1, 9},
           Case{"<a>&#0;</a>", "bad character reference", 1, 4},
           Case{"<a/><b/>", "a second root element", 1, 5},
           Case{"<a x='1' x='2'/>", "duplicate attribute 'x'", 1, 10},
           Case{"text<a/>", "text before the root element", 1, 1},
           Case{"<a/>tail", "text after the root element", 1, 5},
           Case{"<a><!-- x -- y --></a>", "\"--\" inside a comment", 1, 11},
           Case{"<a>]]></a>", "\"]]>\" in text", 1, 4},
           Case{"<a x='<'/>", "'<' in an attribute value", 1, 7},
           Case{"<a/>\n<?xml version='1.0'?>", "XML declaration not at the start", 2, 6},
           Case{"", "no root element", 1, 1},
           Case{"<a>\x01</a>", "character not allowed in XML", 1, 4},
           Case{"<a>\xC3</a>", "invalid UTF-8", 1, 4},
           Case{"<1a/>", "expected a name", 1, 2},
           Case{"<a x='1'y='2'/>", "expected whitespace before an attribute", 1, 9},
       }) {
    const auto r = check_xml(c.doc);
    EXPECT_FALSE(r.ok) << c.doc;
    EXPECT_NE(r.message.find(c.fragment), std::string::npos) << c.doc << " → " << r.message;
    EXPECT_EQ(r.line, c.line) << c.doc << " → " << r.message;
    EXPECT_EQ(r.column, c.column) << c.doc << " → " << r.message;
  }
}

}  // namespace
}  // namespace imunoise::report
