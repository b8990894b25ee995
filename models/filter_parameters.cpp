#include "models/filter_parameters.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>

#include "common/errors.h"
#include "common/number_text.h"

namespace imunoise::models {
namespace {

constexpr double kFlickerAvarFactor = 2.0 * std::numbers::ln2 / std::numbers::pi;  // §4.1

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

/// The coefficient the options ask for: the point value, or the upper end of its interval.
double chosen(const Estimate& e, bool conservative) {
  return conservative ? std::max(e.value, e.ci_high) : e.value;
}

/// The GM that stands for B (or the largest fitted GM), scaled to the chosen B.
GaussMarkov bias_as_gm(const AxisModel& axis, double chosen_b, const FilterParameterOptions& o) {
  if (chosen_b > 0.0) {
    const double fitted_b = axis.terms[static_cast<int>(NoiseTerm::bias_instability)].value;
    for (const auto& stored : axis.bias_instability_gm) {
      // All three conventions are linear in B at a fixed τ_min, so the stored conversion of
      // the point value scales to the upper bound ((a) scales its measured minimum ADEV).
      if (stored.convention == name_of(o.gm_convention) && fitted_b > 0.0)
        return {stored.value.sigma * chosen_b / fitted_b, stored.value.tau_c_s};
    }
    if (!(axis.tau_min_adev_s > 0.0))
      throw InputError(axis.name +
                       ": bias instability needs fit.tau_of_min_adev_s > 0 for its "
                       "Gauss-Markov form (theory.md §4.4)");
    return gauss_markov_from_bias_instability(chosen_b, axis.tau_min_adev_s, o.gm_convention);
  }
  const GaussMarkovEstimate* largest = nullptr;
  for (const auto& gm : axis.gauss_markov)
    if (largest == nullptr || gm.value.sigma > largest->value.sigma) largest = &gm;
  if (largest == nullptr) return {};
  const double sigma = o.conservative ? std::max(largest->value.sigma, largest->sigma_ci_high)
                                      : largest->value.sigma;
  return {sigma, largest->value.tau_c_s};
}

/// Whether the upper bound of T may stand in for it on AXIS when it is not identified (best
/// estimates): B only without a fitted GM (which then stands for the bias) and with a τ of the
/// ADEV minimum (its GM form needs one).
bool may_bound(const AxisModel& axis, NoiseTerm t) {
  if (t != NoiseTerm::bias_instability) return true;
  return axis.gauss_markov.empty() && axis.tau_min_adev_s > 0.0;
}

SensorAxisParameters one_axis(const AxisModel& axis, const FilterParameterOptions& o) {
  SensorAxisParameters p;
  p.from = axis.name;
  for (NoiseTerm t : kNoiseTerms) {
    const Estimate& e = axis.terms[t];
    double v = chosen(e, o.conservative);
    if (!e.identified) {
      UnidentifiedTerm u{axis.name, t, e.ci_high > 0.0 ? e.ci_high : 0.0, false};
      if (!o.conservative && o.upper_bound_when_not_identified && !(e.value > 0.0) &&
          u.upper_bound > 0.0 && may_bound(axis, t))
        v = u.upper_bound;
      u.substituted = u.upper_bound > 0.0 && v == u.upper_bound;
      p.unidentified.push_back(u);
    }
    coefficient(p, t) = v;
  }
  p.bias_gm = bias_as_gm(axis, p.bias_instability, o);
  if (!o.conservative) {
    p.rw_only_white_noise = p.white_noise;
    p.rw_only_random_walk = p.random_walk;
    return p;
  }
  NoiseCoefficients c = p;  // the five chosen terms; the upper GM terms follow
  for (const auto& gm : axis.gauss_markov)
    c.gauss_markov.push_back({std::max(gm.value.sigma, gm.sigma_ci_high), gm.value.tau_c_s});
  double t = o.correction_interval_s > 0.0 ? o.correction_interval_s : axis.tau_min_adev_s;
  if (c.bias_instability > 0.0 && !(t > 0.0))
    throw InputError(axis.name +
                     ": the conservative fold of bias instability needs a correction interval (" +
                     o.setting_names.correction_interval + ") or fit.tau_of_min_adev_s > 0");
  if (!(t > 0.0)) t = 1.0;  // no B: T only decides where a GM is folded
  if (c.ramp > 0.0 && !(axis.fit_tau_max_s > 0.0))
    throw InputError(axis.name + ": the conservative fold of the ramp needs fit.tau_max_s > 0");
  const auto fold = fold_into_random_walk(c, t, o.filter_rate_hz, axis.fit_tau_max_s);
  p.rw_only_white_noise = fold.white_noise;
  p.rw_only_random_walk = fold.random_walk;
  return p;
}

/// Combines the axes of one sensor by the axis rule.
SensorParameters combine(const std::vector<SensorAxisParameters>& axes, SensorKind kind,
                         AxisChoice choice) {
  SensorParameters out;
  out.kind = kind;
  if (choice == AxisChoice::each) {
    for (int i = 0; i < 3; ++i) out.axes[i] = axes[i];
    return out;
  }
  SensorAxisParameters p;
  for (const auto& a : axes)
    p.unidentified.insert(p.unidentified.end(), a.unidentified.begin(), a.unidentified.end());
  std::string names;
  for (const auto& a : axes) names += (names.empty() ? "" : ", ") + a.from;
  using Member = double SensorAxisParameters::*;
  const std::initializer_list<Member> members = {&SensorAxisParameters::quantization,
                                                 &SensorAxisParameters::white_noise,
                                                 &SensorAxisParameters::bias_instability,
                                                 &SensorAxisParameters::random_walk,
                                                 &SensorAxisParameters::ramp,
                                                 &SensorAxisParameters::rw_only_white_noise,
                                                 &SensorAxisParameters::rw_only_random_walk};
  const double n = static_cast<double>(axes.size());
  if (choice == AxisChoice::worst) {
    p.from = "largest of " + names;
    for (auto m : members)
      for (const auto& a : axes) p.*m = std::max(p.*m, a.*m);
    for (const auto& a : axes)
      if (a.bias_gm.sigma > p.bias_gm.sigma) p.bias_gm = a.bias_gm;
  } else {  // mean: root mean square, i.e. the mean variance
    p.from = "root mean square of " + names;
    for (auto m : members) {
      double sum = 0.0;
      for (const auto& a : axes) sum += a.*m * a.*m;
      p.*m = std::sqrt(sum / n);
    }
    double sum = 0.0, tau_sum = 0.0;
    int with_gm = 0;
    for (const auto& a : axes) {
      sum += a.bias_gm.sigma * a.bias_gm.sigma;
      if (a.bias_gm.sigma > 0.0) {
        tau_sum += a.bias_gm.tau_c_s;
        ++with_gm;
      }
    }
    p.bias_gm.sigma = std::sqrt(sum / n);
    p.bias_gm.tau_c_s = with_gm > 0 ? tau_sum / with_gm : 0.0;
  }
  out.axes.fill(p);
  return out;
}

std::optional<SensorParameters> sensor_parameters(const NoiseModel& model, SensorKind kind,
                                                  const FilterParameterOptions& o,
                                                  std::vector<std::string>& rules) {
  std::vector<const AxisModel*> axes;
  for (const auto& a : model.axes)
    if (a.kind == kind) axes.push_back(&a);
  if (axes.empty()) return std::nullopt;
  const std::string sensor(sensor_name(kind));
  // x, y, z order by name suffix where the names say it (model order otherwise).
  std::stable_sort(axes.begin(), axes.end(), [](const AxisModel* a, const AxisModel* b) {
    const auto rank = [](const std::string& n) {
      return ends_with(n, "_x") ? 0 : ends_with(n, "_y") ? 1 : ends_with(n, "_z") ? 2 : 3;
    };
    return rank(a->name) < rank(b->name);
  });
  if (o.axis == AxisChoice::x || o.axis == AxisChoice::y || o.axis == AxisChoice::z) {
    const char* suffix = o.axis == AxisChoice::x ? "_x" : o.axis == AxisChoice::y ? "_y" : "_z";
    const auto it = std::find_if(axes.begin(), axes.end(),
                                 [&](const AxisModel* a) { return ends_with(a->name, suffix); });
    if (it == axes.end())
      throw InputError("the model has no " + sensor + " axis named *" + suffix + " (" +
                       o.setting_names.axis + ")");
    axes = {*it};
  }
  if (o.axis == AxisChoice::each && axes.size() != 3)
    throw InputError(o.setting_names.axis + " each needs three " + sensor +
                     " axes; the model has " + std::to_string(axes.size()));
  std::vector<SensorAxisParameters> per_axis;
  for (const AxisModel* a : axes) per_axis.push_back(one_axis(*a, o));
  auto out = combine(per_axis, kind,
                     o.axis == AxisChoice::each ? AxisChoice::each
                     : axes.size() == 1         ? AxisChoice::worst
                                                : o.axis);
  if (axes.size() == 1) out.axes.fill(per_axis[0]);
  rules.push_back(
      sensor + " values from " +
      (o.axis == AxisChoice::each ? std::string("each axis separately") : out.one().from));
  return out;
}

}  // namespace

RandomWalkFold fold_into_random_walk(const NoiseCoefficients& c, double correction_interval_s,
                                     double filter_rate_hz, double horizon_s) {
  // one_axis() has refused a model or options without them (InputError naming the model key).
  IMUNOISE_EXPECT(correction_interval_s > 0.0 && std::isfinite(correction_interval_s),
                  "fold_into_random_walk: correction interval must be > 0, got " +
                      shortest_number_text(correction_interval_s));
  IMUNOISE_EXPECT(!(c.quantization > 0.0) || filter_rate_hz > 0.0,
                  "fold_into_random_walk: the quantization fold needs a rate > 0");
  IMUNOISE_EXPECT(!(c.ramp > 0.0) || horizon_s > 0.0,
                  "fold_into_random_walk: the ramp fold needs a horizon > 0");
  const double t = correction_interval_s;
  double n2 = c.white_noise * c.white_noise;
  double k2 = c.random_walk * c.random_walk;
  const double floor = kFlickerAvarFactor * c.bias_instability * c.bias_instability;
  n2 += floor * t;
  k2 += 3.0 * floor / t;
  for (const auto& gm : c.gauss_markov) {
    if (gm.tau_c_s <= t)
      n2 += 2.0 * gm.sigma * gm.sigma * gm.tau_c_s;
    else
      k2 += 2.0 * gm.sigma * gm.sigma / gm.tau_c_s;
  }
  if (c.quantization > 0.0) n2 += 3.0 * c.quantization * c.quantization * filter_rate_hz;
  if (c.ramp > 0.0) k2 += 1.5 * c.ramp * c.ramp * horizon_s;
  return {std::sqrt(n2), std::sqrt(k2)};
}

SensorAxisParameters axis_filter_parameters(const AxisModel& axis,
                                            const FilterParameterOptions& options) {
  return one_axis(axis, options);
}

FilterParameters select_filter_parameters(const NoiseModel& model,
                                          const FilterParameterOptions& options) {
  if (!(options.filter_rate_hz > 0.0) || !std::isfinite(options.filter_rate_hz))
    throw InputError("the filter rate must be > 0 Hz, got " +
                     shortest_number_text(options.filter_rate_hz));
  FilterParameters out;
  out.rules.push_back(options.conservative
                          ? "values: conservative — the upper end of each " +
                                shortest_number_text(100.0 * model.confidence) +
                                " % interval (a term not identified: its upper bound)"
                      : options.upper_bound_when_not_identified
                          ? "values: best estimates (the point values of the model; a term not "
                            "identified: its upper bound)"
                          : "values: best estimates (the point values of the model)");
  out.gyro = sensor_parameters(model, SensorKind::gyro, options, out.rules);
  out.accel = sensor_parameters(model, SensorKind::accel, options, out.rules);
  out.rules.push_back(std::string("bias instability as one Gauss-Markov term: convention ") +
                      std::string(name_of(options.gm_convention)) +
                      " (theory.md §4.4); without B, the largest fitted GM term");
  if (options.conservative)
    out.rules.push_back(
        "white + random-walk only filters: N'^2 = N^2 + (2 ln2/pi) B^2 T + 3 Q^2 rate"
        " [+ 2 sigma^2 T_c per GM with T_c <= T], K'^2 = K^2 + 3 (2 ln2/pi) B^2 / T"
        " + 1.5 R^2 T_h [+ 2 sigma^2 / T_c per GM with T_c > T]; T = " +
        (options.correction_interval_s > 0.0
             ? shortest_number_text(options.correction_interval_s) + " s (" +
                   options.setting_names.correction_interval + ")"
             : std::string("each axis's tau of the ADEV minimum")) +
        ", T_h = longest fitted tau; the exported AVAR N'^2/tau + K'^2 tau/3 is >= the "
        "model's for 1/rate <= tau <= T_h");
  return out;
}

const std::map<std::string, AxisChoice, std::less<>>& axis_choices_by_name() {
  static const std::map<std::string, AxisChoice, std::less<>> map{
      {"worst", AxisChoice::worst}, {"mean", AxisChoice::mean}, {"x", AxisChoice::x},
      {"y", AxisChoice::y},         {"z", AxisChoice::z},       {"each", AxisChoice::each}};
  return map;
}

}  // namespace imunoise::models
