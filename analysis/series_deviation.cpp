#include "analysis/series_deviation.h"

#include <cstdint>
#include <string>
#include <vector>

#include "common/errors.h"

namespace imunoise::analysis {

std::size_t min_series_values(SeriesKind kind) { return kind == SeriesKind::kPhase ? 2 : 1; }

DeviationCurve series_deviation(std::span<const double> values, SeriesKind kind, double tau0_s,
                                const TauGridSpec& grid, const DeviationOptions& options,
                                std::string_view where) {
  IMUNOISE_EXPECT(values.size() >= min_series_values(kind),
                  "series_deviation: fewer values than min_series_values");
  const std::vector<double> phase =
      kind == SeriesKind::kPhase ? detrended_phase(values) : phase_from_rate(values, tau0_s);
  std::vector<std::int64_t> factors;
  try {
    factors = averaging_factors(grid, options.type, static_cast<std::int64_t>(phase.size()));
  } catch (const AnalysisError& e) {
    throw AnalysisError(std::string(where) + ": " + e.what());
  }
  return compute_deviation(phase, tau0_s, factors, options);
}

}  // namespace imunoise::analysis
