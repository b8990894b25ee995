#include "io/deviation_curve_text.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

namespace imunoise::io {

namespace {

/// Which EDF model the interval uses, for the table header.
const char* edf_model(analysis::DeviationType type) {
  using analysis::DeviationType;
  switch (type) {
    case DeviationType::totdev:
      return "of SP 1065 (TOTDEV)";
    case DeviationType::mtotdev:
    case DeviationType::ttotdev:
      return "of SP 1065 Table 8 (MTOT)";
    case DeviationType::htotdev:
      return "by Greenhall-Riley (OHDEV model)";
    case DeviationType::theo1:
      return "of SP 1065 (Theo1)";
    default:
      return "by Greenhall-Riley";
  }
}

}  // namespace

nlohmann::ordered_json series_curve_json(const analysis::DeviationCurve& curve,
                                         const SeriesCurveInfo& info) {
  nlohmann::ordered_json out;
  out["type"] = std::string(analysis::to_string(curve.type));
  out["data"] = info.data;
  out["tau0_s"] = curve.tau0_s;
  out["n_samples"] = info.n_samples;
  out["confidence"] = curve.confidence;
  out["tau0_source"] = info.tau0_source;
  out["source"] = info.source;
  out["column"] = info.column;
  out["n_phase"] = curve.n_phase;
  out["non_finite_dropped"] = info.non_finite_dropped;
  const bool time_statistic =
      curve.type == analysis::DeviationType::tdev || curve.type == analysis::DeviationType::ttotdev;
  out["value_unit"] = time_statistic ? "input unit * s" : "input unit";
  out["bias_corrected"] = info.bias_corrected && analysis::cost_grows_with_m(curve.type);
  auto& points = out["points"] = nlohmann::ordered_json::array();
  for (const auto& p : curve.points) {
    points.push_back({{"m", p.m},
                      {"tau_s", p.tau_s},
                      {"value", p.value},
                      {"n_terms", p.n_terms},
                      {"alpha", p.alpha},
                      {"edf", p.edf},
                      {"ci_low", p.ci_low},
                      {"ci_high", p.ci_high}});
  }
  return out;
}

std::string series_curve_table(const analysis::DeviationCurve& curve, const SeriesCurveInfo& info) {
  std::string out = fmt::format(
      "# {} of {} column '{}' ({} data, tau0 = {} s from {}, {} samples, {} phase points)\n"
      "# confidence interval: {:.1f} % two-sided chi-square, EDF {}{}\n",
      analysis::to_string(curve.type), info.source, info.column, info.data, curve.tau0_s,
      info.tau0_source, info.n_samples, curve.n_phase, 100.0 * curve.confidence,
      edf_model(curve.type),
      info.alpha ? fmt::format(", alpha fixed at {}", *info.alpha)
                 : ", alpha identified per tau (lag-1 ACF)");
  if (info.non_finite_dropped > 0) {
    out += fmt::format("# {} NaN/Inf values dropped\n", info.non_finite_dropped);
  }
  out += fmt::format("{:>10} {:>13} {:>10} {:>5} {:>11} {:>13} {:>13} {:>13}\n", "m", "tau_s",
                     "n_terms", "alpha", "edf", "ci_low", "value", "ci_high");
  for (const auto& p : curve.points) {
    out += fmt::format("{:>10} {:>13.6e} {:>10} {:>5} {:>11.4g} {:>13.6e} {:>13.6e} {:>13.6e}\n",
                       p.m, p.tau_s, p.n_terms, p.alpha, p.edf, p.ci_low, p.value, p.ci_high);
  }
  return out;
}

}  // namespace imunoise::io
