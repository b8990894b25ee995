/// @file
/// @brief The datasheet spec of `imunoise fleet --spec FILE`: per sensor and term a maximum in
/// datasheet units (the units of models/datasheet_units.h, named in each key), its reader and
/// its writer. Example:
///
///     # imunoise fleet spec
///     name: ACME IMU-100 datasheet rev B
///     gyro:
///       arw_deg_per_sqrt_h: 0.15
///       bias_instability_deg_per_h: 10
///     accel:
///       vrw_ug_per_sqrt_hz: 80
///
/// Keys per sensor — gyro: quantization_urad, arw_deg_per_sqrt_h, bias_instability_deg_per_h,
/// rrw_deg_per_h_per_sqrt_h, ramp_deg_per_h2; accel: quantization_mm_per_s, vrw_ug_per_sqrt_hz,
/// bias_instability_ug, rw_m_per_s_per_h_per_sqrt_h, ramp_ug_per_h. Every maximum is finite and
/// > 0; an unknown or repeated key is an error at its line.
#pragma once

#include <string>
#include <string_view>

#include "common/noise_term.h"
#include "common/sensor_kind.h"
#include "pipeline/fleet.h"

namespace imunoise::io {

/// The spec key of TERM for SENSOR (e.g. "arw_deg_per_sqrt_h").
std::string_view fleet_spec_key(SensorKind sensor, NoiseTerm term);

/// Parses the spec TEXT; SOURCE names it in errors. Maxima are returned in SI.
/// @throws InputError "SOURCE:line:column: problem".
pipeline::FleetSpec parse_fleet_spec(const std::string& text, const std::string& source);

/// Reads the spec file PATH (as parse_fleet_spec).
pipeline::FleetSpec read_fleet_spec(const std::string& path);

/// The text of SPEC in this format (maxima back in datasheet units, round-trip digits).
std::string fleet_spec_text(const pipeline::FleetSpec& spec);

}  // namespace imunoise::io
