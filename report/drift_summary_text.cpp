/// @file
/// @brief The terminal summary of `imunoise drift` (see drift_summary_text.h).
#include "report/drift_summary_text.h"

#include <algorithm>
#include <sstream>

#include "common/number_text.h"

namespace imunoise::report {

namespace {

/// One row per report time: predicted, actual, ratio, NEES, coverage (and the MC RMS).
void consistency_rows(std::ostringstream& out,
                      const std::vector<pipeline::DriftConsistency>& consistency, bool mc) {
  out << "\n  time   predicted DRMS   actual RMS   ratio [95% CI]        mean NEES [95% band]"
         "     coverage 1/2/3 sigma (exp. 39/86/99 %)"
      << (mc ? "   MC RMS" : "") << "\n";
  for (const pipeline::DriftConsistency& c : consistency) {
    out << "  " << significant_number_text(c.time_s) << " s   "
        << significant_number_text(c.predicted_drms_m) << " m   "
        << significant_number_text(c.actual_rms_m) << " m   "
        << significant_number_text(c.rms_ratio, 3) << " ["
        << significant_number_text(c.rms_ratio_ci_low, 3) << ", "
        << significant_number_text(c.rms_ratio_ci_high, 3) << "]   "
        << significant_number_text(c.mean_nees, 3) << " ["
        << significant_number_text(c.nees_band_low, 3) << ", "
        << significant_number_text(c.nees_band_high, 3) << "] "
        << (c.nees_inside ? "inside" : "OUTSIDE") << "   "
        << significant_number_text(100 * c.coverage[0], 3) << "/"
        << significant_number_text(100 * c.coverage[1], 3) << "/"
        << significant_number_text(100 * c.coverage[2], 3) << " %";
    if (mc && c.monte_carlo_radial_rms_m)
      out << "   " << significant_number_text(*c.monte_carlo_radial_rms_m) << " m";
    out << "\n";
  }
  if (consistency.size() < 2) return;
  // One verdict over all report times: a consistent model is inside every per-time 95 % band
  // only ~86 % of the time at three times, inside the joint band at all of them ≥ 95 %.
  const auto& first = consistency.front();
  const bool all_inside =
      std::all_of(consistency.begin(), consistency.end(),
                  [](const pipeline::DriftConsistency& c) { return c.nees_inside_joint_band; });
  out << "  all " << consistency.size() << " report times together: mean NEES "
      << (all_inside ? "inside" : "OUTSIDE") << " the joint 95 % band (["
      << significant_number_text(first.nees_joint_band_low, 3) << ", "
      << significant_number_text(first.nees_joint_band_high, 3) << "] at each time)\n";
}

}  // namespace

std::string drift_summary_text(const pipeline::DriftSummary& s) {
  const bool mc = s.monte_carlo.has_value();
  std::ostringstream out;
  out << "drift: " << s.protocol.segments << " segments of "
      << significant_number_text(s.protocol.align_s) << " s alignment + "
      << significant_number_text(s.protocol.navigation_s) << " s navigation, height hold\n";
  if (!s.location.given)
    out << "location not given: assumed 45 deg N, 0 deg E, 0 m (--location LAT,LON,H)\n";
  out << "heading: " << s.protocol.heading << "\n";
  if (!s.motion.stationary) out << "WARNING: not stationary (" << s.motion.reason << "), forced\n";
  consistency_rows(out, s.consistency, mc);
  if (s.holdout) {
    out << "\nsplit-sample check: model fitted on the " << s.holdout->fitted_on << ",\n  judged on "
        << s.holdout->segments << " segments of the " << s.holdout->judged_on << "\n";
    consistency_rows(out, s.holdout->consistency, false);
  }
  return out.str();
}

std::string drift_budget_text(const pipeline::DriftBudget& b) {
  if (std::find(b.report_time.begin(), b.report_time.end(), true) == b.report_time.end()) return "";
  std::ostringstream out;
  out << "\ndrift budget: share of the predicted horizontal variance [%]\n  time  ";
  for (std::size_t g = 0; g < ins::kDriftBudgetTerms; ++g)
    out << "  " << ins::name_of(static_cast<ins::DriftBudgetTerm>(g));
  out << "\n";
  for (std::size_t i = 0; i < b.time_s.size(); ++i) {
    if (!b.report_time[i]) continue;
    out << "  " << significant_number_text(b.time_s[i]) << " s";
    const double total = b.predicted_variance_m2[i];
    for (const double v : b.variance_m2[i])
      out << "  " << significant_number_text(total > 0.0 ? 100.0 * v / total : 0.0, 3);
    out << "\n";
  }
  return out.str();
}

}  // namespace imunoise::report
