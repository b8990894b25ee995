#include "io/fftw_wisdom_planning.h"

#include <fftw3.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/fftw_planner_lock.h"

namespace imunoise::io {
namespace {

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

}  // namespace

LengthPlanResult plan_fft_length(std::size_t length, PlannerEffort effort_kind,
                                 double time_limit_s) {
  IMUNOISE_EXPECT(length >= 2 && length <= static_cast<std::size_t>(INT_MAX),
                  "plan_fft_length: length must be 2 to INT_MAX");
  const unsigned effort = effort_kind == PlannerEffort::kPatient ? FFTW_PATIENT : FFTW_MEASURE;
  const int n = static_cast<int>(length);
  const std::size_t bins = length / 2 + 1;
  LengthPlans p;
  LengthPlanResult r;
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

}  // namespace imunoise::io
