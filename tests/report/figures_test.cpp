// The report's figures and HTML page: the model lines and read-off points of the Allan figure
// against the closed forms of theory.md §4.1–4.2, the CSV behind each figure against the
// plotted series, the drift envelopes, the interval histogram, and the HTML page's structure
// and escaping (every embedded SVG parsed as XML).

#include "report/figures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/number_text.h"
#include "report/html_page.h"
#include "xml_check.h"

namespace imunoise::report {
namespace {

using test::check_xml;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

const Series* find_series(const Figure& f, const std::string& csv_id) {
  for (std::size_t i = 0; i < f.series_ids.size(); ++i) {
    if (f.series_ids[i] == csv_id) return &f.plot.series[i];
  }
  return nullptr;
}

/// y of SERIES at x (linear interpolation in log-log; the model lines are log-spaced).
double value_at(const Series& s, double x) {
  for (std::size_t i = 0; i + 1 < s.x.size(); ++i) {
    if (s.x[i] <= x && x <= s.x[i + 1]) {
      const double w = std::log(x / s.x[i]) / std::log(s.x[i + 1] / s.x[i]);
      return std::exp(std::log(s.y[i]) + w * std::log(s.y[i + 1] / s.y[i]));
    }
  }
  return std::nan("");
}

/// A gyro model with N, B, K (and the read-offs of an ideal curve).
models::NoiseModel gyro_model() {
  models::NoiseModel m;
  m.confidence = 0.95;
  models::AxisModel a;
  a.name = "gyro_x";
  a.kind = SensorKind::gyro;
  const double n = 1e-4, b = 2e-5, k = 3e-7;
  a.terms[1].value = n;
  a.terms[1].identified = true;
  a.terms[2].value = b;
  a.terms[2].identified = true;
  a.terms[3].value = k;
  a.terms[3].identified = true;
  a.readoff.slope = {0.0, n, b, k, 0.0};
  a.tau_min_adev_s = 100.0;
  m.axes.push_back(a);
  return m;
}

io::AllanAxis gyro_curve() {
  io::AllanAxis d;
  d.name = "gyro_x";
  for (double tau = 0.02; tau < 2e4; tau *= 2.0) {
    const double adev =
        std::sqrt(1e-8 / tau + 2.0 * std::log(2.0) / std::numbers::pi * 4e-10 + 9e-14 * tau / 3.0);
    analysis::DeviationPoint p;
    p.tau_s = tau;
    p.value = adev;
    p.ci_low = 0.9 * adev;
    p.ci_high = 1.1 * adev;
    d.oadev.points.push_back(p);
  }
  return d;
}

TEST(AllanFigure, ModelAndTermLinesFollowTheClosedForms) {
  const Figure f = allan_figure(SensorKind::gyro, {gyro_curve()}, gyro_model());
  EXPECT_EQ(f.name, "allan-gyro");
  const Series* total = find_series(f, "gyro_x model");
  const Series* n = find_series(f, "gyro_x term N");
  const Series* b = find_series(f, "gyro_x term B");
  const Series* k = find_series(f, "gyro_x term K");
  ASSERT_TRUE(total && n && b && k);
  EXPECT_EQ(find_series(f, "gyro_x term Q"), nullptr);  // not identified: not drawn
  // theory.md §4.1: σ² = N²/τ + (2 ln2/π)B² + K²τ/3, each term on its own.
  for (std::size_t i = 0; i < total->x.size(); ++i) {
    const double tau = total->x[i];
    EXPECT_NEAR(n->y[i], 1e-4 / std::sqrt(tau), 1e-12 * n->y[i]);
    EXPECT_NEAR(b->y[i], 2e-5 * std::sqrt(2.0 * std::log(2.0) / std::numbers::pi), 1e-15);
    EXPECT_NEAR(k->y[i], 3e-7 * std::sqrt(tau / 3.0), 1e-12 * k->y[i]);
    EXPECT_NEAR(total->y[i] * total->y[i],
                n->y[i] * n->y[i] + b->y[i] * b->y[i] + k->y[i] * k->y[i],
                1e-12 * total->y[i] * total->y[i]);
  }
  EXPECT_EQ(n->line, Line::dashed);
  EXPECT_EQ(total->line, Line::solid);
  // The model spans the measured τ range.
  EXPECT_DOUBLE_EQ(total->x.front(), 0.02);
  EXPECT_NEAR(total->x.back(), gyro_curve().oadev.points.back().tau_s, 1e-9);
}

TEST(AllanFigure, ReadoffPointsLieOnTheTermLinesWhereIeee952ReadsThem) {
  const Figure f = allan_figure(SensorKind::gyro, {gyro_curve()}, gyro_model());
  ASSERT_EQ(f.plot.points.size(), 3u);  // N, B, K (Q and R not read off)
  for (const PointLabel& p : f.plot.points) {
    const std::string symbol = p.text.substr(p.text.size() - 1);
    const Series* term = find_series(f, "gyro_x term " + symbol);
    ASSERT_NE(term, nullptr) << p.text;
    EXPECT_NEAR(value_at(*term, p.x), p.y, 1e-9 * p.y) << p.text;
  }
  // N at τ = 1 s reads N; K at τ = 3 s reads K; B at the minimum reads 0.664·B.
  EXPECT_EQ(f.plot.points[0].x, 1.0);
  EXPECT_DOUBLE_EQ(f.plot.points[0].y, 1e-4);
  EXPECT_EQ(f.plot.points[1].x, 100.0);
  EXPECT_NEAR(f.plot.points[1].y, 0.6643 * 2e-5, 1e-4 * 2e-5);
  EXPECT_EQ(f.plot.points[2].x, 3.0);
  EXPECT_DOUBLE_EQ(f.plot.points[2].y, 3e-7);
}

TEST(AllanFigure, OtherSensorAxesAreLeftOut) {
  const Figure f = allan_figure(SensorKind::accel, {gyro_curve()}, gyro_model());
  EXPECT_EQ(f.name, "allan-accel");
  EXPECT_TRUE(f.plot.series.empty());
  EXPECT_TRUE(check_xml(render_svg(f.plot)).ok);
}

TEST(FigureCsv, HoldsExactlyThePlottedPointsWithUnitsInTheHeader) {
  const Figure f = allan_figure(SensorKind::gyro, {gyro_curve()}, gyro_model());
  const auto lines = lines_of(figure_csv(f));
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0], "series,tau_s,adev_rad_per_s,adev_rad_per_s_ci_low,adev_rad_per_s_ci_high");
  std::size_t points = 0;
  for (const Series& s : f.plot.series) points += s.x.size();
  EXPECT_EQ(lines.size(), 1 + points + f.plot.points.size());
  // The first data row is the first OADEV point with its interval, round-trip exact.
  const analysis::DeviationPoint d = gyro_curve().oadev.points.front();
  EXPECT_EQ(lines[1].substr(0, lines[1].find(',')), "gyro_x oadev");
  std::vector<double> cells;
  std::istringstream row(lines[1].substr(lines[1].find(',') + 1));
  for (std::string cell; std::getline(row, cell, ',');) cells.push_back(std::stod(cell));
  ASSERT_EQ(cells.size(), 4u);
  EXPECT_EQ(cells[0], d.tau_s);
  EXPECT_EQ(cells[1], d.value);
  EXPECT_EQ(cells[2], d.ci_low);
  EXPECT_EQ(cells[3], d.ci_high);
  EXPECT_EQ(lines.back().rfind("readoff: x K,3,", 0), 0u) << lines.back();
}

TEST(DriftFigure, ThreeSigmaIsThreeTimesTheDrms) {
  pipeline::DriftSeries d;
  d.time_s = {1, 10, 100};
  d.predicted_drms_m = {0.01, 0.5, 40};
  d.recorded_rms_m = {0.012, 0.4, 45};
  std::vector<pipeline::DriftSegment> segments(2);
  segments[0].time_s = segments[1].time_s = {1, 10, 100};
  segments[0].position_error_ne_m = {{0.01, 0.0}, {0.3, 0.0}, {30.0, 0.0}};
  segments[1].position_error_ne_m = {{0.02, 0.0}, {0.6, 0.0}, {60.0, 0.0}};
  const Figure f = drift_figure(d, segments);
  const Series* one = find_series(f, "predicted 1 sigma");
  const Series* three = find_series(f, "predicted 3 sigma");
  ASSERT_TRUE(one && three);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(three->y[i], 3.0 * one->y[i]);
  EXPECT_EQ(f.plot.series.front().name, "recorded segments (2)");
  EXPECT_EQ(f.plot.series[1].name, "");  // one legend entry for all segments
  EXPECT_TRUE(check_xml(render_svg(f.plot)).ok);
}

TEST(DriftBudgetFigure, BandsStackTheSharesToOneHundredPercent) {
  pipeline::DriftBudget b;
  b.time_s = {1, 10, 100, 1000};
  // white, B, K, GM, R, alignment, heading; R and heading are 0 throughout.
  b.variance_m2 = {{1, 1, 0, 0, 0, 2, 0},
                   {4, 2, 1, 1, 0, 2, 0},
                   {10, 20, 30, 30, 0, 10, 0},
                   {5, 50, 300, 100, 0, 45, 0}};
  b.predicted_variance_m2 = {4, 10, 100, 500};
  b.report_time = {false, true, true, false};
  const Figure f = drift_budget_figure(b);
  EXPECT_EQ(f.name, "drift-budget");
  ASSERT_EQ(f.plot.series.size(), 5u);  // the sources that are 0 throughout are left out
  std::vector<std::string> names;
  for (const Series& s : f.plot.series) names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"N", "B", "K", "GM", "alignment"}));
  for (std::size_t k = 0; k < f.plot.series.size(); ++k) {
    const Series& s = f.plot.series[k];
    EXPECT_EQ(s.fill_base, k == 0 ? std::vector<double>(4, 0.0) : f.plot.series[k - 1].y);
  }
  EXPECT_EQ(f.plot.series[0].y, (std::vector<double>{25, 40, 10, 1}));
  for (const double top : f.plot.series.back().y) EXPECT_DOUBLE_EQ(top, 100.0);
  const std::string svg = render_svg(f.plot);
  EXPECT_TRUE(check_xml(svg).ok);
  EXPECT_NE(svg.find("fill-opacity=\"0.55\""), std::string::npos);  // the bands are drawn
  const auto lines = lines_of(figure_csv(f));
  EXPECT_EQ(lines[0], "series,time_s,cumulative_share_percent");
  EXPECT_EQ(lines[1], "white_noise,1,25");
}

TEST(IntervalFigure, OneStemPerNonEmptyBinAndOneBinShowsTheStep) {
  const Figure f =
      interval_figure({0.0098, 0.0099, 0.0100}, {0.0099, 0.0100, 0.0101}, {5, 0, 995}, 0.01);
  const Series* h = find_series(f, "histogram");
  ASSERT_NE(h, nullptr);
  ASSERT_EQ(h->x.size(), 2u);  // the empty bin has no stem
  EXPECT_DOUBLE_EQ(h->x[0], 9.85);
  EXPECT_EQ(h->y[0] + h->y[1], 1000.0);
  EXPECT_EQ(h->y_low, (std::vector<double>{0.0, 0.0}));  // from the axis bottom
  EXPECT_EQ(h->y_high, h->y);
  const auto lines = lines_of(figure_csv(f));
  EXPECT_EQ(lines[0], "series,interval_ms,count");
  EXPECT_EQ(lines[1], "histogram," + shortest_number_text(h->x[0]) + ",5");
  const Figure one = interval_figure({0.02 - 1e-8}, {0.02 + 1e-8}, {7}, 0.02);
  ASSERT_TRUE(one.plot.x.min && one.plot.x.max);
  EXPECT_NEAR(*one.plot.x.min, 18.0, 1e-9);
  EXPECT_NEAR(*one.plot.x.max, 22.0, 1e-9);
  EXPECT_TRUE(check_xml(render_svg(one.plot)).ok);
  EXPECT_THROW(interval_figure({0.0}, {}, {1}, 0.01), ContractViolation);
}

TEST(GapsFigure, NoGapsIsStillAValidPlot) {
  const Figure none = gaps_figure({}, {}, 3600.0, 0);
  EXPECT_NE(none.plot.title.find("none found"), std::string::npos);
  EXPECT_TRUE(check_xml(render_svg(none.plot)).ok);
  const Figure some = gaps_figure({10.0, 7200.0}, {0.5, 3.0}, 10800.0, 5);
  EXPECT_NE(some.caption.find("only the first 2 of 5"), std::string::npos);
  EXPECT_DOUBLE_EQ(some.plot.series[0].x[1], 2.0);  // hours
}

// --------------------------------------------------------------------------------- HTML page

using test::svg_elements;

TEST(HtmlPage, SectionsTablesFiguresAndEscaping) {
  ReportPage page;
  page.title = "imunoise report — <rec> & \"x\"";
  page.facts = {{"samples", "100"}};
  PageSection s;
  s.id = "summary";
  s.heading = "Summary";
  s.tables.push_back({"summary-table", "cap", {"a", "b"}, {{"1.5", "x<y"}, {"-2", "z"}}});
  pipeline::DriftSeries drift;
  drift.time_s = {1, 2};
  drift.predicted_drms_m = {1, 2};
  Figure f = drift_figure(drift, {});
  s.figures.push_back({f.name, render_svg(f.plot), "cap & more", {{"data", "plots/d.csv"}}});
  s.code_lines = {"imunoise analyze 'a b.csv' -o out"};
  page.sections.push_back(s);
  const std::string html = render_html(page);
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("<title>imunoise report — &lt;rec&gt; &amp; &quot;x&quot;</title>"),
            std::string::npos);
  EXPECT_NE(html.find("<table id=\"summary-table\">"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\">1.5</td><td>x&lt;y</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\">-2</td>"), std::string::npos);
  EXPECT_NE(html.find("<figure id=\"fig-drift-horizontal\">"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"plots/d.csv\">data</a>"), std::string::npos);
  EXPECT_NE(html.find("<section id=\"summary\">"), std::string::npos);
  EXPECT_NE(html.find("imunoise analyze 'a b.csv' -o out"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);  // no script, no external resource
  EXPECT_EQ(html.find("http://"), html.find("http://www.w3.org"));
  const auto svgs = svg_elements(html);
  ASSERT_EQ(svgs.size(), 1u);
  const auto check = check_xml(svgs[0]);
  EXPECT_TRUE(check.ok) << check.message;
  // The whole page nests: every opened section/figure/table is closed.
  for (const char* tag : {"section", "figure", "table", "tbody", "pre"}) {
    std::size_t open = 0, close = 0, at = 0;
    while ((at = html.find(std::string("<") + tag, at)) != std::string::npos) ++open, ++at;
    at = 0;
    while ((at = html.find(std::string("</") + tag + ">", at)) != std::string::npos) ++close, ++at;
    EXPECT_EQ(open, close) << tag;
  }
}

TEST(HtmlPage, RowLengthMismatchIsAnError) {
  ReportPage page;
  PageSection s;
  s.tables.push_back({"t", "", {"a", "b"}, {{"1"}}});
  page.sections.push_back(s);
  EXPECT_THROW(render_html(page), ContractViolation);
}

}  // namespace
}  // namespace imunoise::report
