#include "io/simulation_setup.h"

#include <array>
#include <fstream>
#include <string_view>

#include "io/noise_model_yaml.h"

namespace imunoise::io {

namespace {

constexpr std::array<std::string_view, 3> kAxes{"x", "y", "z"};

}  // namespace

bool is_fitted_model_file(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (int i = 0; i < 64 && std::getline(in, line); ++i) {
    if (line.rfind("format:", 0) == 0) return line.find(kModelYamlFormat) != std::string::npos;
  }
  return false;
}

SimulationModelFile load_fitted_model_as_simulation(const std::string& path) {
  const models::NoiseModel fitted = load_model_yaml(path);
  SimulationModelFile setup;
  setup.source = path;
  setup.name = "fitted model of " + fitted.source;
  setup.sample_rate_hz = fitted.sample_rate_hz;
  for (std::size_t a = 0; a < 3; ++a) {
    for (const SensorKind kind : kSensorKinds) {
      const std::string name = std::string(sensor_name(kind)) + "_" + std::string(kAxes[a]);
      const models::AxisModel* axis = fitted.find_axis(name);
      if (axis == nullptr) continue;
      (kind == SensorKind::gyro ? setup.gyro : setup.accel)[a].coefficients = axis->coefficients();
    }
  }
  return setup;
}

SimulationModelFile load_simulation_setup(const std::string& path) {
  return is_fitted_model_file(path) ? load_fitted_model_as_simulation(path)
                                    : load_simulation_model(path);
}

models::ImuNoiseModel imu_noise_model(const SimulationModelFile& setup) {
  const auto validated = [](const SimulationAxis& axis, const std::string& where) {
    models::ChannelNoiseModel model = channel_model(axis);
    models::validate_channel_model(model, where);
    return model;
  };
  models::ImuNoiseModel model;
  for (std::size_t a = 0; a < 3; ++a) {
    model.gyro[a] = validated(setup.gyro[a], "gyro." + std::string(kAxes[a]));
    model.accel[a] = validated(setup.accel[a], "accel." + std::string(kAxes[a]));
  }
  return model;
}

}  // namespace imunoise::io
