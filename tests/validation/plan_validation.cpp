/// @file
/// @brief Validation of `imunoise plan` (issue 23 item 2) against simulation: for each grade of
/// the validation battery (tests/validation/battery/battery_cases.cpp: consumer, industrial,
/// tactical), plan the recording length that brings a term's 95 % interval to a target
/// relative half-width (pipeline::plan_recording on the grade's true coefficients), generate
/// recordings of that length with the battery's independent generator (no code shared with
/// models/noise_simulator), analyse each with the default `imunoise analyze` (the binary, as a
/// user runs it) and measure the median relative half-width (ci_high − ci_low)/(2·estimate) of
/// the term over channels and seeds. A channel where the term is not identified counts as an
/// infinite half-width (the target is not reached), so it pulls the median up.
///
/// Seed noise: the median of n half-widths has a distribution-free 95 % interval between the
/// order statistics k_lo = ⌊n/2 − 0.98√n⌋ and k_hi = ⌈n/2 + 0.98√n⌉ + 1 (1-based; the binomial
/// (n, ½) count below the median, normal approximation). The 15 % claim holds beyond the seed
/// noise when that whole interval, divided by the target, lies in [0.85, 1.15]; --check exits 1
/// when the measured median is outside 15 % of the target (reduced runs, few seeds: the interval
/// is printed but not required inside).
///
/// Channels of one sensor share the ratios of their coefficients (each axis scales all of them
/// by 1.0, 1.2, 0.85), so their relative half-widths are draws of one distribution; the
/// channels of a sensor are pooled, the sensors (gyro, accel) are planned and scored apart.
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "battery/battery_cases.h"
#include "battery/generator.h"
#include "common/errors.h"
#include "io/binary_recording.h"
#include "io/noise_model_yaml.h"
#include "pipeline/recording_plan.h"

namespace fs = std::filesystem;
using imunoise::battery::BatteryCase;

namespace {

struct Options {
  std::vector<std::string> grades = {"consumer", "industrial", "tactical"};
  std::vector<std::string> sensors = {"gyro", "accel"};
  std::string target = "K:20%";
  double rate_hz = 100.0;
  int seeds = 10;
  int first_seed = 1;
  std::string out = "plan_validation";
  std::string imunoise = IMUNOISE_BINARY_PATH;
  double tolerance = 0.15;
  bool check = false;
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(item);
  return out;
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char ch : s) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

imunoise::NoiseCoefficients coefficients_of(const imunoise::battery::ChannelTruth& t) {
  imunoise::NoiseCoefficients c;
  c.quantization = t.quantization;
  c.white_noise = t.white_noise;
  c.bias_instability = t.bias_instability;
  c.random_walk = t.random_walk;
  c.ramp = t.ramp;
  return c;
}

/// Writes the CHANNELS of recording G (case C) as .imnb at the fixed rate.
void write_recording(const BatteryCase& c, const std::vector<int>& channels,
                     const std::vector<std::vector<double>>& values, const fs::path& path) {
  namespace io = imunoise::io;
  io::BinaryRecordingHeader h;
  h.source_path = "plan_validation:" + c.class_name + ":" + std::to_string(c.seed);
  h.created_by = std::string(io::kBinaryCreatedBy);
  h.sample_count = c.spec.samples;
  h.sample_period_s = 1.0 / c.spec.rate_hz;
  h.rate_hz = c.spec.rate_hz;
  for (int ch : channels) {
    const auto& truth = c.truth[static_cast<std::size_t>(ch)];
    imunoise::pipeline::Channel channel;
    channel.name = channel.source_column = truth.name;
    channel.kind = truth.gyro ? imunoise::SensorKind::gyro : imunoise::SensorKind::accel;
    channel.source_unit = truth.gyro ? "rad/s" : "m/s^2";
    h.channels.push_back(channel);
  }
  io::BinaryRecordingWriter writer(path.string(), h);
  for (std::size_t k = 0; k < values.size(); ++k) writer.append(k, values[k]);
  writer.commit();
}

double median_of(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// The distribution-free 95 % interval of the median of sorted V (see the file comment).
std::pair<double, double> median_interval(std::vector<double> v) {
  if (v.empty())
    return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  std::sort(v.begin(), v.end());
  const double n = static_cast<double>(v.size());
  const auto lo = static_cast<std::ptrdiff_t>(std::floor(n / 2.0 - 0.98 * std::sqrt(n)));
  const auto hi = static_cast<std::ptrdiff_t>(std::ceil(n / 2.0 + 0.98 * std::sqrt(n)));
  const auto at = [&](std::ptrdiff_t k) {
    k = std::clamp<std::ptrdiff_t>(k, 1, static_cast<std::ptrdiff_t>(v.size()));
    return v[static_cast<std::size_t>(k - 1)];
  };
  return {at(lo), at(hi + 1)};
}

struct Score {
  std::string grade, sensor;
  double duration_s = 0.0, predicted = 0.0, target = 0.0, median = 0.0, ci_low = 0.0, ci_high = 0.0;
  int samples = 0, not_identified = 0, recordings = 0;
  double seconds = 0.0;
};

Score run_sensor(const Options& o, const std::string& grade, const std::string& sensor,
                 const imunoise::pipeline::PlanTarget& target, const fs::path& work) {
  using namespace imunoise;
  Score s;
  s.grade = grade;
  s.sensor = sensor;
  s.target = target.relative_halfwidth;
  const BatteryCase base = battery::make_case(grade, battery::BatterySize::full, 1);
  const int first = sensor == "gyro" ? 0 : 3;
  std::vector<int> channels;  // the sensor's channels that have the term
  std::vector<pipeline::PlanAxis> axes;
  for (int ch = first; ch < first + 3; ++ch) {
    const auto& t = base.truth[static_cast<std::size_t>(ch)];
    axes.push_back({t.name, coefficients_of(t)});
    if (coefficient(axes.back().model, target.term) > 0.0) channels.push_back(ch);
  }
  pipeline::RecordingPlanOptions plan_options;
  plan_options.threads = 2;
  const pipeline::RecordingPlan plan =
      pipeline::plan_recording(axes, o.rate_hz, std::span(&target, 1), plan_options);
  s.duration_s = plan.all_targets_duration_s;
  if (!std::isfinite(s.duration_s)) {
    std::fprintf(stderr, "%s %s: target beyond the searched range\n", grade.c_str(),
                 sensor.c_str());
    return s;
  }
  // The plan's expected half-width at the planned duration, per channel with the term.
  std::vector<double> predicted;
  for (int ch : channels) {
    const auto p = pipeline::expected_precision(axes[static_cast<std::size_t>(ch - first)].model,
                                                o.rate_hz, s.duration_s, ch - first, plan_options);
    predicted.push_back(p[target.term].relative_halfwidth);
  }
  s.predicted = median_of(predicted);
  std::vector<double> widths;
  const auto start = std::chrono::steady_clock::now();
  for (int seed = o.first_seed; seed < o.first_seed + o.seeds; ++seed) {
    BatteryCase c =
        battery::make_case(grade, battery::BatterySize::full, static_cast<std::uint64_t>(seed));
    c.spec.rate_hz = o.rate_hz;
    c.spec.samples = static_cast<std::size_t>(std::llround(s.duration_s * o.rate_hz));
    std::vector<std::vector<double>> values;
    for (int ch : channels) values.push_back(battery::generate_channel(c.spec, ch));
    const std::string tag = grade + "_" + sensor + "_seed" + std::to_string(seed);
    const fs::path rec = work / (tag + ".imnb");
    const fs::path dir = work / tag;
    write_recording(c, channels, values, rec);
    values.clear();
    std::ostringstream command;
    command << "nice -n 5 " << shell_quote(o.imunoise) << " analyze " << shell_quote(rec.string())
            << " -q -o " << shell_quote(dir.string()) << " > "
            << shell_quote((work / (tag + ".log")).string()) << " 2>&1";
    const int status = std::system(command.str().c_str());
    fs::remove(rec);
    ++s.recordings;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::fprintf(stderr, "%s: analyze failed, see %s.log\n", tag.c_str(), tag.c_str());
      for (std::size_t k = 0; k < channels.size(); ++k) {
        widths.push_back(std::numeric_limits<double>::infinity());
        ++s.not_identified;
      }
      continue;
    }
    const models::NoiseModel model = io::load_model_yaml((dir / "model.yaml").string());
    for (int ch : channels) {
      const std::string& name = c.truth[static_cast<std::size_t>(ch)].name;
      double w = std::numeric_limits<double>::infinity();
      for (const models::AxisModel& axis : model.axes) {
        if (axis.name != name) continue;
        const models::Estimate& e = axis.terms[target.term];
        if (e.identified && e.value > 0.0) w = (e.ci_high - e.ci_low) / (2.0 * e.value);
      }
      if (!std::isfinite(w)) ++s.not_identified;
      widths.push_back(w);
    }
  }
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  s.samples = static_cast<int>(widths.size());
  s.median = median_of(widths);
  std::tie(s.ci_low, s.ci_high) = median_interval(widths);
  std::ofstream raw(work / (grade + "_" + sensor + "_widths.csv"));
  raw << "relative_halfwidth\n";
  for (double w : widths) raw << w << "\n";
  return s;
}

int usage() {
  std::fprintf(stderr,
               "usage: plan_validation [--grades a,b] [--sensors gyro,accel] [--target K:20%%]\n"
               "  [--rate HZ] [--seeds N] [--first-seed S] [--out DIR] [--imunoise PATH]\n"
               "  [--tolerance 0.15] [--check]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    try {
      if (a == "--grades") {
        o.grades = split(value());
      } else if (a == "--sensors") {
        o.sensors = split(value());
      } else if (a == "--target") {
        o.target = value();
      } else if (a == "--rate") {
        o.rate_hz = std::stod(value());
      } else if (a == "--seeds") {
        o.seeds = std::stoi(value());
      } else if (a == "--first-seed") {
        o.first_seed = std::stoi(value());
      } else if (a == "--out") {
        o.out = value();
      } else if (a == "--imunoise") {
        o.imunoise = value();
      } else if (a == "--tolerance") {
        o.tolerance = std::stod(value());
      } else if (a == "--check") {
        o.check = true;
      } else {
        return usage();
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "plan_validation: %s\n", e.what());
      return usage();
    }
  }
  try {
    const auto targets = imunoise::pipeline::parse_plan_targets(o.target, "--target");
    if (targets.size() != 1) throw imunoise::InputError("--target: give exactly one term");
    const fs::path work = fs::path(o.out);
    fs::create_directories(work);
    std::vector<Score> scores;
    for (const std::string& grade : o.grades) {
      for (const std::string& sensor : o.sensors) {
        scores.push_back(run_sensor(o, grade, sensor, targets.front(), work));
        const Score& s = scores.back();
        std::fprintf(stderr, "%s %s: %.0f s planned, %d widths, %.0f s\n", grade.c_str(),
                     sensor.c_str(), s.duration_s, s.samples, s.seconds);
      }
    }
    std::ostringstream table;
    table
        << "| grade | sensor | rate [Hz] | target | planned duration [h] | plan's half-width "
           "there | recordings | channel-seeds | not identified | measured median | 95 % "
           "interval of the median | median / target | within "
        << o.tolerance * 100
        << " % | beyond seed noise |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    bool ok = true;
    for (const Score& s : scores) {
      const double ratio = s.median / s.target;
      const bool within = std::fabs(ratio - 1.0) <= o.tolerance;
      const bool certain =
          s.ci_low / s.target >= 1.0 - o.tolerance && s.ci_high / s.target <= 1.0 + o.tolerance;
      ok = ok && within;
      char line[512];
      std::snprintf(line, sizeof line,
                    "| %s | %s | %g | %s | %.3g | %.1f %% | %d | %d | %d | %.1f %% | %.1f – %.1f "
                    "%% | %.3f | %s | %s |\n",
                    s.grade.c_str(), s.sensor.c_str(), o.rate_hz, o.target.c_str(),
                    s.duration_s / 3600.0, 100.0 * s.predicted, s.recordings, s.samples,
                    s.not_identified, 100.0 * s.median, 100.0 * s.ci_low, 100.0 * s.ci_high, ratio,
                    within ? "yes" : "**no**", certain ? "yes" : "no");
      table << line;
    }
    std::printf("%s", table.str().c_str());
    std::ofstream(work / "summary.md") << table.str();
    return o.check && !ok ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "plan_validation: %s\n", e.what());
    return 2;
  }
}
