/// @file
/// @brief The data-quality findings of a recording's sampling report, one line each, as
/// model.yaml's data_quality list and the summary print them.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/outliers.h"
#include "pipeline/sampling_checks.h"
#include "pipeline/start_transient.h"

namespace imunoise::pipeline {

/// Data-quality findings of a sampling report, one line each (empty = nothing to say): gaps,
/// non-monotonic and duplicate stamps, jitter above 1 % of the interval, dropped NaN/Inf rows,
/// per channel saturation, full-scale excursions and the output LSB.
std::vector<std::string> quality_findings(const SamplingReport& report);

/// What was done about a start transient: the samples dropped and whether the trim was the
/// automatic one (else given by the user, SETTING names the flag, e.g. "--trim-start").
struct StartTrim {
  double trim_s = 0.0;
  bool automatic = true;
  std::string setting = "trim_start";
};

/// The warm-up finding of SCAN with its cause and remedy, or "" when nothing was detected and
/// nothing was trimmed (a user's trim of a clean record is still stated). UNITS: the unit of
/// each of scan.channels.
std::string start_transient_finding(const StartTransient& scan, const StartTrim& trim,
                                    std::span<const std::string> units);

/// The outlier finding of channel NAME [UNIT] with its cause and remedy ("" when SCAN is not
/// significant). N_EFFECT is (N with the outliers kept) / (N without) − 1 from the
/// first-difference RMS; SETTING names the policy flag.
std::string outlier_finding(const std::string& name, std::string_view unit, std::size_t samples,
                            const OutlierScan& scan, OutlierPolicy policy, double n_effect,
                            std::string_view setting);

}  // namespace imunoise::pipeline
