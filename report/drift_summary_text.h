/// @file
/// @brief The summary `imunoise drift` prints on the terminal: the protocol, the assumed
/// location and heading, then per report time the predicted DRMS, the recording's RMS, their
/// ratio with its 95 % interval, the mean NEES with its band, the 1/2/3-σ coverage and the
/// Monte Carlo RMS when it ran (theory.md §7.7). Pure: a summary in, text out.
#pragma once

#include <string>

#include "pipeline/drift_run.h"

namespace imunoise::report {

/// The terminal summary of SUMMARY; every line ends with '\n'.
std::string drift_summary_text(const pipeline::DriftSummary& summary);

/// The drift budget as a table: per report time (the rows of BUDGET so flagged) the share [%]
/// of each source in the predicted horizontal variance (pipeline::DriftBudget); empty text
/// without a report time.
std::string drift_budget_text(const pipeline::DriftBudget& budget);

}  // namespace imunoise::report
