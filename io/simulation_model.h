/// @file
/// @brief The YAML model file of `imunoise simulate`: per-axis noise terms of a 6-axis IMU,
/// each term given in one of several datasheet units named in its key and converted once to
/// SI here (common/units.h, theory.md §1.3). Full key list with SI factors:
/// docs/simulation-model.md.
///
/// Schema (unknown keys are errors that list the accepted ones):
/// @code{.yaml}
/// name: demo consumer MEMS IMU        # optional, echoed in the CSV header
/// sample_rate_hz: 100                 # optional default for --rate
/// flicker_band_s: [0.01, 7200]        # optional; default [1/rate, duration]
/// gyro:                               # terms shared by x, y, z ...
///   arw_deg_per_sqrt_h: 0.4           # = arw_rad_per_sqrt_s: 1.16355e-4
///   bias_instability_deg_per_h: 25.2
///   rrw_rad_per_s_sqrt_s: 6.80678e-6
///   gauss_markov: [{sigma_deg_per_h: 20, tau_c_s: 30}]
///   sinusoids: [{amplitude_deg_per_s: 0.01, frequency_hz: 2.5, phase_rad: 0}]
///   x: {bias_deg_per_s: 0.1}          # ... and per-axis overrides (a list replaces the list)
/// accel:
///   vrw_ug_per_sqrt_hz: 150           # two-sided density, theory.md §1.2
///   z: {specific_force_g: -1}         # level FRD: z down, f = −g₀
/// @endcode
///
/// Term keys, alternatives separated by '|', the SI one first:
/// - gyro: `quantization_rad|quantization_deg|quantization_urad`,
///   `arw_rad_per_sqrt_s|arw_deg_per_sqrt_h|arw_deg_per_s_per_sqrt_hz`,
///   `bias_instability_rad_per_s|bias_instability_deg_per_h|bias_instability_deg_per_s`,
///   `rrw_rad_per_s_sqrt_s|rrw_deg_per_h_per_sqrt_h|rrw_deg_per_s_per_sqrt_s`,
///   `ramp_rad_per_s2|ramp_deg_per_h2|ramp_deg_per_s_per_h`,
///   `bias_rad_per_s|bias_deg_per_h|bias_deg_per_s`,
///   `angular_rate_rad_per_s|angular_rate_deg_per_s`, `output_lsb_rad_per_s|output_lsb_deg_per_s`;
///   in gauss_markov items `sigma_rad_per_s|sigma_deg_per_h|sigma_deg_per_s`, in sinusoids
///   `amplitude_rad_per_s|amplitude_deg_per_h|amplitude_deg_per_s`.
/// - accel: `quantization_m_per_s`,
///   `vrw_m_per_s_sqrt_s|vrw_m_per_s_per_sqrt_h|vrw_ug_per_sqrt_hz`,
///   `bias_instability_m_per_s2|bias_instability_ug|bias_instability_mg`,
///   `rw_m_per_s2_sqrt_s|rw_m_per_s_per_h_per_sqrt_h|rw_ug_per_sqrt_s`,
///   `ramp_m_per_s3|ramp_m_per_s2_per_h`, `bias_m_per_s2|bias_mg|bias_ug`,
///   `specific_force_m_per_s2|specific_force_g`, `output_lsb_m_per_s2|output_lsb_mg`;
///   in gauss_markov items `sigma_m_per_s2|sigma_ug|sigma_mg`, in sinusoids
///   `amplitude_m_per_s2|amplitude_ug|amplitude_mg`.
/// - both: gauss_markov items `tau_c_s|tau_c_h`; sinusoid items `frequency_hz`,
///   `phase_rad|phase_deg` (optional, default 0).
/// Ramps, biases, signals, amplitudes and phases may be negative; every other value must be
/// ≥ 0 (τ_c and the sample rate > 0). One term given twice in one mapping, in the same or
/// in different units, is an error naming both keys.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "common/noise_coefficients.h"
#include "common/sensor_kind.h"
#include "models/noise_simulator.h"

namespace imunoise::io {

/// One axis of the model file, SI units (gyro rad, rad/s; accelerometer m/s, m/s²).
struct SimulationAxis {
  NoiseCoefficients coefficients;  ///< Q, N, B, K, R, Gauss–Markov terms, sinusoids
  double bias = 0.0;               ///< constant turn-on bias [rad/s | m/s²]
  double signal = 0.0;             ///< true angular rate / specific force [rad/s | m/s²]
  double output_lsb = 0.0;  ///< step of the output rounding quantizer [rad/s | m/s²]; 0 = off
};

/// A model file, every value in SI.
struct SimulationModelFile {
  std::string source;                    ///< the path it was read from
  std::string name;                      ///< `name`, newlines replaced by spaces; "" if absent
  std::optional<double> sample_rate_hz;  ///< `sample_rate_hz` [Hz]
  std::optional<models::FlickerBand> flicker_band;  ///< `flicker_band_s` [s]
  std::array<SimulationAxis, 3> gyro;               ///< x, y, z
  std::array<SimulationAxis, 3> accel;              ///< x, y, z
};

/// Reads a model file. Throws InputError "FILE:LINE:COL: KEY.PATH: what" on a syntax error,
/// an unknown key (listing the accepted ones), a term given twice, a value that is not a
/// finite number or out of range; "FILE: cannot open the model file" if it cannot be read.
SimulationModelFile load_simulation_model(const std::string& path);

/// As load_simulation_model, from YAML text; SOURCE_NAME stands for the file in messages.
SimulationModelFile parse_simulation_model(const std::string& yaml_text,
                                           const std::string& source_name);

/// The simulator's model of AXIS: its coefficients, constant = bias + signal, output LSB.
models::ChannelNoiseModel channel_model(const SimulationAxis& axis);

/// The non-zero terms of AXIS under their SI keys, each preceded by a space, e.g.
/// " arw_rad_per_sqrt_s=0.000116355 bias_rad_per_s=0.002", or " (no terms)".
std::string si_terms_text(const SimulationAxis& axis, SensorKind kind);

}  // namespace imunoise::io
