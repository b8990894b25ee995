/// @file
/// @brief What `imunoise simulate` simulates, read from a file: a simulator model file
/// (io/simulation_model.h) or a fitted model.yaml (io/noise_model_yaml.h, told apart by its
/// `format:` line), as one SimulationModelFile; and the simulator's ImuNoiseModel of it.
#pragma once

#include <string>

#include "io/simulation_model.h"
#include "models/noise_simulator.h"

namespace imunoise::io {

/// True when PATH is a fitted model.yaml: one of its first 64 lines starts with `format:` and
/// names kModelYamlFormat.
bool is_fitted_model_file(const std::string& path);

/// A fitted model.yaml as a simulation set-up: each of gyro_x … accel_z with its point
/// estimates (terms not identified are 0; fitted Gauss–Markov terms and sinusoids included),
/// `name` "fitted model of SOURCE", its sample rate. No bias or signal: the fitted model
/// describes the noise only. Throws as load_model_yaml.
SimulationModelFile load_fitted_model_as_simulation(const std::string& path);

/// load_fitted_model_as_simulation when PATH is_fitted_model_file, else
/// load_simulation_model.
SimulationModelFile load_simulation_setup(const std::string& path);

/// The simulator's model of SETUP: channel_model of each axis, validated with the axis named
/// "gyro.x" … "accel.z" (models::validate_channel_model, whose errors name it).
models::ImuNoiseModel imu_noise_model(const SimulationModelFile& setup);

}  // namespace imunoise::io
