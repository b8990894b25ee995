/// @file
/// @brief The data-quality findings of a recording's sampling report, one line each, as
/// model.yaml's data_quality list and the summary print them.
#pragma once

#include <string>
#include <vector>

#include "pipeline/sampling_checks.h"

namespace imunoise::pipeline {

/// Data-quality findings of a sampling report, one line each (empty = nothing to say): gaps,
/// non-monotonic and duplicate stamps, jitter above 1 % of the interval, dropped NaN/Inf rows,
/// per channel saturation, full-scale excursions and the output LSB.
std::vector<std::string> quality_findings(const SamplingReport& report);

}  // namespace imunoise::pipeline
