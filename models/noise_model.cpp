#include "models/noise_model.h"

namespace imunoise::models {

std::string_view term_name(Term term) {
  switch (term) {
    case Term::quantization:
      return "quantization";
    case Term::white_noise:
      return "white_noise";
    case Term::bias_instability:
      return "bias_instability";
    case Term::random_walk:
      return "random_walk";
    case Term::ramp:
      return "ramp";
  }
  return "unknown";
}

// SI units of theory.md §1.3, written in ASCII so they survive every terminal and config.
std::string_view term_si_unit(Term term, bool gyro) {
  switch (term) {
    case Term::quantization:
      return gyro ? "rad" : "m/s";
    case Term::white_noise:
      return gyro ? "rad/s^0.5" : "m/s^1.5";
    case Term::bias_instability:
      return gyro ? "rad/s" : "m/s^2";
    case Term::random_walk:
      return gyro ? "rad/s^1.5" : "m/s^2.5";
    case Term::ramp:
      return gyro ? "rad/s^2" : "m/s^3";
  }
  return "";
}

double& coefficient(NoiseCoefficients& c, Term term) {
  switch (term) {
    case Term::quantization:
      return c.quantization;
    case Term::white_noise:
      return c.white_noise;
    case Term::bias_instability:
      return c.bias_instability;
    case Term::random_walk:
      return c.random_walk;
    case Term::ramp:
      break;
  }
  return c.ramp;
}

double coefficient(const NoiseCoefficients& c, Term term) {
  return coefficient(const_cast<NoiseCoefficients&>(c), term);
}

NoiseCoefficients AxisModel::coefficients() const {
  NoiseCoefficients c;
  for (Term term : kTerms) coefficient(c, term) = terms[static_cast<std::size_t>(term)].value;
  for (const GaussMarkovEstimate& gm : gauss_markov) c.gauss_markov.push_back(gm.value);
  c.sinusoids = sinusoids;
  return c;
}

const AxisModel* NoiseModel::find_axis(std::string_view name) const {
  for (const AxisModel& axis : axes) {
    if (axis.name == name) return &axis;
  }
  return nullptr;
}

}  // namespace imunoise::models
