/// @file
/// @brief The fit's input and its check against the data: a deviation curve as fit points
/// (EDF capped) and the fraction of points whose interval holds a model (see noise_fit.h).
#include <algorithm>
#include <cmath>
#include <string>

#include "analysis/confidence.h"
#include "analysis/edf.h"
#include "analysis/noise_fit.h"
#include "analysis/noise_terms.h"
#include "common/errors.h"

namespace imunoise::analysis {

std::vector<FitPoint> fit_points(const DeviationCurve& curve) {
  const DeviationType type = curve.type;
  IMUNOISE_EXPECT(type == DeviationType::adev || type == DeviationType::oadev ||
                      type == DeviationType::totdev || type == DeviationType::hdev ||
                      type == DeviationType::ohdev,
                  "fit_points: the noise fit needs an AVAR (adev, oadev, totdev) or HVAR (hdev, "
                  "ohdev) curve, not " +
                      std::string(to_string(type)));
  std::vector<FitPoint> out;
  out.reserve(curve.points.size());
  for (const DeviationPoint& p : curve.points) {
    double cap = 0.0;
    for (int alpha : {0, -1, -2}) cap = std::max(cap, curve_edf(curve, alpha, p.m));
    out.push_back({p.tau_s, p.value * p.value, std::min(p.edf, cap)});
  }
  return out;
}

double fraction_inside_ci(std::span<const FitPoint> points, std::span<const std::size_t> used,
                          const NoiseCoefficients& model, double confidence, bool hadamard) {
  IMUNOISE_EXPECT(!used.empty(), "fraction_inside_ci: no points to check");
  std::size_t inside = 0;
  for (std::size_t k : used) {
    IMUNOISE_EXPECT(k < points.size(), "fraction_inside_ci: index " + std::to_string(k) +
                                           " is out of range (" + std::to_string(points.size()) +
                                           " points)");
    const FitPoint& p = points[k];
    IMUNOISE_CHECK(std::isfinite(p.tau_s) && p.tau_s > 0.0 && std::isfinite(p.avar) &&
                       p.avar >= 0.0 && std::isfinite(p.edf) && p.edf > 0.0,
                   AnalysisError,
                   "fraction_inside_ci: point " + std::to_string(k) +
                       " needs tau > 0, a finite variance >= 0 and edf > 0");
    const double dev = std::sqrt(model_variance(model, p.tau_s, hadamard));
    const DeviationInterval ci = deviation_interval(std::sqrt(p.avar), p.edf, confidence);
    if (dev >= ci.low && dev <= ci.high) ++inside;
  }
  return static_cast<double>(inside) / static_cast<double>(used.size());
}

}  // namespace imunoise::analysis
