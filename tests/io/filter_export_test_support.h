/// @file
/// @brief The fixed model of the export tests (theory.md §8's worked example) and the request
/// they make, shared by tests/io/filter_export_test.cpp and filter_export_robotics_test.cpp.
#pragma once

#include <string>

#include "common/units.h"
#include "io/filter_export.h"
#include "models/noise_model.h"

namespace imunoise::io::test_fixture {

using models::AxisModel;
using models::Estimate;
using models::NoiseModel;

inline Estimate estimate(double value, double low, double high) {
  Estimate e;
  e.value = value;
  e.ci_low = low;
  e.ci_high = high;
  e.identified = value > 0.0;
  e.method = "wnnls-oavar";
  return e;
}

inline AxisModel axis(const std::string& name, SensorKind kind, double n, double b, double k) {
  AxisModel a;
  a.name = name;
  a.kind = kind;
  a.terms[static_cast<int>(NoiseTerm::quantization)] = estimate(0.0, 0.0, 0.1 * n);
  a.terms[static_cast<int>(NoiseTerm::white_noise)] = estimate(n, 0.98 * n, 1.02 * n);
  a.terms[static_cast<int>(NoiseTerm::bias_instability)] = estimate(b, 0.9 * b, 1.1 * b);
  a.terms[static_cast<int>(NoiseTerm::random_walk)] = estimate(k, 0.7 * k, 1.4 * k);
  a.terms[static_cast<int>(NoiseTerm::ramp)] = estimate(0.0, 0.0, 0.0);
  a.tau_min_adev_s = 29.6;
  a.fit_tau_min_s = 0.005;
  a.fit_tau_max_s = 3600.0;
  return a;
}

/// The theory.md §8 gyro on all three axes (N = 0.4 deg/√h, B = 25.2 deg/h, K = 84.24
/// deg/h/√h, B → GM (b) of §8.3: σ = 1.314e-4 rad/s, T_c = 15.6 s) and the assumed
/// accelerometer of §8.5 (150 µg/√Hz; B 0.05 mg; K 1e-4 m/s^2.5).
inline NoiseModel worked_example() {
  NoiseModel m;
  m.sensor_name = "theory.md §8 consumer MEMS";
  m.source = "worked-example.csv";
  m.sample_rate_hz = 200.0;
  m.duration_s = 28800.0;
  m.samples = 5760000;
  for (const char* name : {"gyro_x", "gyro_y", "gyro_z"}) {
    auto a = axis(name, SensorKind::gyro, 0.4 * units::kDegPerSqrtHour, 25.2 * units::kDegPerHour,
                  84.24 * units::kDegPerHourPerSqrtHour);
    a.bias_instability_gm.push_back({"peak_match", {1.314e-4, 15.6}});
    m.axes.push_back(a);
  }
  for (const char* name : {"accel_x", "accel_y", "accel_z"})
    m.axes.push_back(axis(name, SensorKind::accel, 150.0 * units::kMicroGPerSqrtHz,
                          0.05 * units::kMilliG, 1e-4));
  return m;
}

inline ExportRequest request(ExportFormat format, double rate_hz = 0.0, bool conservative = false) {
  ExportRequest r;
  r.format = format;
  r.rate_hz = rate_hz;
  r.parameters.conservative = conservative;
  r.model_path = "worked-example.yaml";
  r.command = "imunoise export worked-example.yaml --to " + std::string(export_format_name(format));
  return r;
}

}  // namespace imunoise::io::test_fixture
