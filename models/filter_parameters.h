/// @file
/// @brief From a fitted NoiseModel to the few numbers a filter config holds: one value per
/// sensor (or per axis) for each coefficient, chosen by an explicit axis rule, as best
/// estimates or as a documented overbound (theory.md §6.4), plus the representations a
/// filter can carry — white + random-walk bias only (Kalibr family) or white + one
/// Gauss–Markov bias (KF-GINS, gnss-ins-sim). SI in and out; every choice made is returned
/// as a line of text so the exported file can say what was done.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/noise_coefficients.h"
#include "models/bias_instability_gm.h"
#include "models/noise_model.h"

namespace imunoise::models {

/// How the three axes of a sensor become the value(s) a config holds.
enum class AxisChoice {
  worst,  ///< per coefficient the largest over x, y, z (GM: the axis with the largest σ)
  mean,   ///< per coefficient the root mean square over the axes (the mean variance)
  x,
  y,
  z,    ///< that axis only
  each  ///< every axis its own value (for formats with per-axis slots)
};

/// Every axis rule by the name settings use for it: worst, mean, x, y, z, each.
const std::map<std::string, AxisChoice, std::less<>>& axis_choices_by_name();

/// How the messages and the rule lines of select_filter_parameters() name the settings a caller
/// offers its user. The defaults name the options; the CLI passes its flags.
struct FilterSettingNames {
  std::string axis = "axis";                                  ///< `export --axis`
  std::string correction_interval = "correction_interval_s";  ///< `export --correction-interval`
};

struct FilterParameterOptions {
  AxisChoice axis = AxisChoice::worst;
  /// false: point estimates. true: the upper end of each coefficient's interval (for terms
  /// not identified, their upper bound), and terms a format cannot carry folded into the
  /// ones it can so the exported AVAR is ≥ the model's (rules in fold_into_random_walk()).
  bool conservative = false;
  /// Which single GM stands for bias instability B (theory.md §4.4 (a)–(c)).
  GmConvention gm_convention = GmConvention::peak_match;
  /// T of the B fold (the filter's correction interval) [s]; 0 = the axis's τ of the ADEV
  /// minimum, where the floor is reached.
  double correction_interval_s = 0.0;
  /// The rate the filter runs at [Hz], > 0: bounds the quantization fold (τ ≥ 1/rate).
  double filter_rate_hz = 0.0;
  /// false: a term not identified keeps its value 0 in the best estimates. true: its upper
  /// bound (Estimate::ci_high, when > 0) takes its place, so a short recording (K not
  /// identified) still gives every term a usable number; B is bounded so only when the axis has
  /// no fitted GM term and a τ of the ADEV minimum for its GM form. Each substitution is listed
  /// in SensorAxisParameters::unidentified. Conservative sets always use upper bounds.
  bool upper_bound_when_not_identified = false;
  FilterSettingNames setting_names;  ///< the names messages and rule lines give axis and T
};

/// A term of a model axis that is not identified (Estimate::identified false).
struct UnidentifiedTerm {
  std::string axis;  ///< the model axis, e.g. "gyro_x"
  NoiseTerm term = NoiseTerm::random_walk;
  double upper_bound = 0.0;  ///< the model's ci_high for it [SI]; 0: the model has none
  bool substituted = false;  ///< true: upper_bound is the value used in its place
};

/// The numbers of one axis slot of one sensor (SI: rad… for a gyro, m/s… for an accel).
/// The NoiseCoefficients part holds Q, N, B, K, R as chosen (best or upper); its Gauss–Markov
/// terms and sinusoids are not used (GM terms reach a config as bias_gm or folded).
struct SensorAxisParameters : NoiseCoefficients {
  std::string from;  ///< which model axes gave these values, e.g. "max of gyro_x, gyro_y"
  /// B (or, without B, the largest fitted GM) as one first-order GM; σ = 0 when neither.
  GaussMarkov bias_gm;
  /// White density and RW density for a filter with only those two (Kalibr, VINS, …):
  /// best = N, K; conservative = N, K with B, GM, Q and R folded in.
  double rw_only_white_noise = 0.0, rw_only_random_walk = 0.0;
  /// The terms not identified on the axes these values come from (every axis combined).
  std::vector<UnidentifiedTerm> unidentified;
};

/// One sensor (gyro or accel): slot 0, 1, 2 = x, y, z (all three equal unless `each`).
struct SensorParameters {
  SensorKind kind = SensorKind::gyro;  ///< which sensor the three slots are of
  std::array<SensorAxisParameters, 3> axes;
  const SensorAxisParameters& one() const { return axes[0]; }
};

struct FilterParameters {
  std::optional<SensorParameters> gyro, accel;  ///< absent when the model has no such axes
  std::vector<std::string> rules;  ///< every selection/overbound rule applied, one per line
};

/// The parameters of one model axis under OPTIONS (the axis rule is not used): best or upper
/// values, B as one GM by the convention, and the white + RW pair.
/// @throws InputError as select_filter_parameters().
SensorAxisParameters axis_filter_parameters(const AxisModel& axis,
                                            const FilterParameterOptions& options);

/// The parameters of MODEL under OPTIONS.
/// @throws InputError when OPTIONS asks for an axis the model lacks, the GM conversion of B
///   needs τ of the ADEV minimum and the model has none, or filter_rate_hz ≤ 0 (the model's
///   sample rate or the user's).
FilterParameters select_filter_parameters(const NoiseModel& model,
                                          const FilterParameterOptions& options);

/// White density and RW density whose AVAR N'²/τ + K'²τ/3 overbounds the AVAR of C
/// (theory.md §4.1), used for conservative exports to white + RW filters:
///   B:  N'² += (2 ln2/π)B²·T, K'² += 3(2 ln2/π)B²/T  → covers the floor at every τ
///       (the N part for τ ≤ T, the K part for τ ≥ T);
///   GM: AVAR_GM ≤ 2σ²T_c/τ and ≤ (2/3)σ²τ/T_c at every τ, so add 2σ²T_c to N'² when
///       T_c ≤ T, else 2σ²/T_c to K'² (each alone bounds the GM everywhere);
///   Q:  3Q²/τ² ≤ 3Q²·rate/τ for τ ≥ 1/rate → N'² += 3Q²·rate;
///   R:  R²τ²/2 ≤ (R²·T_h/2)τ for τ ≤ T_h → K'² += 1.5·R²·T_h (T_h = longest fitted τ).
/// Sinusoids are not folded (they are deterministic; the PSD shows them).
/// @throws ContractViolation unless correction_interval_s > 0, filter_rate_hz > 0 when Q > 0
///   and horizon_s > 0 when R > 0.
struct RandomWalkFold {
  double white_noise = 0.0, random_walk = 0.0;
};
RandomWalkFold fold_into_random_walk(const NoiseCoefficients& c, double correction_interval_s,
                                     double filter_rate_hz, double horizon_s);

}  // namespace imunoise::models
