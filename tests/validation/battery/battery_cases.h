/// @file
/// @brief The classes of the validation battery (three sensor grades and one class per
/// phenomenon of issue 20) and the truth of each case: the coefficients in imunoise's
/// conventions (the fields of common/noise_coefficients.h, theory.md §1.3/§4.1, SI units)
/// that a correct estimator should report for the recording the generator makes, including
/// the effect of each phenomenon (derivations in docs/validation.md). Own structs: like the
/// generator, this file uses no imunoise code.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "battery/generator.h"

namespace imunoise::battery {

/// A spectral line of the truth, with the SNR it was placed at.
struct TruthLine {
  double amplitude = 0.0;     ///< A [rad/s | m/s²]
  double frequency_hz = 0.0;  ///< f [Hz]
  double phase_rad = 0.0;     ///< φ at t = 0 [rad]
  double snr = 0.0;           ///< line power A²/2 over the continuum S₁(f)·16/T (see .cpp)
};

/// What a correct estimator should report for one channel (SI; 0 = the term is absent).
struct ChannelTruth {
  std::string name;  ///< gyro_x … accel_z
  bool gyro = true;
  double quantization = 0.0;      ///< Q [rad | m/s]
  double white_noise = 0.0;       ///< N [rad/√s | m/s/√s]
  double bias_instability = 0.0;  ///< B [rad/s | m/s²]
  double random_walk = 0.0;       ///< K [rad/s^{3/2} | m/s^{5/2}]
  double ramp = 0.0;              ///< R [rad/s² | m/s³]
  std::vector<GaussMarkovSpec> gauss_markov;
  std::vector<TruthLine> lines;
  /// N of the samples as they are, before the estimator's remedy (differs from white_noise
  /// with outliers kept: N·√(1 + p k²)); informational.
  double white_noise_as_recorded = 0.0;
  double temperature_coefficient = 0.0;  ///< d(bias)/dT [rate/°C] (temperature class)
};

/// The phenomena a case carries (each should produce its data-quality finding).
enum class Phenomenon { warmup, outliers, low_pass, decimation, stamps, lsb, lines, temperature };
inline constexpr std::array<Phenomenon, 8> kPhenomena = {
    Phenomenon::warmup, Phenomenon::outliers, Phenomenon::low_pass, Phenomenon::decimation,
    Phenomenon::stamps, Phenomenon::lsb,      Phenomenon::lines,    Phenomenon::temperature};
/// "warmup", "outliers", "low_pass", "decimation", "stamps", "lsb", "lines", "temperature".
const char* phenomenon_name(Phenomenon p);

/// One recording of the battery: how to generate it and what the truth is.
struct BatteryCase {
  std::string class_name;
  std::string grade;        ///< consumer, industrial, tactical
  std::string description;  ///< one line for the tables
  std::uint64_t seed = 0;   ///< the battery seed (spec.seed is derived from it and the class)
  RecordingSpec spec;
  std::array<ChannelTruth, 6> truth;
  std::vector<Phenomenon> phenomena;
  bool write_stamps = false;  ///< write the stamps (as CSV with a time column), else a fixed rate
  /// The grade's datasheet as `imunoise fleet --spec` reads it: the nominal white-noise density
  /// of each sensor (the x axis, before any phenomenon), which the runner gives `analyze --spec`
  /// (a decimation without averaging is visible only against it).
  std::string datasheet;
};

/// Sizes: `full` is the closing-note battery, `reduced` the ctest one (rate ≤ 100 Hz, 20 min),
/// `long_record` every class at rate ≤ 100 Hz for at least 6 h (the drift validation of
/// issue 25: free-inertial segments up to 30 min, judged on each half).
enum class BatterySize { full, reduced, long_record };

/// The class names, in table order.
std::vector<std::string> battery_classes();

/// The case of class NAME at SIZE for SEED (seeds 1, 2, … give independent recordings; the
/// generator seed mixes in the class name, so classes never share a stream either).
/// @throws std::invalid_argument for an unknown class.
BatteryCase make_case(const std::string& name, BatterySize size, std::uint64_t seed);

/// @name The truth's AVAR in imunoise's continuous conventions (theory.md §4.1)
/// @{
double truth_avar(const ChannelTruth& t, double tau_s);
/// Share of K²τ/3 in truth_avar at τ (for "K carries ≥ 60 % of the AVAR at T/10").
double random_walk_share(const ChannelTruth& t, double tau_s);
/// Continuum one-sided PSD S₁(f) of the truth without lines (theory.md §5.3).
double truth_psd(const ChannelTruth& t, double f_hz, double tau0_s);
/// @}

}  // namespace imunoise::battery
