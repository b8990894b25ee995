#include "pipeline/datasheet_check.h"

#include <cmath>
#include <optional>

#include "common/number_text.h"
#include "models/datasheet_units.h"

namespace imunoise::pipeline {

namespace {

/// The spec's white-noise density of SENSOR [SI], if it states one.
std::optional<double> spec_white_noise(const FleetSpec& spec, SensorKind sensor) {
  for (const SpecLimit& limit : spec.limits)
    if (limit.sensor == sensor && limit.term == NoiseTerm::white_noise) return limit.max_si;
  return std::nullopt;
}

}  // namespace

std::vector<std::string> datasheet_findings(const models::NoiseModel& model,
                                            const FleetSpec& spec) {
  std::vector<std::string> findings;
  for (const models::AxisModel& axis : model.axes) {
    const std::optional<double> density = spec_white_noise(spec, axis.kind);
    const models::Estimate& n = axis.terms[NoiseTerm::white_noise];
    if (!density || !(*density > 0.0) || !n.identified) continue;
    // Judged by the interval's lower end: only a white noise that is above √2 × the datasheet
    // at the interval's level is called a decimation.
    const double ratio_low = n.ci_low / *density;
    if (!(ratio_low >= kDecimationWhiteNoiseRatio)) continue;
    const double ratio = n.value / *density;
    const models::DatasheetUnit unit = models::datasheet_unit(NoiseTerm::white_noise, axis.kind);
    findings.push_back(
        axis.name + ": output likely decimated without averaging: white noise " +
        significant_number_text(n.value * unit.factor, 3) + " " + std::string(unit.ascii) + " is " +
        significant_number_text(ratio, 3) + "x the datasheet's " +
        significant_number_text(*density * unit.factor, 3) + " " + std::string(unit.ascii) +
        (spec.name.empty() ? "" : " (" + spec.name + ")") + " (lower end of its " +
        significant_number_text(100.0 * model.confidence, 3) + " % interval " +
        significant_number_text(ratio_low, 3) + "x), as from a decimation by about " +
        significant_number_text(ratio * ratio, 2) +
        "; cause: samples kept every d-th without averaging fold the internal rate's white "
        "noise into the output band (N grows as sqrt(d); nothing else in the data shows it), "
        "or the unit exceeds its datasheet; remedy: configure the sensor or driver to average "
        "(or filter to the output band) before decimating, or record at the internal rate "
        "and decimate with averaging; a filter built on this model must use the measured N, "
        "not the datasheet's");
  }
  return findings;
}

}  // namespace imunoise::pipeline
