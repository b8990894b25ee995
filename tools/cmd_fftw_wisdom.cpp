/// @file
/// @brief `imunoise fftw-wisdom`: measures FFTW r2c plans for the Welch segment lengths that
/// `analyze` will use and saves them as FFTW wisdom, so that `analyze --fftw-wisdom FILE` (or
/// IMUNOISE_FFTW_WISDOM=FILE) runs its PSD transforms with a measured plan without measuring.
/// Prints, per length, the planning time and the time of one transform with the wisdom plan
/// and with the FFTW_ESTIMATE plan analyze uses otherwise.
#include <fftw3.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/psd.h"
#include "common/errors.h"
#include "common/fftw_planner_lock.h"
#include "common/number_text.h"
#include "io/atomic_output.h"
#include "io/fftw_wisdom.h"
#include "tools/commands.h"
#include "tools/duration.h"
#include "tools/verbosity.h"

namespace imunoise::tools {
namespace {

struct WisdomArgs {
  std::vector<std::size_t> samples;
  std::vector<std::size_t> lengths;
  std::string effort = "measure";
  std::string time_limit;  // empty = no limit
  std::string output;
  bool merge = false;
  Verbosity verbosity;
};

/// The buffers and the two plans of one length; destroyed under the planner mutex.
struct LengthPlans {
  double* in = nullptr;
  fftw_complex* out = nullptr;
  fftw_plan estimate = nullptr;
  fftw_plan wisdom = nullptr;

  LengthPlans() = default;
  LengthPlans(const LengthPlans&) = delete;
  LengthPlans& operator=(const LengthPlans&) = delete;
  ~LengthPlans() {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    if (estimate != nullptr) fftw_destroy_plan(estimate);
    if (wisdom != nullptr) fftw_destroy_plan(wisdom);
    fftw_free(in);
    fftw_free(out);
  }
};

struct MallocFree {
  void operator()(char* p) const { std::free(p); }  // fftw_export_wisdom_to_string: free()
};

/// What planning one length gave.
struct LengthResult {
  double planning_s = 0.0;
  bool already_known = false;  ///< the merged wisdom had it: nothing was measured
  bool usable = false;         ///< analyze's wisdom-only planning finds it
  double wisdom_s = 0.0;       ///< one transform, wisdom plan (median)
  double estimate_s = 0.0;     ///< one transform, FFTW_ESTIMATE plan (median)
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Appends to SAMPLES the time of one execution of PLAN, averaged over BATCH executions.
void time_batch(fftw_plan plan, int batch, std::vector<double>& samples) {
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < batch; ++i) fftw_execute(plan);
  samples.push_back(seconds_since(start) / batch);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

LengthResult plan_length(std::size_t length, unsigned effort, double time_limit_s) {
  const int n = static_cast<int>(length);
  const std::size_t bins = length / 2 + 1;
  LengthPlans p;
  LengthResult r;
  {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    p.in = static_cast<double*>(fftw_malloc(sizeof(double) * length));
    p.out = static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * bins));
    if (p.in == nullptr || p.out == nullptr) throw std::bad_alloc();
    // The reference: the ESTIMATE plan analyze makes without wisdom. FFTW's ESTIMATE planning
    // uses any wisdom it holds, so it is made with the wisdom set aside, then restored.
    const std::unique_ptr<char, MallocFree> saved(fftw_export_wisdom_to_string());
    if (!saved) throw std::bad_alloc();
    fftw_forget_wisdom();
    p.estimate = fftw_plan_dft_r2c_1d(n, p.in, p.out, FFTW_ESTIMATE);
    fftw_forget_wisdom();
    if (fftw_import_wisdom_from_string(saved.get()) == 0) {
      throw std::runtime_error("fftw-wisdom: FFTW did not take back its own wisdom");
    }
    // Merged wisdom of this rigour already covers the length: nothing to measure.
    p.wisdom = fftw_plan_dft_r2c_1d(n, p.in, p.out, effort | FFTW_WISDOM_ONLY);
    r.already_known = p.wisdom != nullptr;
    if (p.wisdom == nullptr) {
      fftw_set_timelimit(time_limit_s > 0.0 ? time_limit_s : FFTW_NO_TIMELIMIT);
      const auto start = std::chrono::steady_clock::now();
      p.wisdom = fftw_plan_dft_r2c_1d(n, p.in, p.out, effort);
      r.planning_s = seconds_since(start);
      fftw_set_timelimit(FFTW_NO_TIMELIMIT);
    }
    // What analyze will find: planning cut short by the time limit leaves no wisdom that
    // wisdom-only planning accepts.
    fftw_plan probe = fftw_plan_dft_r2c_1d(n, p.in, p.out, FFTW_MEASURE | FFTW_WISDOM_ONLY);
    r.usable = probe != nullptr;
    if (probe != nullptr) fftw_destroy_plan(probe);
  }
  if (p.estimate == nullptr || p.wisdom == nullptr) {
    throw AnalysisError("fftw-wisdom: FFTW could not plan a transform of length " +
                        std::to_string(length));
  }
  // Planning with measurement overwrote the input: fill it now (deterministic, white-ish).
  std::uint64_t state = 0x9e3779b97f4a7c15ULL;
  for (std::size_t i = 0; i < length; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    p.in[i] = static_cast<double>(state >> 11) * 0x1.0p-53 - 0.5;
  }
  // Batches of ~2^20 points so that short transforms are timed over a few milliseconds; the
  // two plans alternate so that a slow moment of a shared machine hits both.
  const int batch = static_cast<int>(std::max<std::size_t>(1, (std::size_t{1} << 20) / length));
  std::vector<double> wisdom_samples, estimate_samples;
  fftw_execute(p.wisdom);  // warm the caches and pages once for each
  fftw_execute(p.estimate);
  for (int k = 0; k < 5; ++k) {
    time_batch(p.wisdom, batch, wisdom_samples);
    time_batch(p.estimate, batch, estimate_samples);
  }
  r.wisdom_s = median(wisdom_samples);
  r.estimate_s = median(estimate_samples);
  return r;
}

/// "47.7 ns", "8.1 ms", "0.21 s", "310 s".
std::string duration_text(double seconds) {
  if (seconds < 1e-6) return significant_number_text(seconds * 1e9, 3) + " ns";
  if (seconds < 1e-3) return significant_number_text(seconds * 1e6, 3) + " us";
  if (seconds < 1.0) return significant_number_text(seconds * 1e3, 3) + " ms";
  return significant_number_text(seconds, 3) + " s";
}

void run_fftw_wisdom(const WisdomArgs& args) {
  if (args.samples.empty() && args.lengths.empty()) {
    throw InputError(
        "fftw-wisdom: give the record lengths (--samples N) or the segment "
        "lengths (--length L) to plan for");
  }
  unsigned effort = FFTW_MEASURE;
  if (args.effort == "patient") effort = FFTW_PATIENT;
  const double time_limit_s =
      args.time_limit.empty() ? 0.0 : parse_duration_s(args.time_limit, "--time-limit");

  // Each length once, with the first record length that asked for it.
  std::map<std::size_t, std::string> lengths;
  for (std::size_t n : args.samples) {
    if (n < 16) {
      throw InputError("--samples: " + std::to_string(n) +
                       " samples is too short for a Welch PSD (at least 16)");
    }
    lengths.emplace(analysis::automatic_segment_length(n),
                    "the automatic length for " + std::to_string(n) + " samples");
  }
  for (std::size_t l : args.lengths) {
    if (l < 2 || l > static_cast<std::size_t>(INT_MAX)) {
      throw InputError("--length: " + std::to_string(l) + " is not a segment length (2 to " +
                       std::to_string(INT_MAX) + ")");
    }
    lengths.emplace(l, "--length");
  }

  // Fail in a second, not after minutes of planning, when FILE cannot be written.
  { const io::AtomicOutputFile probe(args.output); }
  if (args.merge) {
    if (std::filesystem::exists(args.output)) {
      io::import_fftw_wisdom(args.output);
      print_info(args.verbosity, "fftw-wisdom", "merging with the wisdom in " + args.output);
    } else {
      print_info(args.verbosity, "fftw-wisdom",
                 args.output + " does not exist yet: nothing to merge");
    }
  }

  std::size_t unusable = 0;
  for (const auto& [length, origin] : lengths) {
    print_detail(args.verbosity, "fftw-wisdom",
                 "planning L = " + std::to_string(length) + " (" + args.effort + ")…");
    const LengthResult r = plan_length(length, effort, time_limit_s);
    std::ostringstream line;
    line << "L = " << length << " (" << origin << "): ";
    if (r.already_known) {
      line << "already in the merged wisdom";
    } else {
      line << args.effort << " planning " << duration_text(r.planning_s);
    }
    line << "; one transform " << duration_text(r.wisdom_s) << " with the wisdom plan vs "
         << duration_text(r.estimate_s) << " with FFTW_ESTIMATE (" << std::fixed
         << std::setprecision(2) << r.estimate_s / r.wisdom_s << "x)";
    std::cout << line.str() << std::endl;
    if (!r.usable) {
      ++unusable;
      std::cerr << "imunoise fftw-wisdom: warning: L = " << length
                << (time_limit_s > 0.0
                        ? ": planning stopped at the --time-limit, and FFTW keeps no reusable "
                          "wisdom from an interrupted search"
                        : ": FFTW kept no reusable wisdom for this length")
                << "; analyze will use FFTW_ESTIMATE for it"
                << (time_limit_s > 0.0 ? " (raise or drop --time-limit)\n" : "\n");
    }
  }
  io::export_fftw_wisdom(args.output);
  std::cout << "wrote " << args.output;
  if (unusable > 0) std::cout << " (" << unusable << " length(s) without usable wisdom)";
  std::cout << "; use it with 'imunoise analyze REC --fftw-wisdom " << args.output
            << "' or IMUNOISE_FFTW_WISDOM=" << args.output << "\n";
}

}  // namespace

void register_fftw_wisdom_command(CLI::App& app) {
  auto args = std::make_shared<WisdomArgs>();
  CLI::App* cmd = app.add_subcommand(
      "fftw-wisdom",
      "Measure FFTW plans for the PSD segment lengths of 'analyze' and save them as FFTW "
      "wisdom (FILE), so that 'analyze --fftw-wisdom FILE' uses a measured plan without "
      "measuring; prints the planning time and the transform time with and without it");
  cmd->add_option("--samples", args->samples,
                  "record lengths [samples] to plan for (repeat or N1,N2,...): each gives the "
                  "automatic Welch segment length of analyze (largest power of two <= N/8, at "
                  "least 16)")
      ->delimiter(',');
  cmd->add_option("--length", args->lengths, "explicit segment lengths L (repeat or L1,L2,...)")
      ->delimiter(',');
  cmd->add_option("--effort", args->effort,
                  "planner rigour: measure (default) or patient (slower to plan, sometimes a "
                  "faster plan)")
      ->check(CLI::IsMember({"measure", "patient"}));
  cmd->add_option("--time-limit", args->time_limit,
                  "stop FFTW's search for one length after this long (600, 10min; default: no "
                  "limit); a length cut short keeps no reusable wisdom (a warning says so)");
  cmd->add_option("-o,--output", args->output, "wisdom file to write (atomically)")->required();
  cmd->add_flag("--merge", args->merge,
                "import FILE first, if it exists, and keep its wisdom (lengths already in it are "
                "not measured again)");
  add_verbosity_options(*cmd, args->verbosity);
  cmd->footer(
      "Examples:\n"
      "  imunoise fftw-wisdom --samples 86400000 -o imu.wisdom    # 24 h at 1 kHz: L = 2^23, ~5 "
      "min\n"
      "  imunoise fftw-wisdom --length 1048576,4096 --merge -o imu.wisdom\n"
      "  imunoise analyze rec.imnb -o out --fftw-wisdom imu.wisdom\n"
      "  IMUNOISE_FFTW_WISDOM=imu.wisdom imunoise analyze rec.imnb -o out\n"
      "Wisdom holds for this machine and this FFTW build only; analyze plans from it without\n"
      "measuring, and falls back to FFTW_ESTIMATE for a length it does not cover.");
  cmd->callback([args] {
    StageTimes times;
    run_fftw_wisdom(*args);
    times.mark("plan, time and write");
    print_timings(args->verbosity, "fftw-wisdom", times);
  });
}

}  // namespace imunoise::tools
