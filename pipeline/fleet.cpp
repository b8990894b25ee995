/// @file
/// @brief Many units of one IMU model side by side (see fleet.h).
#include "pipeline/fleet.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "common/errors.h"

namespace imunoise::pipeline {

namespace {

double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  const double upper = v[mid];
  if (v.size() % 2 == 1) return upper;
  const double lower = *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid));
  return 0.5 * (lower + upper);
}

}  // namespace

const char* spec_verdict_name(SpecVerdict verdict) {
  switch (verdict) {
    case SpecVerdict::pass:
      return "pass";
    case SpecVerdict::fail:
      return "fail";
    case SpecVerdict::undecided:
      return "undecided";
  }
  return "?";
}

SpecVerdict judge_against_spec(const models::Estimate& e, double max_si) {
  if (e.identified && e.ci_low > max_si) return SpecVerdict::fail;
  // Not identified: [0, upper bound]; a term without a bound (ci_high 0) is not shown by the
  // data at all, so nothing says it exceeds the maximum — and nothing bounds it: undecided.
  if (e.ci_high > 0.0 && e.ci_high <= max_si) return SpecVerdict::pass;
  return SpecVerdict::undecided;
}

FleetResult analyze_fleet(std::span<const FleetUnit> units, const std::optional<FleetSpec>& spec) {
  IMUNOISE_CHECK(!units.empty(), InputError, "fleet: no unit given");
  FleetResult r;
  r.spec = spec;
  // Axis names in first-seen order, with their sensor.
  std::vector<std::pair<std::string, SensorKind>> axes;
  for (const FleetUnit& u : units) {
    IMUNOISE_CHECK(!u.model.axes.empty(), InputError,
                   "fleet: " + u.name + ": the model has no axis");
    r.units.push_back(u.name);
    for (const models::AxisModel& a : u.model.axes) {
      if (std::none_of(axes.begin(), axes.end(), [&](const auto& p) { return p.first == a.name; }))
        axes.emplace_back(a.name, a.kind);
    }
  }
  for (std::size_t i = 0; i < units.size(); ++i) {
    for (const models::AxisModel& a : units[i].model.axes) {
      for (NoiseTerm term : kNoiseTerms) {
        FleetEntry e;
        e.unit = i;
        e.axis = a.name;
        e.sensor = a.kind;
        e.term = term;
        e.estimate = a.terms[term];
        e.robust_z = std::numeric_limits<double>::quiet_NaN();
        if (spec) {
          for (const SpecLimit& limit : spec->limits) {
            if (limit.sensor != a.kind || limit.term != term) continue;
            e.spec_max_si = limit.max_si;
            e.spec_verdict = judge_against_spec(e.estimate, limit.max_si);
          }
        }
        r.entries.push_back(std::move(e));
      }
    }
  }
  for (const auto& [axis, sensor] : axes) {
    for (NoiseTerm term : kNoiseTerms) {
      TermDistribution d;
      d.axis = axis;
      d.sensor = sensor;
      d.term = term;
      std::vector<FleetEntry*> with;
      std::vector<double> logs, values;
      for (FleetEntry& e : r.entries) {
        if (e.axis != axis || e.term != term) continue;
        ++d.units;
        if (!e.estimate.identified || !(e.estimate.value > 0.0)) continue;
        with.push_back(&e);
        values.push_back(e.estimate.value);
        logs.push_back(std::log10(e.estimate.value));
      }
      d.identified = values.size();
      if (!values.empty()) {
        d.median_si = median_of(values);
        d.min_si = *std::min_element(values.begin(), values.end());
        d.max_si = *std::max_element(values.begin(), values.end());
      }
      if (logs.size() >= 2) {
        const double center = median_of(logs);
        std::vector<double> deviations;
        for (double l : logs) deviations.push_back(std::fabs(l - center));
        const double mad = median_of(deviations);
        // 1.4826 = 1/Φ⁻¹(3/4): the MAD of a normal variable times it is its σ.
        d.log10_spread = 1.4826 * mad;
        if (logs.size() >= 3 && mad > 0.0) {
          for (std::size_t k = 0; k < with.size(); ++k) {
            // Iglewicz & Hoaglin (1993): M = 0.6745 (x − median) / MAD.
            with[k]->robust_z = 0.6745 * (logs[k] - center) / mad;
            // An outlier is far from the fleet in the fleet's own spread and its own interval
            // excludes the fleet median: a unit whose estimate is merely uncertain (a short
            // record, a term barely identified) is not flagged for its scatter.
            const models::Estimate& est = with[k]->estimate;
            const double median_value = std::pow(10.0, center);
            with[k]->outlier = std::fabs(with[k]->robust_z) > kOutlierRobustZ &&
                               (est.ci_low > median_value || est.ci_high < median_value);
            if (with[k]->outlier) d.outliers.push_back(with[k]->unit);
          }
        }
      }
      r.distributions.push_back(std::move(d));
    }
  }
  if (spec) {
    r.unit_verdicts.assign(units.size(), SpecVerdict::pass);
    for (const FleetEntry& e : r.entries) {
      if (!e.spec_verdict) continue;
      SpecVerdict& v = r.unit_verdicts[e.unit];
      if (*e.spec_verdict == SpecVerdict::fail) v = SpecVerdict::fail;
      if (*e.spec_verdict == SpecVerdict::undecided && v == SpecVerdict::pass)
        v = SpecVerdict::undecided;
    }
  }
  return r;
}

}  // namespace imunoise::pipeline
