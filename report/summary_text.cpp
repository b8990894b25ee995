/// @file
/// @brief The terminal summary of `imunoise analyze` (see summary_text.h).
#include "report/summary_text.h"

#include <algorithm>
#include <cstddef>
#include <sstream>
#include <string>

#include "common/number_text.h"
#include "common/sensor_kind.h"
#include "models/datasheet_units.h"
#include "pipeline/recording.h"
#include "report/verdict.h"

namespace imunoise::report {

namespace {

/// "1.234e-02 [1.1e-02, 1.4e-02]" or "- (< 3e-4)" (not identified, with its upper bound).
std::string estimate_text(const models::Estimate& e, const models::DatasheetUnit& unit) {
  if (!e.identified) {
    if (e.ci_high > 0.0) return "- (< " + significant_number_text(e.ci_high * unit.factor, 2) + ")";
    return "-";
  }
  return significant_number_text(e.value * unit.factor, 4) + " [" +
         significant_number_text(e.ci_low * unit.factor, 3) + ", " +
         significant_number_text(e.ci_high * unit.factor, 3) + "]";
}

}  // namespace

std::string summary_text(const models::NoiseModel& model,
                         const std::optional<std::array<NoiseCoefficients, 6>>& truth,
                         std::string_view model_path) {
  using pipeline::kImuChannelNames;
  std::ostringstream out;
  out << "imunoise analyze: " << model.source << " — " << model.samples << " samples at "
      << significant_number_text(model.sample_rate_hz, 6) << " Hz ("
      << significant_number_text(model.duration_s / 3600.0, 4) << " h); coefficients with "
      << significant_number_text(100.0 * model.confidence, 3)
      << " % intervals, '-' = not identified (upper bound);\n"
      << "ieee952 = the graphical slope read-off of the OADEV curve, for traceability\n";
  out << "\n" << verdict_text(model, model_path);
  out << "\ndetails: per sensor and term each axis\n";
  for (const SensorKind kind : kSensorKinds) {
    out << "\n" << sensor_name(kind) << "\n";
    for (NoiseTerm term : kNoiseTerms) {
      const models::DatasheetUnit unit = models::datasheet_unit(term, kind);
      out << "  " << term_name(term) << " [" << unit.ascii << "]\n";
      for (const models::AxisModel& axis : model.axes) {
        if (axis.kind != kind) continue;
        const models::Estimate& e = axis.terms[term];
        out << "    " << axis.name << ": " << estimate_text(e, unit);
        const double slope = axis.readoff.slope[term];
        if (slope > 0.0) out << "   ieee952 " << significant_number_text(slope * unit.factor, 4);
        if (truth) {
          const std::size_t channel = static_cast<std::size_t>(
              std::find(kImuChannelNames.begin(), kImuChannelNames.end(), axis.name) -
              kImuChannelNames.begin());
          if (channel < 6) {
            const double true_value = coefficient((*truth)[channel], term);
            const bool inside = true_value >= e.ci_low && true_value <= e.ci_high;
            out << "   true " << significant_number_text(true_value * unit.factor, 4)
                << (inside ? "  (inside)" : "  (OUTSIDE)");
          }
        }
        out << "\n";
      }
    }
  }
  return out.str();
}

}  // namespace imunoise::report
