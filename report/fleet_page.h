/// @file
/// @brief The page and the terminal summary of `imunoise fleet` (pure: a pipeline::FleetResult
/// in, a ReportPage or text out; report/write_report.h writes fleet.html). The page opens with
/// the verdict — per unit pass / fail / undecided against the spec with the terms that decide
/// it, and the robust outliers — then per sensor the distribution of every axis and term over
/// the units in datasheet units, then (folded) every unit's value with its interval.
#pragma once

#include <string>

#include "pipeline/fleet.h"
#include "report/html_page.h"

namespace imunoise::report {

/// The fleet page of RESULT; WRITTEN is the time the page states it was written.
ReportPage build_fleet_page(const pipeline::FleetResult& result, const std::string& written);

/// The summary `imunoise fleet` prints: per unit its verdict and the terms behind it, then the
/// outliers. Every line ends with '\n'.
std::string fleet_summary_text(const pipeline::FleetResult& result);

}  // namespace imunoise::report
