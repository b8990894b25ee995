/// @file
/// @brief The fitted stochastic model of a 6-axis IMU — the single source of every export
/// (native model.yaml, filter configs, state models, LCM). SI units inside (theory.md §1.3);
/// each coefficient carries its 95 % interval, the method that produced it and whether the
/// data identified it at all.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/noise_coefficients.h"
#include "common/sensor_kind.h"

namespace imunoise::models {

/// SI unit of a term for a gyro (rad…) or an accelerometer (m/s…), e.g. "rad/s^0.5".
std::string_view term_si_unit(NoiseTerm term, SensorKind kind);

/// One estimated coefficient [SI unit of its term].
struct Estimate {
  double value = 0.0;           ///< point estimate; 0 when not identified
  double ci_low = 0.0;          ///< lower end of the interval (≥ 0)
  double ci_high = 0.0;         ///< upper end; for a term not identified, an upper bound
  bool identified = false;      ///< false: the data do not show this term ("0 = not identified")
  std::string method;           ///< e.g. "wnnls-oavar" (theory.md §4.3)
  std::string interval_method;  ///< e.g. "parametric bootstrap, 50 replicates"
};

/// A Gauss–Markov term with intervals on σ and T_c.
struct GaussMarkovEstimate {
  GaussMarkov value;
  double sigma_ci_low = 0.0, sigma_ci_high = 0.0;  ///< [rad/s | m/s²]
  double tau_c_ci_low_s = 0.0, tau_c_ci_high_s = 0.0;
};

/// A sinusoid (spectral line) with the interval on its amplitude.
struct SinusoidEstimate {
  Sinusoid value;
  double amplitude_ci_low = 0.0;   ///< [rad/s | m/s²]; equal to the amplitude when no interval
  double amplitude_ci_high = 0.0;  ///< [rad/s | m/s²]
};

/// One B → Gauss–Markov conversion (theory.md §4.4), named by its convention.
struct BiasInstabilityGm {
  std::string convention;  ///< "min_adev_at_tau_min" (a), "peak_match" (b), "sigma_equals_b" (c)
  GaussMarkov value;
};

/// Traceability values of the graphical methods (not the estimator), 0 = not found.
struct ReadoffValues {
  PerTerm<double> slope{};  ///< IEEE-952 slope read-off on the OADEV curve
  PerTerm<double> psd{};    ///< PSD read-off (theory.md §5.3)
};

/// The model of one axis.
struct AxisModel {
  std::string name;                    ///< gyro_x … accel_z
  SensorKind kind = SensorKind::gyro;  ///< gyro (rad/s) or accelerometer (m/s²)
  PerTerm<Estimate> terms;
  std::vector<GaussMarkovEstimate> gauss_markov;  ///< fitted GM terms (if any)
  /// The σ of one more GM term the data exclude, per T_c over the fitted τ range (a GM term
  /// the fit does not hold lies below the curve at the confidence of the model); empty when
  /// not computed.
  std::vector<GaussMarkovBound> gauss_markov_bounds;
  std::vector<SinusoidEstimate> sinusoids;             ///< fitted sinusoids (if any)
  std::vector<BiasInstabilityGm> bias_instability_gm;  ///< B as one GM, each convention
  std::vector<GaussMarkov> multi_gm;  ///< B as 2–4 GMs (theory.md §4.4 "preferred"); empty if B = 0
  double multi_gm_fraction_inside_ci = 0.0;  ///< fraction of fitted τ whose model ADEV with
                                             ///< multi_gm lies inside the point's 95 % CI
  double tau_min_adev_s = 0.0;  ///< τ of the ADEV minimum (used by the B → GM conversions)
  double fit_tau_min_s = 0.0, fit_tau_max_s = 0.0;  ///< τ range of the fit
  std::string fit_note;                             ///< model selection / range notes
  ReadoffValues readoff;
  std::optional<bool> psd_check_pass;  ///< model PSD vs measured PSD (theory.md §5.4)
  std::string psd_check_note;

  /// Point values as a NoiseCoefficients (GM terms included; B kept as flicker).
  NoiseCoefficients coefficients() const;
};

/// The model of the whole IMU.
struct NoiseModel {
  std::string sensor_name;  ///< free text (e.g. the input file's name)
  std::string source;       ///< the recording it was fitted from
  double sample_rate_hz = 0.0;
  double duration_s = 0.0;
  std::int64_t samples = 0;
  double confidence = 0.95;               ///< level of every [ci_low, ci_high]
  std::vector<AxisModel> axes;            ///< usually gyro_x … accel_z
  std::vector<std::string> data_quality;  ///< sampling findings, one line each
  std::string software = "imunoise";

  const AxisModel* find_axis(std::string_view name) const;
};

}  // namespace imunoise::models
