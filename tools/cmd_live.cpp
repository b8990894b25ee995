/// @file
/// @brief `imunoise live`: an LCM node that subscribes to imunoise.imu_sample_t, keeps a
/// rolling window of bounded memory, re-runs the analysis of `imunoise analyze` on it every
/// --every of data, and publishes the model (and OADEV curves). Bad traffic — undecodable
/// messages, another type on the channel, NaN/Inf, stamps out of order, a change between rates
/// and increments, floods beyond the window — is counted and reported, never fatal.
/// SIGINT/SIGTERM (or the end of a file:// log) stop it after one last analysis of new data.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <filesystem>
#include <future>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "common/errors.h"
#include "common/number_text.h"
#include "io/atomic_output.h"
#include "io/duration_parser.h"
#include "io/imu_sample_message.h"
#include "io/lcm_messages.h"
#include "io/noise_model_yaml.h"
#include "pipeline/gap_policy.h"
#include "pipeline/imu_samples.h"
#include "pipeline/live_window.h"
#include "tools/analysis_options.h"
#include "tools/commands.h"
#include "tools/lcm_bus.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

namespace {

std::atomic<bool> g_stop_requested{false};

extern "C" void request_stop(int) { g_stop_requested = true; }

struct LiveArgs {
  std::string url = kDefaultLcmUrl;
  std::string publish_url;  // empty = url
  std::string channel = "IMU";
  std::string window = "30min";
  std::string every = "60s";
  std::string max_runtime;
  std::int64_t max_samples = 5'000'000;
  int queue_capacity = 100'000;
  std::string model_channel = "NOISE_MODEL";
  std::string curves_channel = "ALLAN_CURVE";
  bool no_curves = false;
  std::string output_dir;
  AnalysisSettings analysis;
  Verbosity verbosity;
};

/// What the loop did with the window (the window counts what arrived).
struct AnalysisCounts {
  std::int64_t analyses = 0, failed_analyses = 0, skipped_analyses = 0;
  std::int64_t publish_failures = 0;
};

std::string counts_text(const pipeline::LiveWindowCounts& c) {
  return "received " + std::to_string(c.received) + ", accepted " + std::to_string(c.accepted) +
         ", undecodable " + std::to_string(c.undecodable) + ", non-finite " +
         std::to_string(c.non_finite) + ", out of order " + std::to_string(c.out_of_order) +
         ", rate/increment switches " + std::to_string(c.mode_changes) + ", gaps " +
         std::to_string(c.gaps) + ", dropped by --max-samples " + std::to_string(c.trimmed_by_cap) +
         ", restarts " + std::to_string(c.restarts);
}

/// The message handler: called by the LCM thread that calls handleTimeout(), i.e. the main
/// thread, the one thread that touches the window.
void handle_imu(const lcm::ReceiveBuffer* buffer, const std::string&,
                pipeline::LiveWindow* window) {
  if (const auto sample = io::decode_imu_sample(buffer->data, buffer->data_size)) {
    window->add(*sample);
  } else {
    window->add_undecodable();
  }
}

void run_live(const LiveArgs& args) {
  const double window_s = io::parse_duration_s(args.window, "--window");
  const double every_s = io::parse_duration_s(args.every, "--every");
  // 0 = no limit.
  const double max_runtime_s =
      args.max_runtime.empty() ? 0.0 : io::parse_duration_s(args.max_runtime, "--max-runtime");
  if (args.max_samples < 16) throw InputError("--max-samples: expected at least 16");
  (void)gap_policy_option(args.analysis);
  import_fftw_wisdom_option(args.analysis);  // once, for every analysis of the window
  if (args.queue_capacity < 1) throw InputError("--queue-capacity: expected at least 1");
  if (!args.output_dir.empty()) io::create_output_directory(args.output_dir);

  const bool reads_a_log = args.url.rfind("file://", 0) == 0 &&
                           args.url.find("mode=w") == std::string::npos &&
                           args.url.find("mode=a") == std::string::npos;
  if (reads_a_log && args.publish_url.empty()) {
    throw InputError("--lcm-url '" + args.url +
                     "' replays a log, which cannot be published to: give --publish-url (e.g. "
                     "'file:///tmp/estimates.lcmlog?mode=w' or the udpm:// bus)");
  }
  LcmBus bus(args.url);
  // A separate output bus when asked (e.g. input replayed from a file:// log, which cannot be
  // published to).
  std::optional<LcmBus> publish_bus;
  if (!args.publish_url.empty() && args.publish_url != args.url)
    publish_bus.emplace(args.publish_url);
  LcmBus& out_bus = publish_bus ? *publish_bus : bus;
  pipeline::LiveWindow window({window_s, args.max_samples, every_s}, io::imu_sample_fields());
  lcm::Subscription* subscription = bus.lcm().subscribeFunction(args.channel, &handle_imu, &window);
  // LCM queues messages per subscription while the handler is not being called; bounded, so a
  // flood costs dropped messages, not memory.
  subscription->setQueueCapacity(args.queue_capacity);

  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);

  const std::string source = "lcm:" + args.channel;
  const auto started = std::chrono::steady_clock::now();
  std::future<pipeline::RecordingAnalysis> running;
  AnalysisCounts counts;

  const auto log = [&](const std::string& line) {
    if (!args.verbosity.quiet) std::cerr << "imunoise live: " << line << "\n";
  };
  auto analysis_started = started;  // for --verbose
  const auto start_analysis = [&] {
    analysis_started = std::chrono::steady_clock::now();
    pipeline::ImuSampleColumns columns = window.snapshot();
    running = std::async(std::launch::async, [columns = std::move(columns), &args, source,
                                              channel = args.channel]() mutable {
      const pipeline::Recording recording =
          pipeline::recording_from_imu_samples(std::move(columns), source, channel);
      return analyze_recording(recording, source, args.analysis);
    });
  };
  const auto finish_analysis = [&] {
    try {
      pipeline::RecordingAnalysis result = running.get();
      ++counts.analyses;
      window.set_nominal_period_s(result.tau0_s);
      const std::int64_t utime = now_utime_us();
      try {
        out_bus.publish(args.model_channel, io::noise_model_message(result.model, utime));
        if (!args.no_curves) {
          for (const pipeline::AxisAnalysis& a : result.axes) {
            out_bus.publish(args.curves_channel,
                            io::allan_curve_message(a.model.name, a.oadev, utime));
          }
        }
      } catch (const InputError& e) {
        ++counts.publish_failures;  // a bus hiccup is not a reason to stop listening
        log(e.what());
      }
      if (!args.output_dir.empty()) {
        io::write_model_yaml(result.model,
                             (std::filesystem::path(args.output_dir) / "model.yaml").string());
      }
      log("published model " + std::to_string(counts.analyses) + " (" +
          std::to_string(result.model.samples) + " samples, " +
          significant_number_text(result.model.duration_s, 6) + " s at " +
          significant_number_text(result.model.sample_rate_hz, 6) + " Hz); " +
          counts_text(window.counts()));
      if (args.verbosity.verbose) {
        const std::chrono::duration<double> took =
            std::chrono::steady_clock::now() - analysis_started;
        log("analysis and publishing took " + significant_number_text(took.count(), 3) +
            " s wall time");
      }
    } catch (const InputError& e) {
      ++counts.failed_analyses;
      log(std::string("analysis failed, will retry with more data: ") + e.what());
    } catch (const AnalysisError& e) {
      ++counts.failed_analyses;
      log(std::string("analysis failed, will retry with more data: ") + e.what());
    }
  };

  log("listening on '" + args.channel + "' (" + args.url + "), window " + args.window +
      ", analysis every " + args.every + " of data");
  bool end_of_input = false;
  while (!g_stop_requested) {
    const int handled = bus.lcm().handleTimeout(100);
    if (handled < 0) {
      // A signal interrupts the wait (EINTR) — then the loop condition ends it; otherwise it
      // is the file:// provider at the end of its log, or a dead socket.
      if (g_stop_requested) break;
      end_of_input = true;
      break;
    }
    if (running.valid() && running.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      finish_analysis();
    }
    // After a restart the stamps may lie before the last analysis: then it is due when the
    // window alone spans --every again.
    if (window.analysis_due()) {
      if (running.valid()) {
        ++counts.skipped_analyses;  // the previous one still runs; the next check retries
      } else {
        start_analysis();
      }
    }
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - started;
    if (max_runtime_s > 0.0 && elapsed.count() >= max_runtime_s) {
      break;
    }
  }
  // One last analysis of whatever arrived since the previous one.
  if (running.valid()) finish_analysis();
  if (window.has_unanalysed_data()) {
    start_analysis();
    finish_analysis();
  }
  bus.lcm().unsubscribe(subscription);
  std::cout << "imunoise live: stopped ("
            << (g_stop_requested ? "signal"
                : end_of_input   ? "end of input"
                                 : "--max-runtime")
            << "); " << counts_text(window.counts()) << "; analyses " << counts.analyses
            << ", failed " << counts.failed_analyses << ", publish failures "
            << counts.publish_failures << "\n";
}

}  // namespace

void register_live_command(CLI::App& app) {
  auto args = std::make_shared<LiveArgs>();
  CLI::App* cmd = app.add_subcommand(
      "live",
      "LCM node: subscribe to imunoise.imu_sample_t, keep a rolling window, re-fit the noise "
      "model every --every of data and publish it (imunoise.noise_model_t, allan_curve_t)");
  cmd->add_option("--channel", args->channel, "IMU channel to subscribe to")->capture_default_str();
  cmd->add_option("--lcm-url", args->url, "LCM provider URL (file://LOG?speed=0 replays a log)")
      ->capture_default_str();
  cmd->add_option("--publish-url", args->publish_url,
                  "LCM provider URL for the published estimates (default: --lcm-url)");
  cmd->add_option("--window", args->window, "length of the rolling window of data")
      ->capture_default_str();
  cmd->add_option("--every", args->every,
                  "re-analyse after this much new data (also the least data analysed)")
      ->capture_default_str();
  cmd->add_option("--max-samples", args->max_samples,
                  "memory bound: most samples kept (oldest dropped and counted)")
      ->capture_default_str();
  cmd->add_option("--queue-capacity", args->queue_capacity,
                  "LCM messages queued while busy before LCM drops them")
      ->capture_default_str();
  cmd->add_option("--max-runtime", args->max_runtime, "stop after this wall-clock time");
  cmd->add_option("--model-channel", args->model_channel, "channel of the published model")
      ->capture_default_str();
  cmd->add_option("--curves-channel", args->curves_channel, "channel of the OADEV curves")
      ->capture_default_str();
  cmd->add_flag("--no-curves", args->no_curves, "publish the model only");
  cmd->add_option("-o,--output", args->output_dir,
                  "also write DIR/model.yaml after every analysis (atomically)");
  // A live stream loses datagrams: one lost message must not stop every analysis of the
  // window, so the pieces are pooled unless the user asks otherwise.
  args->analysis.gaps = "split";
  add_analysis_options(*cmd, args->analysis);
  add_verbosity_options(*cmd, args->verbosity);
  cmd->footer(
      "Examples:\n"
      "  imunoise live --channel IMU --window 30min --every 60s\n"
      "  imunoise live --channel IMU --lcm-url 'file:///data/imu.lcmlog?speed=0' \\\n"
      "      --publish-url 'file:///data/estimates.lcmlog?mode=w' --every 10min -o out/live\n"
      "Stops on SIGINT/SIGTERM after one last analysis of the data that arrived since the\n"
      "previous one; the counts of bad or dropped messages are printed on exit.");
  cmd->callback([args] { run_live(*args); });
}

}  // namespace imunoise::tools
