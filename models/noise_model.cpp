#include "models/noise_model.h"

namespace imunoise::models {

// SI units of theory.md §1.3, written in ASCII so they survive every terminal and config.
std::string_view term_si_unit(NoiseTerm term, SensorKind kind) {
  const auto unit = [kind](std::string_view gyro_unit, std::string_view accel_unit) {
    return kind == SensorKind::gyro ? gyro_unit : accel_unit;
  };
  switch (term) {
    case NoiseTerm::quantization:
      return unit("rad", "m/s");
    case NoiseTerm::white_noise:
      return unit("rad/s^0.5", "m/s^1.5");
    case NoiseTerm::bias_instability:
      return si_rate_unit(kind);
    case NoiseTerm::random_walk:
      return unit("rad/s^1.5", "m/s^2.5");
    case NoiseTerm::ramp:
      return unit("rad/s^2", "m/s^3");
  }
  return "";
}

NoiseCoefficients AxisModel::coefficients() const {
  NoiseCoefficients c;
  for (NoiseTerm term : kNoiseTerms) coefficient(c, term) = terms[term].value;
  for (const GaussMarkovEstimate& gm : gauss_markov) c.gauss_markov.push_back(gm.value);
  for (const SinusoidEstimate& s : sinusoids) c.sinusoids.push_back(s.value);
  return c;
}

const AxisModel* NoiseModel::find_axis(std::string_view name) const {
  for (const AxisModel& axis : axes) {
    if (axis.name == name) return &axis;
  }
  return nullptr;
}

}  // namespace imunoise::models
