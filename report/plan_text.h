/// @file
/// @brief What `imunoise plan` prints: the shortest recording meeting every target, per axis
/// the duration that identifies each term and the one that meets its target, then per sensor
/// the table of duration vs expected relative half-width of each term's 95 % interval
/// (pipeline/recording_plan.h). Pure: a plan in, text out.
#pragma once

#include <string>

#include "pipeline/recording_plan.h"

namespace imunoise::report {

/// A duration a person reads: "45 s", "12 min", "6.4 h", "2.5 d"; "> 30 d" style text is the
/// caller's. 3 significant digits at most.
std::string human_duration(double seconds);

/// The text of PLAN (a plan_recording result: required durations, then the table rows up to
/// the first table duration at or above every finite required duration). SOURCE names the
/// model file in the first line. Every line ends with '\n'.
std::string plan_text(const pipeline::RecordingPlan& plan, const std::string& source);

/// The text of a precision_at result: per sensor, axis and term the expected relative
/// half-width at the one duration, whether each term is identified and whether each target
/// is met.
std::string precision_text(const pipeline::RecordingPlan& plan, const std::string& source);

}  // namespace imunoise::report
