/// @file
/// @brief The report's figures (see figures.h).
#include "report/figures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "analysis/noise_terms.h"
#include "common/errors.h"
#include "common/number_text.h"
#include "common/sampling_gap.h"
#include "common/sensor_kind.h"

namespace imunoise::report {

namespace {

constexpr int kModelPoints = 80;  // log-spaced points of each model line

std::string axis_letter(const std::string& axis_name) {
  const std::size_t underscore = axis_name.rfind('_');
  return underscore == std::string::npos ? axis_name : axis_name.substr(underscore + 1);
}

int axis_color(const std::string& axis_name) {
  const std::string letter = axis_letter(axis_name);
  if (letter == "x") return 0;
  if (letter == "y") return 1;
  if (letter == "z") return 2;
  return 3;
}

Marker axis_marker(int color) {
  switch (color) {
    case 0:
      return Marker::circle;
    case 1:
      return Marker::square;
    case 2:
      return Marker::triangle;
    default:
      return Marker::diamond;
  }
}

/// The figure an axis goes in: gyro for "gyro…" names, the accelerometer one for every other.
SensorKind figure_kind(const std::string& axis_name) {
  return sensor_kind_of_channel(axis_name).value_or(SensorKind::accel);
}

/// KPOINTS log-spaced values from LO to HI (both > 0).
std::vector<double> log_space(double lo, double hi, int points) {
  std::vector<double> out;
  const double a = std::log10(lo), b = std::log10(hi);
  for (int i = 0; i < points; ++i) {
    out.push_back(std::pow(10.0, a + (b - a) * i / (points - 1)));
  }
  return out;
}

/// Keeps about kThinnedPoints of (X, Y), evenly spaced in log x (the first and last always):
/// a segment of 600 one-second points draws the same on a log time axis from a sixth of them.
constexpr std::size_t kThinnedPoints = 120;
void thin_for_log_axis(const std::vector<double>& x, const std::vector<double>& y,
                       std::vector<double>& x_out, std::vector<double>& y_out) {
  const std::size_t n = std::min(x.size(), y.size());
  if (n <= kThinnedPoints || !(x.front() > 0.0) || !(x[n - 1] > x.front())) {
    x_out.assign(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(n));
    y_out.assign(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(n));
    return;
  }
  const double step = std::log(x[n - 1] / x.front()) / static_cast<double>(kThinnedPoints - 1);
  double next = std::log(x.front());
  for (std::size_t i = 0; i < n; ++i) {
    const bool last = i + 1 == n;
    if (x[i] > 0.0 && (std::log(x[i]) >= next || last)) {
      x_out.push_back(x[i]);
      y_out.push_back(y[i]);
      next = std::log(x[i]) + step;
    }
  }
}

void add_series(Figure& f, Series s, std::string csv_id) {
  f.plot.series.push_back(std::move(s));
  f.series_ids.push_back(std::move(csv_id));
}

/// ADEV of one term of C alone (the other coefficients zeroed) at each τ.
std::vector<double> term_adev(const NoiseCoefficients& c, NoiseTerm term,
                              const std::vector<double>& tau) {
  std::vector<double> out;
  const double value = coefficient(c, term);
  for (double t : tau) {
    out.push_back(value * std::sqrt(analysis::term_avar_basis(term, t)));
  }
  return out;
}

}  // namespace

std::string figure_csv(const Figure& figure) {
  IMUNOISE_EXPECT(figure.series_ids.size() == figure.plot.series.size(),
                  "figure '" + figure.name + "': one CSV name per series is needed");
  std::string out = "series,";
  out.append(figure.x_column).append(",").append(figure.y_column);
  if (figure.csv_intervals) {
    out.append(",").append(figure.y_column).append("_ci_low,");
    out.append(figure.y_column).append("_ci_high");
  }
  out.append("\n");
  for (std::size_t s = 0; s < figure.plot.series.size(); ++s) {
    const Series& series = figure.plot.series[s];
    const bool bars = !series.y_low.empty();
    for (std::size_t i = 0; i < series.x.size(); ++i) {
      if (!std::isfinite(series.x[i]) || !std::isfinite(series.y[i])) continue;
      out.append(figure.series_ids[s]).append(",");
      out.append(shortest_number_text(series.x[i])).append(",");
      out.append(shortest_number_text(series.y[i]));
      if (figure.csv_intervals) {
        out.append(",");
        if (bars) {
          out.append(shortest_number_text(series.y_low[i])).append(",");
          out.append(shortest_number_text(series.y_high[i]));
        } else {
          out.append(",");
        }
      }
      out.append("\n");
    }
  }
  for (const PointLabel& p : figure.plot.points) {
    out.append("readoff: ").append(p.text).append(",");
    out.append(shortest_number_text(p.x)).append(",").append(shortest_number_text(p.y));
    out.append(figure.csv_intervals ? ",,\n" : "\n");
  }
  return out;
}

namespace {

/// The measured OADEV of one axis of allan.csv as the plotted columns.
struct Measured {
  std::string axis_name;
  std::vector<double> tau_s, deviation, ci_low, ci_high;
};

Measured oadev_of(const io::AllanAxis& axis) {
  Measured m;
  m.axis_name = axis.name;
  for (const analysis::DeviationPoint& p : axis.oadev.points) {
    m.tau_s.push_back(p.tau_s);
    m.deviation.push_back(p.value);
    m.ci_low.push_back(p.ci_low);
    m.ci_high.push_back(p.ci_high);
  }
  return m;
}

}  // namespace

Figure allan_figure(SensorKind kind, const std::vector<io::AllanAxis>& curves,
                    const models::NoiseModel& model) {
  Figure f;
  const std::string sensor(sensor_name(kind));
  f.name = "allan-" + sensor;
  f.x_column = "tau_s";
  f.y_column = "adev_" + std::string(rate_unit_suffix(kind));
  f.plot.id = f.name;
  f.plot.title = kind == SensorKind::gyro ? "Gyroscopes: overlapping Allan deviation"
                                          : "Accelerometers: overlapping Allan deviation";
  f.plot.x = {"averaging time τ [s]", Scale::log10, {}, {}};
  f.plot.y = {kind == SensorKind::gyro ? "σ(τ) [rad/s]" : "σ(τ) [m/s²]", Scale::log10, {}, {}};
  double confidence = model.confidence;
  for (const io::AllanAxis& allan : curves) {
    const Measured curve = oadev_of(allan);
    if (figure_kind(curve.axis_name) != kind) continue;
    const int color = axis_color(curve.axis_name);
    const std::string letter = axis_letter(curve.axis_name);
    Series data;
    data.name = letter + ": OADEV";
    data.x = curve.tau_s;
    data.y = curve.deviation;
    data.y_low = curve.ci_low;
    data.y_high = curve.ci_high;
    data.color = color;
    data.line = Line::none;
    data.marker = axis_marker(color);
    add_series(f, std::move(data), curve.axis_name + " oadev");

    const models::AxisModel* axis = model.find_axis(curve.axis_name);
    if (axis == nullptr || curve.tau_s.empty()) continue;
    const auto [lo, hi] = std::minmax_element(curve.tau_s.begin(), curve.tau_s.end());
    if (!(*lo > 0.0) || !(*hi > *lo)) continue;
    const std::vector<double> tau = log_space(*lo, *hi, kModelPoints);
    const NoiseCoefficients c = axis->coefficients();

    Series total;
    total.name = letter + ": fitted model";
    total.x = tau;
    for (double t : tau) total.y.push_back(analysis::model_adev(c, t));
    total.color = color;
    total.line_width = 1.8;
    add_series(f, std::move(total), curve.axis_name + " model");

    std::string term_list;
    std::vector<Series> terms;
    std::vector<std::string> term_ids;
    for (NoiseTerm term : kNoiseTerms) {
      if (!(coefficient(c, term) > 0.0)) continue;
      Series s;
      s.x = tau;
      s.y = term_adev(c, term, tau);
      terms.push_back(std::move(s));
      term_ids.push_back(curve.axis_name + " term " + term_symbol(term));
      term_list.append(term_list.empty() ? "" : ", ").append(term_symbol(term));
    }
    for (std::size_t g = 0; g < c.gauss_markov.size(); ++g) {
      Series s;
      s.x = tau;
      for (double t : tau) {
        s.y.push_back(std::sqrt(
            analysis::gauss_markov_avar(c.gauss_markov[g].sigma, c.gauss_markov[g].tau_c_s, t)));
      }
      terms.push_back(std::move(s));
      term_ids.push_back(curve.axis_name + " term GM" + std::to_string(g + 1));
      term_list.append(term_list.empty() ? "" : ", ").append("GM");
    }
    for (std::size_t k = 0; k < c.sinusoids.size(); ++k) {
      Series s;
      s.x = tau;
      for (double t : tau) {
        s.y.push_back(std::sqrt(
            analysis::sinusoid_avar(c.sinusoids[k].amplitude, c.sinusoids[k].frequency_hz, t)));
      }
      terms.push_back(std::move(s));
      term_ids.push_back(curve.axis_name + " term sine" + std::to_string(k + 1));
      term_list.append(term_list.empty() ? "" : ", ").append("sine");
    }
    for (std::size_t t = 0; t < terms.size(); ++t) {
      Series& s = terms[t];
      if (t == 0) s.name = letter + ": terms " + term_list;
      s.color = color;
      s.line = Line::dashed;
      s.line_width = 1.0;
      add_series(f, std::move(s), term_ids[t]);
    }

    // IEEE-952 read-offs where the method reads them off the curve (theory.md §4.2).
    const auto& readoff = axis->readoff.slope;
    const double b_factor = std::sqrt(2.0 * std::log(2.0) / std::numbers::pi);
    const struct {
      NoiseTerm term;
      double tau_s, factor;
    } places[] = {{NoiseTerm::quantization, std::sqrt(3.0), 1.0},
                  {NoiseTerm::white_noise, 1.0, 1.0},
                  {NoiseTerm::bias_instability, axis->tau_min_adev_s, b_factor},
                  {NoiseTerm::random_walk, 3.0, 1.0},
                  {NoiseTerm::ramp, std::sqrt(2.0), 1.0}};
    for (const auto& place : places) {
      const double value = readoff[static_cast<std::size_t>(place.term)];
      if (!(value > 0.0) || !(place.tau_s > 0.0)) continue;
      const char* symbol = term_symbol(static_cast<NoiseTerm>(place.term));
      f.plot.points.push_back({place.tau_s, value * place.factor, letter + " " + symbol, color});
    }
  }
  f.caption = "Overlapping Allan deviation of each " + sensor + " axis with its " +
              significant_number_text(100.0 * confidence, 3) +
              " % chi-square interval (bars), the fitted model (solid) and each fitted term "
              "(dashed); labelled points are the IEEE-952 slope read-offs (Q at τ = √3 s, N at "
              "1 s, B = σ_min/0.664 at the minimum, K at 3 s, R at √2 s).";
  return f;
}

Figure psd_figure(SensorKind kind, const std::vector<io::PsdAxis>& spectra) {
  Figure f;
  const std::string sensor(sensor_name(kind));
  f.name = "psd-" + sensor;
  f.x_column = "frequency_hz";
  f.y_column = "psd_" + std::string(psd_unit_suffix(kind));
  f.plot.id = f.name;
  f.plot.title = kind == SensorKind::gyro ? "Gyroscopes: power spectral density (one-sided)"
                                          : "Accelerometers: power spectral density (one-sided)";
  f.plot.x = {"frequency f [Hz]", Scale::log10, {}, {}};
  f.plot.y = {
      kind == SensorKind::gyro ? "S(f) [(rad/s)²/Hz]" : "S(f) [(m/s²)²/Hz]", Scale::log10, {}, {}};
  for (const io::PsdAxis& s : spectra) {
    if (figure_kind(s.name) != kind) continue;
    const int color = axis_color(s.name);
    const std::string letter = axis_letter(s.name);
    Series measured;
    measured.name = letter + ": Welch PSD";
    measured.x = s.psd.frequency_hz;
    measured.y = s.psd.density;
    measured.color = color;
    measured.line_width = 1.2;
    add_series(f, std::move(measured), s.name + " psd");
    Series model;
    model.name = letter + ": fitted model";
    model.x = s.psd.frequency_hz;
    model.y = s.model_density;
    model.color = color;
    model.line = Line::dashed;
    model.line_width = 1.8;
    add_series(f, std::move(model), s.name + " model psd");
  }
  f.caption = "Log-binned one-sided Welch PSD of each " + sensor +
              " axis (solid) and the PSD the fitted model predicts (dashed): the cross-check of "
              "the Allan fit in the frequency domain.";
  return f;
}

Figure drift_figure(const pipeline::DriftSeries& drift,
                    const std::vector<pipeline::DriftSegment>& segments) {
  Figure f;
  f.name = "drift-horizontal";
  f.x_column = "time_s";
  f.y_column = "horizontal_error_m";
  f.plot.id = f.name;
  f.plot.title = "Free-inertial horizontal drift: recorded segments vs the model";
  f.plot.x = {"time since segment start [s]", Scale::log10, {}, {}};
  f.plot.y = {"horizontal position error [m]", Scale::log10, {}, {}};
  for (std::size_t k = 0; k < segments.size(); ++k) {
    Series s;
    if (k == 0) s.name = "recorded segments (" + std::to_string(segments.size()) + ")";
    thin_for_log_axis(segments[k].time_s, segments[k].horizontal_error_m(), s.x, s.y);
    s.color = 5;
    s.line_width = 0.6;
    add_series(f, std::move(s), "segment " + std::to_string(k));
  }
  if (!drift.recorded_rms_m.empty()) {
    Series rms;
    rms.name = "recorded RMS";
    rms.x = drift.time_s;
    rms.y = drift.recorded_rms_m;
    rms.color = 6;
    rms.line_width = 2.2;
    add_series(f, std::move(rms), "recorded rms");
  }
  Series one;
  one.name = "predicted 1σ (DRMS)";
  one.x = drift.time_s;
  one.y = drift.predicted_drms_m;
  one.color = 1;
  one.line_width = 2.2;
  add_series(f, std::move(one), "predicted 1 sigma");
  Series three;
  three.name = "predicted 3σ";
  three.x = drift.time_s;
  for (double v : drift.predicted_drms_m) three.y.push_back(3.0 * v);
  three.color = 1;
  three.line = Line::dashed;
  three.line_width = 1.6;
  add_series(f, std::move(three), "predicted 3 sigma");
  f.caption =
      "Horizontal position error of each free-inertial segment mechanized from the recording "
      "(thin), their RMS, and the 1σ (DRMS) and 3σ envelopes the fitted model predicts by "
      "covariance propagation.";
  return f;
}

Figure drift_budget_figure(const pipeline::DriftBudget& budget) {
  Figure f;
  f.name = "drift-budget";
  f.x_column = "time_s";
  f.y_column = "cumulative_share_percent";
  f.csv_intervals = false;
  f.plot.id = f.name;
  f.plot.title = "Drift budget: share of each source in the predicted horizontal variance";
  f.plot.x = {"time since segment start [s]", Scale::log10, {}, {}};
  f.plot.y = {"share of the predicted horizontal variance [%] (stacked)", Scale::linear, 0.0,
              100.0};
  const std::size_t n = budget.time_s.size();
  if (n >= 2 && budget.time_s.front() > 0.0 && budget.time_s.back() > budget.time_s.front()) {
    f.plot.x.min = budget.time_s.front();  // the bands end where the navigation ends
    f.plot.x.max = budget.time_s.back();
  }
  std::vector<double> below(n, 0.0);
  for (std::size_t g = 0; g < ins::kDriftBudgetTerms; ++g) {
    bool any = false;
    Series s;
    s.x = budget.time_s;
    s.fill_base = below;
    for (std::size_t i = 0; i < n; ++i) {
      const double total = budget.predicted_variance_m2[i];
      const double share = total > 0.0 ? 100.0 * budget.variance_m2[i][g] / total : 0.0;
      any = any || share > 0.0;
      below[i] += share;
      s.y.push_back(below[i]);
    }
    if (!any) continue;
    const auto term = static_cast<ins::DriftBudgetTerm>(g);
    s.name = std::string(ins::symbol_of(term));
    s.color = static_cast<int>(g);
    s.line_width = 1.0;
    s.fill_opacity = 0.55;
    add_series(f, std::move(s), std::string(ins::name_of(term)));
  }
  f.caption =
      "How the predicted horizontal variance σ_N² + σ_E² splits over its independent sources "
      "as the free-inertial time grows: white noise N, bias instability B, rate random walk K, "
      "the fitted Gauss–Markov terms GM, rate ramp R (process noise during navigation), what "
      "the alignment leaves, and the initial heading; each propagated alone, so the bands "
      "stack to 100 %.";
  return f;
}

Figure interval_figure(const std::vector<double>& bin_low_s, const std::vector<double>& bin_high_s,
                       const std::vector<std::int64_t>& counts, double median_interval_s) {
  IMUNOISE_EXPECT(bin_low_s.size() == counts.size() && bin_high_s.size() == counts.size(),
                  "interval histogram: bin edges and counts differ in length");
  Figure f;
  f.name = "sampling-intervals";
  f.x_column = "interval_ms";
  f.y_column = "count";
  f.plot.id = f.name;
  f.plot.title = "Sampling: histogram of the sample intervals";
  f.plot.x = {"sample interval [ms]", Scale::linear, {}, {}};
  f.plot.y = {"number of intervals", Scale::log10, {}, {}};
  f.csv_intervals = false;
  // Stems: an error bar from the axis bottom (low end 0) to the count, so that even a bin far
  // narrower than a pixel (all intervals equal) shows.
  Series stems;
  stems.name = "intervals (gaps excluded)";
  for (std::size_t b = 0; b < counts.size(); ++b) {
    if (counts[b] <= 0) continue;
    const double c = static_cast<double>(counts[b]);
    stems.x.push_back(0.5e3 * (bin_low_s[b] + bin_high_s[b]));
    stems.y.push_back(c);
    stems.y_low.push_back(0.0);
    stems.y_high.push_back(c);
  }
  stems.color = 0;
  stems.line = Line::none;
  stems.marker = Marker::circle;
  add_series(f, std::move(stems), "histogram");
  if (median_interval_s > 0.0 && !counts.empty()) {
    const std::int64_t peak = *std::max_element(counts.begin(), counts.end());
    Series median;
    median.name = "median " + significant_number_text(1e3 * median_interval_s, 6) + " ms";
    median.x = {1e3 * median_interval_s, 1e3 * median_interval_s};
    median.y = {0.5, std::max(1.0, static_cast<double>(peak)) * 2.0};
    median.color = 1;
    median.line = Line::dotted;
    add_series(f, std::move(median), "median");
  }
  if (counts.size() == 1) {
    // All intervals equal: the one bin is 1e-6 of the step wide; show the step around it.
    f.plot.x.min = 1e3 * median_interval_s * 0.9;
    f.plot.x.max = 1e3 * median_interval_s * 1.1;
  }
  f.caption =
      "Distribution of the intervals between consecutive time stamps, gaps excluded: "
      "one stem per equal-width bin, at its centre (the count axis is logarithmic). "
      "A single stem at the median means no jitter.";
  return f;
}

Figure gaps_figure(const std::vector<double>& start_s, const std::vector<double>& length_s,
                   double duration_s, std::int64_t gap_count) {
  IMUNOISE_EXPECT(start_s.size() == length_s.size(),
                  "gap list: start times and lengths differ in length");
  Figure f;
  f.name = "sampling-gaps";
  f.x_column = "time_h";
  f.y_column = "gap_length_s";
  f.plot.id = f.name;
  f.plot.title =
      gap_count == 0 ? "Sampling: gaps (none found)" : "Sampling: gaps in the time stamps";
  f.plot.x = {"time since the first sample [h]", Scale::linear, 0.0,
              duration_s > 0.0 ? std::optional<double>(duration_s / 3600.0) : std::nullopt};
  f.plot.y = {"gap length [s]", Scale::log10, {}, {}};
  Series gaps;
  gaps.name = "gaps (" + std::to_string(gap_count) + ")";
  for (std::size_t i = 0; i < start_s.size(); ++i) {
    gaps.x.push_back(start_s[i] / 3600.0);
    gaps.y.push_back(length_s[i]);
  }
  gaps.color = 1;
  gaps.line = Line::none;
  gaps.marker = Marker::cross;
  add_series(f, std::move(gaps), "gap");
  const std::string factor = shortest_number_text(kGapFactor);
  f.caption = gap_count == 0
                  ? "No interval exceeded the gap limit (" + factor + " × the median interval)."
                  : "Each gap (an interval longer than " + factor +
                        " × the median) by when it started and how long it lasted" +
                        std::string(static_cast<std::size_t>(gap_count) > start_s.size()
                                        ? "; only the first " + std::to_string(start_s.size()) +
                                              " of " + std::to_string(gap_count) + " are listed."
                                        : ".");
  return f;
}

}  // namespace imunoise::report
