/// @file
/// @brief Chi-square deviation intervals (see confidence.h).
#include "analysis/confidence.h"

#include <cmath>
#include <string>

#include "analysis/chi_square.h"
#include "common/errors.h"

namespace imunoise::analysis {

DeviationInterval deviation_interval(double deviation, double edf, double confidence) {
  IMUNOISE_CHECK(std::isfinite(deviation) && deviation >= 0.0, AnalysisError,
                 "deviation_interval: deviation must be finite and >= 0 (got " +
                     std::to_string(deviation) + ")");
  IMUNOISE_CHECK(
      std::isfinite(edf) && edf > 0.0, AnalysisError,
      "deviation_interval: edf must be finite and > 0 (got " + std::to_string(edf) + ")");
  IMUNOISE_EXPECT(
      confidence > 0.0 && confidence < 1.0,
      "deviation_interval: confidence must be in (0, 1) (got " + std::to_string(confidence) + ")");
  const double tail = 0.5 * (1.0 - confidence);  // probability outside each bound
  // The small chi-square quantile bounds σ² from above and the large one from below.
  const double chi2_low = chi_square_quantile(tail, edf);
  const double chi2_high = chi_square_upper_quantile(tail, edf);
  const double low = deviation * std::sqrt(edf / chi2_high);
  // chi2_low underflows to 0 only for absurdly small edf: the upper bound is then unbounded.
  const double high =
      chi2_low > 0.0 ? deviation * std::sqrt(edf / chi2_low) : (deviation > 0.0 ? HUGE_VAL : 0.0);
  return {low, high};
}

}  // namespace imunoise::analysis
