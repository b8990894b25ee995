#include "pipeline/line_findings.h"

#include "common/number_text.h"

namespace imunoise::pipeline {

std::vector<std::string> spectral_line_findings(const models::AxisModel& axis, double confidence) {
  std::vector<std::string> out;
  const char* unit = axis.kind == SensorKind::gyro ? " rad/s" : " m/s^2";
  for (const models::SinusoidEstimate& s : axis.sinusoids) {
    out.push_back(axis.name + ": spectral line at " +
                  significant_number_text(s.value.frequency_hz, 4) + " Hz (amplitude " +
                  significant_number_text(s.value.amplitude, 3) + unit + ", " +
                  significant_number_text(100.0 * confidence, 3) + " % interval " +
                  significant_number_text(s.amplitude_ci_low, 3) + "–" +
                  significant_number_text(s.amplitude_ci_high, 3) +
                  "): a periodic disturbance (vibration, a fan or motor, a power supply, an "
                  "aliased rate); fitted and removed before the Allan fit, listed under "
                  "sinusoids; remove the source or isolate the sensor if it matters");
  }
  return out;
}

}  // namespace imunoise::pipeline
