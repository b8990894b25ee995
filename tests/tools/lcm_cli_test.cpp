// Process-level tests of the LCM side of the CLI (issue 6): simulate → .lcmlog, analyze/allan
// on a log (same numbers as on the CSV of the same samples), publish through the file://
// provider (decoded with LCM's own reader), live replaying a log through file:// (the model it
// publishes equals `analyze` on the log), live's tolerance of bad traffic and its clean stop on
// SIGTERM, and the end-to-end run over real UDP multicast inside a private network namespace
// (lcm-logger records what publish sends; lcm-logplayer feeds live).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <imunoise/allan_curve_t.hpp>
#include <imunoise/imu_sample_t.hpp>
#include <imunoise/noise_model_t.hpp>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <usertest/scalar_imu_t.hpp>
#include <vector>

#include "io/lcm_messages.h"
#include "io/noise_model_yaml.h"
#include "lcm_test_support.h"
#include "test_support.h"

namespace imunoise {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

std::string shell_quoted(const std::string& s) { return "'" + s + "'"; }
std::string shell_quoted(const fs::path& p) { return shell_quoted(p.string()); }

/// Runs a shell command, capturing stdout and stderr.
test::CommandResult run_shell(const std::string& command, const fs::path& dir) {
  const fs::path out = dir / "shell.out", err = dir / "shell.err";
  const int status = std::system(
      ("(" + command + ") >" + shell_quoted(out) + " 2>" + shell_quoted(err) + " </dev/null")
          .c_str());
  test::CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  const auto slurp = [](const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

struct Event {
  std::string channel;
  std::vector<unsigned char> data;
};

/// Every event of an LCM log, read with LCM's own reader.
std::vector<Event> read_events(const fs::path& path) {
  lcm::LogFile log(path.string(), "r");
  EXPECT_TRUE(log.good()) << path;
  std::vector<Event> events;
  if (!log.good()) return events;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    const auto* bytes = static_cast<const unsigned char*>(e->data);
    events.push_back({e->channel, std::vector<unsigned char>(bytes, bytes + e->datalen)});
  }
  return events;
}

template <typename T>
T decode(const Event& e) {
  T m{};
  EXPECT_EQ(m.decode(e.data.data(), 0, static_cast<int>(e.data.size())),
            static_cast<int>(e.data.size()))
      << "event on " << e.channel;
  return m;
}

/// Every coefficient, interval and flag of two models equal (bit for bit).
void expect_same_coefficients(const models::NoiseModel& a, const models::NoiseModel& b) {
  ASSERT_EQ(a.axes.size(), b.axes.size());
  for (std::size_t i = 0; i < a.axes.size(); ++i) {
    EXPECT_EQ(a.axes[i].name, b.axes[i].name);
    for (std::size_t t = 0; t < 5; ++t) {
      EXPECT_EQ(a.axes[i].terms[t].value, b.axes[i].terms[t].value) << a.axes[i].name << " " << t;
      EXPECT_EQ(a.axes[i].terms[t].ci_low, b.axes[i].terms[t].ci_low);
      EXPECT_EQ(a.axes[i].terms[t].ci_high, b.axes[i].terms[t].ci_high);
      EXPECT_EQ(a.axes[i].terms[t].identified, b.axes[i].terms[t].identified);
    }
  }
}

/// One simulated recording (120 s at 100 Hz, reference IMU) as CSV and as an LCM log, and the
/// analysis of the log, shared by the tests below.
class LcmCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(test::make_temp_dir("lcm_cli"));
    const std::string model =
        shell_quoted(fs::path(IMUNOISE_SOURCE_DIR) / "configs/reference-imu.yaml");
    for (const char* name : {"rec.lcmlog", "rec.csv"}) {
      const auto r =
          test::run_imunoise("simulate " + model + " --duration 120s --rate 100 --seed 11 -o " +
                             shell_quoted(*dir_ / name));
      ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    const auto r = test::run_imunoise("analyze " + shell_quoted(*dir_ / "rec.lcmlog") + " -q " +
                                      kAnalysisFlags + " -o " + shell_quoted(*dir_ / "a_log"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  static void TearDownTestSuite() { delete dir_; }
  static const fs::path& dir() { return *dir_; }
  static inline const std::string kAnalysisFlags = "--bootstrap 4 --seed 9";

 private:
  static inline fs::path* dir_ = nullptr;
};

TEST_F(LcmCli, AnalyzeOnTheLogMatchesTheCsvOfTheSameSamples) {
  const auto r = test::run_imunoise("analyze " + shell_quoted(dir() / "rec.csv") + " -q " +
                                    kAnalysisFlags + " -o " + shell_quoted(dir() / "a_csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const models::NoiseModel from_log = io::load_model_yaml((dir() / "a_log/model.yaml").string());
  const models::NoiseModel from_csv = io::load_model_yaml((dir() / "a_csv/model.yaml").string());
  EXPECT_EQ(from_log.samples, 12000);
  // The CSV stores t = k/100 s as text, the log whole µs; both give the same median period,
  // and the values are the same doubles (shortest round-trip text vs raw IEEE bytes).
  EXPECT_EQ(from_log.sample_rate_hz, from_csv.sample_rate_hz);
  expect_same_coefficients(from_log, from_csv);
}

TEST_F(LcmCli, AllanReadsOneChannelOfTheLog) {
  const auto log = test::run_imunoise("allan " + shell_quoted(dir() / "rec.lcmlog") +
                                      " --channel IMU --column accel_y --taus decade --json");
  const auto csv = test::run_imunoise("allan " + shell_quoted(dir() / "rec.csv") +
                                      " --column accel_y_m_per_s2 --taus decade --json");
  ASSERT_EQ(log.exit_code, 0) << log.err;
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  const auto points = [](const std::string& json) { return json.substr(json.find("\"points\"")); };
  EXPECT_EQ(points(log.out), points(csv.out));
  const auto wrong = test::run_imunoise("allan " + shell_quoted(dir() / "rec.lcmlog") +
                                        " --channel NOPE --column accel_y");
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_THAT(wrong.err, HasSubstr("channel 'NOPE' not found; the log holds 'IMU' "
                                   "(imunoise.imu_sample_t, 12000 events)"));
}

TEST_F(LcmCli, AnalyzeExplainsAWrongChannelAndACorruptLog) {
  auto r = test::run_imunoise("analyze " + shell_quoted(dir() / "rec.lcmlog") +
                              " --channel GPS -o " + shell_quoted(dir() / "x"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("channel 'GPS' not found"));
  EXPECT_FALSE(fs::exists(dir() / "x/model.yaml"));
  // Cut the log in the middle of an event.
  const fs::path cut = dir() / "cut.lcmlog";
  fs::copy_file(dir() / "rec.lcmlog", cut, fs::copy_options::overwrite_existing);
  fs::resize_file(cut, fs::file_size(cut) - 17);
  r = test::run_imunoise("analyze " + shell_quoted(cut) + " -o " + shell_quoted(dir() / "y"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("cut.lcmlog: byte offset"));
  EXPECT_THAT(r.err, HasSubstr("truncated event"));
  EXPECT_FALSE(fs::exists(dir() / "y/model.yaml"));
}

TEST_F(LcmCli, PublishThroughTheFileProviderDecodesToTheSameNumbers) {
  const fs::path drift = dir() / "drift_envelope.csv";
  {
    std::ofstream out(drift);
    out << "time_s,predicted_north_sigma_m,predicted_east_sigma_m,predicted_horizontal_drms_m,"
           "predicted_horizontal_velocity_drms_m_per_s,predicted_roll_sigma_deg,"
           "predicted_pitch_sigma_deg,predicted_heading_sigma_deg,actual_rms_horizontal_error_m\n"
           "60,30,40,50,1,0.3,0.4,1.2,45\n300,3000,4000,5000,10,3,4,12,5500\n";
  }
  const fs::path log = dir() / "published.lcmlog";
  const auto r = test::run_imunoise(
      "publish " + shell_quoted(dir() / "a_log/model.yaml") + " --curves " +
      shell_quoted(dir() / "a_log/allan.csv") + " --drift " + shell_quoted(drift) + " --lcm-url " +
      shell_quoted("file://" + log.string() + "?mode=w") + " --channel MY_MODEL");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<Event> events = read_events(log);
  ASSERT_EQ(events.size(), 1u + 12u + 1u);  // model, OADEV + OHDEV × 6 axes, drift
  ASSERT_EQ(events[0].channel, "MY_MODEL");
  const models::NoiseModel sent =
      io::noise_model_from_message(decode<imunoise::noise_model_t>(events[0]));
  const models::NoiseModel file = io::load_model_yaml((dir() / "a_log/model.yaml").string());
  expect_same_coefficients(sent, file);
  EXPECT_EQ(sent.sample_rate_hz, file.sample_rate_hz);
  EXPECT_EQ(sent.sensor_name, "rec.lcmlog");

  // Curves: the gyro_x OADEV equals the allan.csv column, read here independently.
  const auto rows = test::read_csv_rows(dir() / "a_log/allan.csv");
  const auto& header = rows.front();
  const auto column = std::find(header.begin(), header.end(), "gyro_x_oadev_rad_per_s");
  ASSERT_NE(column, header.end());
  const auto col = static_cast<std::size_t>(column - header.begin());
  std::vector<double> expected;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    if (!rows[i][col].empty()) expected.push_back(std::stod(rows[i][col]));
  }
  const auto curve = decode<imunoise::allan_curve_t>(events[1]);
  EXPECT_EQ(events[1].channel, "ALLAN_CURVE");
  EXPECT_EQ(curve.axis_name, "gyro_x");
  EXPECT_EQ(curve.statistic, "oadev");
  EXPECT_EQ(curve.unit, "rad/s");
  EXPECT_EQ(curve.deviation, expected);

  const auto d = decode<imunoise::drift_prediction_t>(events[13]);
  EXPECT_EQ(events[13].channel, "DRIFT_PREDICTION");
  ASSERT_EQ(d.n, 2);
  EXPECT_EQ(d.time_s, (std::vector<double>{60, 300}));
  EXPECT_EQ(d.horizontal_sigma_m, (std::vector<double>{50, 5000}));
  EXPECT_NEAR(d.attitude_sigma_rad[0], 1.3 * M_PI / 180.0, 1e-15);  // √(.3²+.4²+1.2²) = 1.3°
  EXPECT_NEAR(d.attitude_sigma_rad[1], 13.0 * M_PI / 180.0, 1e-14);
  EXPECT_TRUE(d.has_actual);
  EXPECT_EQ(d.actual_horizontal_m, (std::vector<double>{45, 5500}));
}

TEST_F(LcmCli, PublishRejectsBadInputBeforeSendingAnything) {
  const fs::path log = dir() / "never.lcmlog";
  const fs::path bad = dir() / "bad_allan.csv";
  std::ofstream(bad) << "m,tau_s,gyro_x_oadev_rad_per_s\n1,0.01,abc\n";
  const auto r = test::run_imunoise("publish " + shell_quoted(dir() / "a_log/model.yaml") +
                                    " --curves " + shell_quoted(bad) + " --lcm-url " +
                                    shell_quoted("file://" + log.string() + "?mode=w"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("bad_allan.csv:2"));
  EXPECT_FALSE(fs::exists(log));
  const auto replay = test::run_imunoise(
      "live --lcm-url " + shell_quoted("file://" + (dir() / "rec.lcmlog").string() + "?speed=0"));
  EXPECT_EQ(replay.exit_code, 2);
  EXPECT_THAT(replay.err, HasSubstr("cannot be published to: give --publish-url"));
  const auto url = test::run_imunoise("publish " + shell_quoted(dir() / "a_log/model.yaml") +
                                      " --lcm-url 'nosuch://x'");
  EXPECT_EQ(url.exit_code, 2);
  EXPECT_THAT(url.err, HasSubstr("--lcm-url 'nosuch://x': LCM could not start"));
}

TEST_F(LcmCli, LiveReplayingTheLogPublishesTheModelOfAnalyze) {
  const fs::path out = dir() / "live_published.lcmlog";
  const auto r = test::run_imunoise(
      "live --channel IMU --lcm-url " +
      shell_quoted("file://" + (dir() / "rec.lcmlog").string() + "?speed=0") + " --publish-url " +
      shell_quoted("file://" + out.string() + "?mode=w") + " --window 1h --every 50s " +
      kAnalysisFlags + " -o " + shell_quoted(dir() / "live"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("stopped (end of input); received 12000, accepted 12000"));
  const models::NoiseModel analyzed = io::load_model_yaml((dir() / "a_log/model.yaml").string());
  const models::NoiseModel live = io::load_model_yaml((dir() / "live/model.yaml").string());
  EXPECT_EQ(live.samples, 12000);
  expect_same_coefficients(live, analyzed);
  // The last model on the bus is the final one.
  const std::vector<Event> events = read_events(out);
  const Event* last_model = nullptr;
  int models_published = 0;
  for (const Event& e : events) {
    if (e.channel == "NOISE_MODEL") {
      last_model = &e;
      ++models_published;
    }
  }
  ASSERT_NE(last_model, nullptr);
  EXPECT_GE(models_published, 2);  // at 50 s of data, and at the end (120 s)
  expect_same_coefficients(
      io::noise_model_from_message(decode<imunoise::noise_model_t>(*last_model)), analyzed);
}

TEST_F(LcmCli, LiveCountsBadTrafficAndKeepsGoing) {
  const fs::path path = dir() / "messy.lcmlog";
  {
    test::LcmLogFileWriter log(path);
    std::int64_t event = 0;
    const auto put = [&](const std::string& channel, const test::LcmBytes& data) {
      log.write_raw(channel, data, 1'000'000 + 10'000 * event++);
    };
    const auto encoded = [](const auto& m) { return test::lcm_encode(m); };
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 1e-3);
    const auto good = [&](std::int64_t k) {
      imunoise::imu_sample_t m{};
      m.utime = 10'000 * k;
      for (int a = 0; a < 3; ++a) {
        m.angular_rate_rad_per_s[a] = noise(rng);
        m.specific_force_m_per_s2[a] = noise(rng) + (a == 2 ? -9.8 : 0.0);
      }
      return m;
    };
    for (std::int64_t k = 0; k < 3000; ++k) {
      put("IMU", encoded(good(k)));
      if (k == 100) {
        auto bytes = encoded(good(k));
        bytes.resize(bytes.size() / 2);
        put("IMU", bytes);  // truncated
      }
      if (k == 200) put("IMU", encoded(io::noise_model_message(models::NoiseModel{}, 0)));
      if (k == 300) {
        auto m = good(k);
        m.angular_rate_rad_per_s[1] = std::numeric_limits<double>::quiet_NaN();
        put("IMU", encoded(m));  // same stamp too, but the NaN is seen first
      }
      if (k == 400) put("IMU", encoded(good(k - 50)));  // out of order
      if (k == 500) put("IMU", encoded(good(k)));       // duplicate stamp
      if (k == 600) {
        auto m = good(k);
        m.utime += 1;
        m.has_increments = true;
        put("IMU", encoded(m));  // switches to increments
      }
      if (k == 700) put("OTHER", {1, 2, 3});  // other channels are not ours to judge
    }
    // The sender restarts with its clock back at 0: after 100 rejected samples live starts
    // a new window instead of rejecting the new stream for ever.
    for (std::int64_t k = 0; k < 2000; ++k) put("IMU", encoded(good(k - 200'000)));
  }
  const auto r = test::run_imunoise(
      "live --channel IMU --lcm-url " + shell_quoted("file://" + path.string() + "?speed=0") +
      " --publish-url " +
      shell_quoted("file://" + (dir() / "messy_out.lcmlog").string() + "?mode=w") +
      " --every 10s --bootstrap 0 -o " + shell_quoted(dir() / "messy"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("received 5006, accepted 4901, undecodable 2, non-finite 1, "
                               "out of order 101, rate/increment switches 1"));
  EXPECT_THAT(r.out, HasSubstr("restarts 1"));
  EXPECT_TRUE(fs::exists(dir() / "messy/model.yaml"));
  // The last model is of the new stream: 2000 − 99 rejected before the restart.
  EXPECT_EQ(io::load_model_yaml((dir() / "messy/model.yaml").string()).samples, 1901);
}

TEST_F(LcmCli, LiveStopsCleanlyOnSigterm) {
  // Real-time replay (speed 1) of a 120 s log: live is mid-stream when SIGTERM arrives.
  const std::string command =
      "'" + test::imunoise_binary() + "' live --channel IMU --lcm-url " +
      shell_quoted("file://" + (dir() / "rec.lcmlog").string() + "?speed=1") + " --publish-url " +
      shell_quoted("file://" + (dir() / "term_out.lcmlog").string() + "?mode=w") +
      " --every 1000s --bootstrap 0 & pid=$!; sleep 2; kill -TERM $pid; wait $pid";
  const auto r = run_shell(command, dir());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("stopped (signal)"));
  // About 2 s of data arrived (not the whole log), and one final analysis ran on it.
  EXPECT_THAT(r.out, ::testing::Not(HasSubstr("received 12000")));
  EXPECT_THAT(r.out, HasSubstr("analyses 1, failed 0"));
}

/// Writes MESSAGES on CHANNEL with lcm::LogFile, 10 ms apart.
template <typename T>
void write_log(const fs::path& path, const std::string& channel, const std::vector<T>& messages) {
  test::LcmLogFileWriter log(path);
  std::int64_t n = 0;
  for (const T& m : messages) log.write(channel, m, 1'700'000'000'000'000 + 10'000 * n++);
}

TEST_F(LcmCli, AUsersOwnTypeIsMappedByTheColumnFlags) {
  // The same samples as a user type (deg/s, g, int64 ns stamps, one field per axis) and as
  // imunoise.imu_sample_t in SI: every statistic must agree exactly.
  std::mt19937 rng(21);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<usertest::scalar_imu_t> user;
  std::vector<imunoise::imu_sample_t> si;
  constexpr double kDegToRad = M_PI / 180.0, kG = 9.80665;
  for (std::int64_t k = 0; k < 4000; ++k) {
    usertest::scalar_imu_t u{};
    u.timestamp_ns = 1'700'000'000'000'000'000 + 10'000'000 * k;
    u.gx = noise(rng), u.gy = noise(rng) + 0.2, u.gz = noise(rng);
    u.ax = noise(rng) * 1e-2, u.ay = noise(rng) * 1e-2, u.az = -1.0 + noise(rng) * 1e-2;
    u.temperature = 25.0f;
    u.sequence = static_cast<std::int32_t>(k);
    user.push_back(u);
    imunoise::imu_sample_t m{};
    m.utime = 1'700'000'000'000'000 + 10'000 * k;
    const double g[3] = {u.gx, u.gy, u.gz}, a[3] = {u.ax, u.ay, u.az};
    for (int i = 0; i < 3; ++i) {
      m.angular_rate_rad_per_s[i] = g[i] * kDegToRad;
      m.specific_force_m_per_s2[i] = a[i] * kG;
    }
    si.push_back(m);
  }
  write_log(dir() / "user.lcmlog", "SCALAR_IMU", user);
  write_log(dir() / "si.lcmlog", "IMU", si);
  const std::string type = shell_quoted(fs::path(IMUNOISE_SOURCE_DIR) /
                                        "tests/io/lcm_user_types/usertest_scalar_imu.lcm");
  const std::string mapping =
      " --lcm-type " + type +
      " --time-col timestamp_ns --time-unit ns --gyro-cols gx,gy,gz --gyro-unit deg/s "
      "--accel-cols ax,ay,az --accel-unit g";
  // No --channel: the log's only channel of the user's type (found by its fingerprint).
  const auto mine = test::run_imunoise("analyze " + shell_quoted(dir() / "user.lcmlog") + mapping +
                                       " -q --bootstrap 0 -o " + shell_quoted(dir() / "user"));
  const auto ref = test::run_imunoise("analyze " + shell_quoted(dir() / "si.lcmlog") +
                                      " -q --bootstrap 0 -o " + shell_quoted(dir() / "si"));
  ASSERT_EQ(mine.exit_code, 0) << mine.err;
  ASSERT_EQ(ref.exit_code, 0) << ref.err;
  const models::NoiseModel from_user = io::load_model_yaml((dir() / "user/model.yaml").string());
  EXPECT_EQ(from_user.samples, 4000);
  EXPECT_NEAR(from_user.sample_rate_hz, 100.0, 1e-9);
  expect_same_coefficients(from_user, io::load_model_yaml((dir() / "si/model.yaml").string()));
  const auto check = test::run_imunoise("check " + shell_quoted(dir() / "user.lcmlog") + mapping);
  EXPECT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr("4000"));

  // Without the field names, and with the wrong type on the channel: clear errors.
  auto r = test::run_imunoise("analyze " + shell_quoted(dir() / "user.lcmlog") + " --lcm-type " +
                              type + " -o " + shell_quoted(dir() / "u"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("name the fields with --gyro-cols and --accel-cols"));
  r = test::run_imunoise("analyze " + shell_quoted(dir() / "si.lcmlog") + " --channel IMU" +
                         mapping + " -o " + shell_quoted(dir() / "u"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("usertest.scalar_imu_t"));
  EXPECT_THAT(r.err, HasSubstr("imunoise.imu_sample_t"));
}

/// The acceptance run over real UDP multicast, isolated in a private network namespace.
TEST_F(LcmCli, MulticastEndToEndInAPrivateNetworkNamespace) {
  const fs::path work = dir() / "netns";
  fs::create_directories(work);
  const auto probe = run_shell(
      "command -v lcm-logger && command -v lcm-logplayer && unshare -n -- ip link set lo up", work);
  if (probe.exit_code != 0) {
    GTEST_SKIP() << "cannot run the multicast test: needs lcm-logger, lcm-logplayer and "
                    "'unshare -n' (root or CAP_SYS_ADMIN); CI runs as root. "
                 << probe.err;
  }
  // A 30 s IMU log (3000 messages) and its analysis: the reference for live.
  const std::string model =
      shell_quoted(fs::path(IMUNOISE_SOURCE_DIR) / "configs/reference-imu.yaml");
  auto r = test::run_imunoise("simulate " + model + " --duration 30s --rate 100 --seed 5 -o " +
                              shell_quoted(work / "imu.lcmlog"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run_imunoise("analyze " + shell_quoted(work / "imu.lcmlog") + " -q " + kAnalysisFlags +
                         " -o " + shell_quoted(work / "analyzed"));
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const std::string bin = "'" + test::imunoise_binary() + "'";
  const std::string setup = "set -e; cd " + shell_quoted(work) +
                            "; ip link set lo up; ip route add 224.0.0.0/4 dev lo; "
                            "URL='udpm://239.255.76.67:7667?ttl=0'; ";
  // 1. lcm-logger records what publish sends.
  const std::string publish_script =
      setup + "lcm-logger -q -f --lcm-url=\"$URL\" published.lcmlog & L=$!; sleep 1; " + bin +
      " publish " + shell_quoted(dir() / "a_log/model.yaml") + " --curves " +
      shell_quoted(dir() / "a_log/allan.csv") +
      " --lcm-url \"$URL\"; sleep 1; kill -INT $L; wait $L || true";
  r = run_shell("unshare -n -- bash -c " + shell_quoted(publish_script), work);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const std::vector<Event> published = read_events(work / "published.lcmlog");
  ASSERT_EQ(published.size(), 13u);  // the model and 12 curves
  ASSERT_EQ(published[0].channel, "NOISE_MODEL");
  const models::NoiseModel file = io::load_model_yaml((dir() / "a_log/model.yaml").string());
  expect_same_coefficients(
      io::noise_model_from_message(decode<imunoise::noise_model_t>(published[0])), file);
  EXPECT_EQ(decode<imunoise::allan_curve_t>(published[1]).axis_name, "gyro_x");

  // 2. lcm-logplayer replays the IMU log (10x real time) into live over multicast. UDP may
  // drop a datagram under load; the comparison needs every sample, so a run that lost one is
  // repeated (at most 3 runs) rather than compared.
  const std::string live_script =
      setup + bin + " live --channel IMU --lcm-url \"$URL\" --window 1h --every 1000s " +
      kAnalysisFlags +
      " -o live --max-runtime 120s > live.out 2> live.err & P=$!; sleep 1; "
      "lcm-logplayer -s 10 --lcm-url=\"$URL\" imu.lcmlog; sleep 1; kill -INT $P; wait $P; "
      "cat live.out";
  bool complete = false;
  for (int attempt = 0; attempt < 3 && !complete; ++attempt) {
    r = run_shell("unshare -n -- bash -c " + shell_quoted(live_script), work);
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    complete = r.out.find("received 3000, accepted 3000") != std::string::npos;
    if (!complete) std::cerr << "multicast replay lost messages, repeating: " << r.out;
  }
  ASSERT_TRUE(complete) << "live did not receive all 3000 messages in 3 runs: " << r.out;
  expect_same_coefficients(io::load_model_yaml((work / "live/model.yaml").string()),
                           io::load_model_yaml((work / "analyzed/model.yaml").string()));
}

}  // namespace
}  // namespace imunoise
