// Tests of io/lcm_messages.h, io/imu_samples.h and io/lcm_log_writer.h: model → noise_model_t →
// bytes → noise_model_t → model keeps every number; curve and drift messages carry their
// series; IMU samples become the same Recording whatever their source; our log writer's files
// read back event-for-event by LCM's own reader (lcm::LogFile).
#include "io/lcm_messages.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <random>
#include <string>
#include <vector>

#include "io/atomic_output.h"
#include "io/lcm_log_writer.h"
#include "pipeline/imu_samples.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using test::error_of;
using ::testing::HasSubstr;

template <typename T>
T encode_decode(const T& message) {
  std::vector<unsigned char> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  EXPECT_EQ(message.encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  T out{};
  EXPECT_EQ(out.decode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  return out;
}

models::NoiseModel random_model(std::uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> value(1e-9, 1e-2);
  models::NoiseModel model;
  model.sensor_name = "unit-test imu";
  model.sample_rate_hz = 200.0;
  model.confidence = 0.9;
  for (std::size_t c = 0; c < 6; ++c) {
    models::AxisModel axis;
    axis.name = pipeline::kImuChannelNames[c];
    axis.kind = c < 3 ? SensorKind::gyro : SensorKind::accel;
    for (std::size_t t = 0; t < 5; ++t) {
      models::Estimate& e = axis.terms[t];
      e.identified = (c + t) % 3 != 0;
      e.value = e.identified ? value(rng) : 0.0;
      e.ci_low = e.value * 0.9;
      e.ci_high = e.identified ? e.value * 1.1 : value(rng);
    }
    if (c % 2 == 0) {
      models::GaussMarkovEstimate gm;
      gm.value.sigma = value(rng);
      gm.value.tau_c_s = 10.0 + static_cast<double>(c);
      axis.gauss_markov.push_back(gm);
    }
    model.axes.push_back(axis);
  }
  return model;
}

TEST(LcmMessages, NoiseModelSurvivesEncodingExactly) {
  const models::NoiseModel model = random_model(7);
  const imunoise::noise_model_t sent = noise_model_message(model, 123456789);
  const models::NoiseModel back = noise_model_from_message(encode_decode(sent));
  EXPECT_EQ(sent.utime, 123456789);
  EXPECT_EQ(back.sensor_name, model.sensor_name);
  EXPECT_EQ(back.sample_rate_hz, model.sample_rate_hz);
  EXPECT_EQ(back.confidence, model.confidence);
  ASSERT_EQ(back.axes.size(), 6u);
  for (std::size_t c = 0; c < 6; ++c) {
    const models::AxisModel& a = model.axes[c];
    const models::AxisModel& b = back.axes[c];
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.kind, a.kind);
    for (std::size_t t = 0; t < 5; ++t) {
      EXPECT_EQ(b.terms[t].value, a.terms[t].value) << a.name << " term " << t;
      EXPECT_EQ(b.terms[t].ci_low, a.terms[t].ci_low);
      EXPECT_EQ(b.terms[t].ci_high, a.terms[t].ci_high);
      EXPECT_EQ(b.terms[t].identified, a.terms[t].identified);
    }
    ASSERT_EQ(b.gauss_markov.size(), a.gauss_markov.size()) << a.name;
    if (!a.gauss_markov.empty()) {
      EXPECT_EQ(b.gauss_markov[0].value.sigma, a.gauss_markov[0].value.sigma);
      EXPECT_EQ(b.gauss_markov[0].value.tau_c_s, a.gauss_markov[0].value.tau_c_s);
    }
  }
}

TEST(LcmMessages, InconsistentNoiseModelMessageIsAnInputError) {
  imunoise::noise_model_t msg = noise_model_message(random_model(3), 0);
  msg.white_noise.pop_back();  // as a broken publisher might send (n_axes says 6)
  EXPECT_THAT(error_of([&] { noise_model_from_message(msg); }),
              HasSubstr("has 5 entries, n_axes is 6"));
}

TEST(LcmMessages, AllanCurveAndDriftMessagesCarryTheirSeries) {
  const std::vector<double> tau_s{0.01, 0.1, 1.0}, deviation{3e-3, 1e-3, 3e-4},
      ci_low{2.9e-3, 0.9e-3, 2e-4}, ci_high{3.1e-3, 1.1e-3, 4e-4};
  analysis::DeviationCurve curve;
  curve.type = analysis::DeviationType::oadev;
  curve.confidence = 0.95;
  for (std::size_t i = 0; i < tau_s.size(); ++i) {
    analysis::DeviationPoint p;
    p.tau_s = tau_s[i];
    p.value = deviation[i];
    p.ci_low = ci_low[i];
    p.ci_high = ci_high[i];
    curve.points.push_back(p);
  }
  const imunoise::allan_curve_t c = encode_decode(allan_curve_message("gyro_y", curve, 42));
  EXPECT_EQ(c.axis_name, "gyro_y");
  EXPECT_EQ(c.statistic, "oadev");
  EXPECT_EQ(c.unit, "rad/s");
  EXPECT_EQ(c.confidence_level, 0.95);
  EXPECT_EQ(c.n, 3);
  EXPECT_EQ(c.tau_s, tau_s);
  EXPECT_EQ(c.deviation, deviation);
  EXPECT_EQ(c.ci_low, ci_low);
  EXPECT_EQ(c.ci_high, ci_high);

  pipeline::DriftSeries drift;
  drift.time_s = {60.0, 300.0};
  drift.predicted_drms_m = {40.0, 5000.0};
  drift.predicted_attitude_sigma_rad = {1e-4, 2e-3};
  imunoise::drift_prediction_t d = encode_decode(drift_prediction_message(drift, 1));
  EXPECT_EQ(d.n, 2);
  EXPECT_TRUE(d.height_hold);
  EXPECT_FALSE(d.has_actual);
  EXPECT_EQ(d.actual_horizontal_m, std::vector<double>(2, 0.0));
  EXPECT_EQ(d.horizontal_sigma_m, drift.predicted_drms_m);
  EXPECT_EQ(d.attitude_sigma_rad, drift.predicted_attitude_sigma_rad);
  drift.recorded_rms_m = {35.0, 6000.0};
  d = encode_decode(drift_prediction_message(drift, 1));
  EXPECT_TRUE(d.has_actual);
  EXPECT_EQ(d.actual_horizontal_m, drift.recorded_rms_m);
}

void keep_model(const lcm::ReceiveBuffer*, const std::string&, const imunoise::noise_model_t* m,
                std::vector<imunoise::noise_model_t>* received) {
  received->push_back(*m);
}

TEST(LcmMessages, NoiseModelCrossesAMemqBus) {
  lcm::LCM bus("memq://");
  ASSERT_TRUE(bus.good());
  std::vector<imunoise::noise_model_t> received;
  bus.subscribeFunction("NOISE_MODEL", &keep_model, &received);
  const models::NoiseModel model = random_model(11);
  const imunoise::noise_model_t sent = noise_model_message(model, 77);
  ASSERT_EQ(bus.publish("NOISE_MODEL", &sent), 0);
  ASSERT_GT(bus.handleTimeout(1000), 0);
  ASSERT_EQ(received.size(), 1u);
  const models::NoiseModel back = noise_model_from_message(received[0]);
  for (std::size_t c = 0; c < 6; ++c) {
    EXPECT_EQ(back.axes[c].terms[1].value, model.axes[c].terms[1].value);
    EXPECT_EQ(back.axes[c].terms[3].ci_high, model.axes[c].terms[3].ci_high);
  }
}

imunoise::imu_sample_t sample(std::int64_t utime, double g, double a, bool increments) {
  imunoise::imu_sample_t m{};
  m.utime = utime;
  m.has_increments = increments;
  for (int i = 0; i < 3; ++i) {
    (increments ? m.delta_angle_rad : m.angular_rate_rad_per_s)[i] = g + i;
    (increments ? m.delta_velocity_m_per_s : m.specific_force_m_per_s2)[i] = a + i;
  }
  return m;
}

TEST(ImuSamples, IncrementsAreDividedByTheMedianPeriod) {
  pipeline::ImuSampleColumns columns;
  for (int k = 0; k < 5; ++k) append_imu_sample(sample(1000 + 10'000 * k, 0.5, 2.0, true), columns);
  EXPECT_TRUE(columns.increments);
  EXPECT_EQ(columns.source_fields[1], "delta_angle_rad[1]");
  EXPECT_EQ(columns.source_units[4], "m/s");
  const pipeline::Recording rec = pipeline::recording_from_imu_samples(columns, "mem", "IMU");
  EXPECT_DOUBLE_EQ(rec.sample_period_s, 0.01);
  ASSERT_NE(rec.find_channel("gyro_y"), nullptr);
  EXPECT_DOUBLE_EQ(rec.find_channel("gyro_y")->values[3], 1.5 / 0.01);
  EXPECT_DOUBLE_EQ(rec.find_channel("accel_z")->values[0], 4.0 / 0.01);
  EXPECT_EQ(rec.find_channel("gyro_x")->source_column, "IMU.delta_angle_rad[0]");
  EXPECT_TRUE(rec.find_channel("gyro_x")->from_increments);
  EXPECT_EQ(rec.find_channel("temperature"), nullptr);  // no sample had one
  EXPECT_DOUBLE_EQ(rec.time_s[4], 0.04);
}

TEST(ImuSamples, TemperatureOnlyWhenEverySampleHasOne) {
  pipeline::ImuSampleColumns all, some;
  for (int k = 0; k < 4; ++k) {
    imunoise::imu_sample_t m = sample(10'000 * k, 0.0, 0.0, false);
    m.has_temperature = true;
    m.temperature_degc = 20.0 + k;
    append_imu_sample(m, all);
    if (k == 2) m.has_temperature = false;
    append_imu_sample(m, some);
  }
  const pipeline::Recording a = pipeline::recording_from_imu_samples(all, "mem", "IMU");
  ASSERT_NE(a.find_channel("temperature"), nullptr);
  EXPECT_EQ(a.find_channel("temperature")->values, (std::vector<double>{20, 21, 22, 23}));
  EXPECT_EQ(pipeline::recording_from_imu_samples(some, "mem", "IMU").find_channel("temperature"),
            nullptr);
}

TEST(ImuSamples, TooFewOrFrozenStampsAreInputErrors) {
  pipeline::ImuSampleColumns one;
  append_imu_sample(sample(5, 0, 0, false), one);
  EXPECT_THAT(error_of([&] { pipeline::recording_from_imu_samples(one, "x.lcmlog", "IMU"); }),
              HasSubstr("too few samples: 1"));
  pipeline::ImuSampleColumns frozen;
  for (int k = 0; k < 3; ++k) append_imu_sample(sample(5, 0, 0, false), frozen);
  EXPECT_THAT(error_of([&] { pipeline::recording_from_imu_samples(frozen, "x.lcmlog", "IMU"); }),
              HasSubstr("never increase"));
}

TEST(LcmLogWriter, LcmOwnReaderSeesEveryEventAsWritten) {
  const auto dir = test::make_temp_dir("lcm_writer");
  const std::string path = (dir / "w.lcmlog").string();
  std::vector<std::vector<unsigned char>> payloads;
  std::mt19937 rng(5);
  {
    AtomicOutputFile file(path);
    LcmLogWriter writer(file.stream());
    for (int k = 0; k < 50; ++k) {
      std::vector<unsigned char> data(static_cast<std::size_t>(k * 7 % 300));
      for (auto& b : data) b = static_cast<unsigned char>(rng());
      writer.write(k % 2 ? "IMU" : "OTHER_CHANNEL", 1'700'000'000'000'000 + 2500 * k, data);
      payloads.push_back(data);
    }
    EXPECT_EQ(writer.events(), 50);
    file.commit();
  }
  lcm::LogFile log(path, "r");
  ASSERT_TRUE(log.good());
  for (int k = 0; k < 50; ++k) {
    const lcm::LogEvent* e = log.readNextEvent();
    ASSERT_NE(e, nullptr) << k;
    EXPECT_EQ(e->eventnum, k);
    EXPECT_EQ(e->timestamp, 1'700'000'000'000'000 + 2500 * k);
    EXPECT_EQ(e->channel, k % 2 ? "IMU" : "OTHER_CHANNEL");
    ASSERT_EQ(static_cast<std::size_t>(e->datalen), payloads[k].size());
    EXPECT_TRUE(std::equal(payloads[k].begin(), payloads[k].end(),
                           static_cast<const unsigned char*>(e->data)));
  }
  EXPECT_EQ(log.readNextEvent(), nullptr);
}

}  // namespace
}  // namespace imunoise::io
