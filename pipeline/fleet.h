/// @file
/// @brief Many units of one IMU model, side by side (`imunoise fleet`, issue 23): per axis and
/// term the distribution of the fitted coefficients over the units (median, spread, robust
/// outliers by the median absolute deviation of the log), and each unit against a datasheet
/// spec with its interval. Pure computation: fitted models in, a FleetResult out (io/fleet_csv
/// writes it, report/fleet_page shows it).
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/noise_term.h"
#include "common/sensor_kind.h"
#include "models/noise_model.h"

namespace imunoise::pipeline {

/// One unit: its name (e.g. its results directory) and its fitted model.
struct FleetUnit {
  std::string name;
  models::NoiseModel model;
};

/// A datasheet maximum of one term of one sensor [SI unit of the term].
struct SpecLimit {
  SensorKind sensor = SensorKind::gyro;
  NoiseTerm term = NoiseTerm::white_noise;
  double max_si = 0.0;  ///< > 0
};

/// A datasheet spec: the maxima the units are held to.
struct FleetSpec {
  std::string name;  ///< free text ("ACME IMU-100 datasheet rev B")
  std::vector<SpecLimit> limits;
};

/// How a unit's term compares with its maximum, judged by its interval [ci_low, ci_high]:
/// pass when ci_high ≤ max (the unit meets it at the interval's level), fail when ci_low > max
/// (it exceeds it at that level), undecided otherwise (the interval straddles the maximum:
/// record longer). A term not identified has [0, upper bound]: pass or undecided, never fail.
enum class SpecVerdict { pass, fail, undecided };

/// "pass", "fail", "undecided".
const char* spec_verdict_name(SpecVerdict verdict);

/// The robust z-score above which a unit's coefficient is an outlier (Iglewicz & Hoaglin's
/// modified z-score, 0.6745·(x − median)/MAD, on log10 of the coefficient: noise coefficients
/// of one design spread multiplicatively).
inline constexpr double kOutlierRobustZ = 3.5;

/// One unit's coefficient of one axis and term.
struct FleetEntry {
  std::size_t unit = 0;  ///< index into the units
  std::string axis;      ///< gyro_x …
  SensorKind sensor = SensorKind::gyro;
  NoiseTerm term = NoiseTerm::white_noise;
  models::Estimate estimate;
  /// Modified z-score of log10(value) among the units that identified this axis and term; NaN
  /// when the unit did not identify it or the MAD is 0 or fewer than 3 units identified it.
  double robust_z = 0.0;
  /// |robust_z| > kOutlierRobustZ and the unit's interval excludes the fleet's median (the
  /// median of the log, i.e. the geometric median): far from the fleet beyond its own
  /// uncertainty.
  bool outlier = false;
  std::optional<double> spec_max_si;        ///< the spec's maximum, when it has one
  std::optional<SpecVerdict> spec_verdict;  ///< with spec_max_si
};

/// The distribution of one axis and term over the units that identified it.
struct TermDistribution {
  std::string axis;
  SensorKind sensor = SensorKind::gyro;
  NoiseTerm term = NoiseTerm::white_noise;
  std::size_t units = 0;              ///< units with this axis
  std::size_t identified = 0;         ///< of them, how many identified the term
  double median_si = 0.0;             ///< of the identified values (0 when none)
  double min_si = 0.0, max_si = 0.0;  ///< range of the identified values
  /// MAD of log10(value) × 1.4826 (the σ of a normal log), 0 with fewer than 2 values.
  double log10_spread = 0.0;
  std::vector<std::size_t> outliers;  ///< units flagged, by index
};

/// Everything `imunoise fleet` reports.
struct FleetResult {
  std::vector<std::string> units;  ///< names, in input order
  std::optional<FleetSpec> spec;
  std::vector<FleetEntry> entries;              ///< unit-major, then axis and term in model order
  std::vector<TermDistribution> distributions;  ///< per axis (first-seen order) and term
  /// Per unit: fail if any term fails, else undecided if any is undecided, else pass; empty
  /// without a spec.
  std::vector<SpecVerdict> unit_verdicts;
};

/// Compares UNITS (≥ 1; every axis name of each unit is matched by name across units) and,
/// with SPEC, holds each axis of SPEC's sensors to its maxima.
/// @throws InputError when UNITS is empty or a unit has no axis.
FleetResult analyze_fleet(std::span<const FleetUnit> units, const std::optional<FleetSpec>& spec);

/// The verdict of one estimate against MAX_SI (see SpecVerdict).
SpecVerdict judge_against_spec(const models::Estimate& estimate, double max_si);

}  // namespace imunoise::pipeline
