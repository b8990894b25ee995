/// @file
/// @brief The report's tables of saved results (pure: typed results in, report::Table out): the
/// fitted coefficients in SI and datasheet units, the Gauss–Markov forms of B, the sampling
/// checks and the drift consistency checks.
#pragma once

#include <string>

#include "models/noise_model.h"
#include "pipeline/drift_run.h"
#include "pipeline/sampling_checks.h"
#include "report/html_page.h"

namespace imunoise::report {

/// V with at most DIGITS significant digits (significant_number_text), "—" when not finite:
/// every number of the report's text.
std::string number_cell(double v, int digits = 4);

/// "summary-table": per axis and term the value and interval in SI and datasheet units, the
/// IEEE-952 read-off and the method ("—" = not identified; the interval is then "< upper
/// bound").
Table summary_table(const models::NoiseModel& model);

/// "gauss-markov-table": per axis each B → Gauss–Markov conversion (one row per convention)
/// and each fitted GM term with its intervals. No rows when the model has none.
Table gauss_markov_table(const models::NoiseModel& model);

/// "sampling-table": samples, rates, duration, gaps, stamp order, jitter and rows dropped of
/// REPORT; a quantity that is not finite is left out.
Table sampling_table(const pipeline::SamplingReport& report);

/// "drift-table": per checkpoint of SUMMARY the predicted DRMS, recorded RMS, RMS ratio,
/// coverage and mean NEES with their bands (a non-finite bound leaves its interval out).
Table drift_table(const pipeline::DriftSummary& summary);

/// "drift-budget-table": per source (N, B, K, GM, R, alignment, heading; ins::DriftBudgetTerm)
/// and report time of BUDGET (its rows flagged report_time) the σ that source alone gives
/// [m] (√ of its variance) and its share of the predicted horizontal variance [%]; a last
/// row "total" with the predicted DRMS and 100 %. The variances add (independent sources),
/// so the σ add in quadrature to the DRMS. No rows without a report time.
Table drift_budget_table(const pipeline::DriftBudget& budget);

}  // namespace imunoise::report
