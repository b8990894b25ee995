/// @file
/// @brief Writing a simulated recording (`imunoise simulate -o FILE`), generated in blocks so
/// that memory stays constant for any duration: a CSV in SI units with a '#' header naming the
/// model, seed and terms; an LCM log of imunoise.imu_sample_t (.lcmlog); or an imunoise binary
/// recording (.imnb) whose header holds what converting the CSV output would give.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

#include "common/progress_callback.h"
#include "io/binary_recording.h"
#include "io/simulation_model.h"
#include "models/noise_simulator.h"

namespace imunoise::io {

/// The output formats, told by the output's file name.
enum class SimulationOutputFormat { kCsv, kLcmLog, kBinary };

/// kBinary for a name ending in kBinaryRecordingExtension (.imnb), kLcmLog for one ending in
/// .lcmlog, else kCsv.
SimulationOutputFormat simulation_output_format(const std::string& path);

/// Rate, length and seed of one simulation.
struct SimulationRun {
  double sample_rate_hz = 0.0;       ///< f_s = 1/τ0 [Hz], > 0
  double duration_s = 0.0;           ///< requested length [s], as the header states it
  std::int64_t samples = 0;          ///< samples per channel, ≥ 1
  std::uint64_t seed = 1;            ///< master seed of the simulator
  models::FlickerBand flicker_band;  ///< band of the bias-instability construction [s]
};

/// The run of SETUP at RATE_HZ for DURATION_S in SAMPLES samples (the caller checks them) with
/// SEED; the flicker band is the setup's `flicker_band_s`, else [1/rate, max(duration, 2/rate)].
SimulationRun simulation_run(const SimulationModelFile& setup, double rate_hz, double duration_s,
                             std::int64_t samples, std::uint64_t seed);

/// The simulator of SETUP (imu_noise_model, whose errors name the axis) for RUN.
models::ImuSimulator make_simulator(const SimulationModelFile& setup, const SimulationRun& run);

/// The sample period a read of the CSV output finds: the median of the intervals between the
/// stamps k / RATE_HZ (k < SAMPLES) as pipeline::analyze_timing takes it (mean of the two
/// middle values for an even count; on the stamps' decimal grid when they have one, so 400 Hz
/// gives 0.0025 exactly); 1 / RATE_HZ for a single sample.
double simulated_sample_period_s(double rate_hz, std::int64_t samples);

/// Header of a binary output: what converting the CSV output would give (channels gyro_x …
/// accel_z from the CSV's SI columns, time_s, simulated_sample_period_s), SETUP's source as
/// source_path.
BinaryRecordingHeader simulation_binary_header(const SimulationModelFile& setup,
                                               const SimulationRun& run);

/// The '#' header of a CSV output (source and name, seed, rate, duration, samples, flicker
/// band, every non-zero term per channel under its SI key) and its column line
/// time_s,gyro_x_rad_per_s,…,accel_z_m_per_s2.
void write_simulation_csv_header(std::ostream& out, const SimulationModelFile& setup,
                                 const SimulationRun& run);

/// Generates RUN.samples samples of SIMULATOR (made by make_simulator for RUN) block by block
/// and writes them atomically to PATH in simulation_output_format(PATH): CSV rows of shortest
/// round-trip numbers (io/recording_csv_writer.h), LCM events on LCM_CHANNEL stamped in whole
/// µs from 0, or binary columns. PROGRESS (optional) gets ("generating", samples done,
/// RUN.samples) once per block. Throws InputError naming PATH when it cannot be written.
void write_simulation(models::ImuSimulator& simulator, const SimulationModelFile& setup,
                      const SimulationRun& run, const std::string& path,
                      const std::string& lcm_channel, const ProgressCallback& progress = {});

}  // namespace imunoise::io
