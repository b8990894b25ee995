// imunoise._core.fit and .export_config: the analysis of a Recording with the settings of
// `imunoise analyze` (pipeline::analyze_recording; the same defaults, so the same model), the
// model as the text of model.yaml (io/noise_model_yaml, parsed on the Python side into objects
// mirroring it) with each axis's curves, and the filter configs of `imunoise export`.
#include <pybind11/stl.h>

#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/tau_grid.h"
#include "common/errors.h"
#include "common/number_text.h"
#include "io/filter_export.h"
#include "io/noise_model_yaml.h"
#include "models/bias_instability_gm.h"
#include "pipeline/gap_policy.h"
#include "pipeline/recording.h"
#include "pipeline/recording_analysis.h"
#include "python/core_bindings.h"

namespace imunoise::python {
namespace {

/// The settings of fit(), as `imunoise analyze`'s flags (tools/analysis_options.cpp) with the
/// Python argument names in messages.
pipeline::RecordingAnalysisOptions fit_options(
    double tau0_s, const std::string& taus, double confidence, int interval_draws,
    std::optional<int> bootstrap, std::uint64_t seed, std::optional<bool> gauss_markov,
    const std::vector<double>& sinusoid_hz, double tau_min_s, double tau_max_s, bool low_pass_check,
    const std::string& gaps, unsigned threads) {
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw InputError("confidence: expected a level in (0, 1), got " +
                     shortest_number_text(confidence));
  }
  if (bootstrap && (*bootstrap == 1 || *bootstrap < 0)) {
    throw InputError("bootstrap: expected 0 (least-squares intervals) or at least 2 replicates");
  }
  if (interval_draws == 1 || interval_draws < 0) {
    throw InputError("interval_draws: expected 0 (least-squares intervals) or at least 2");
  }
  for (double f : sinusoid_hz) {
    if (!(f > 0.0) || !(f < 0.5 / tau0_s)) {
      throw InputError("sinusoid_hz: " + shortest_number_text(f) + " Hz is not in (0, Nyquist = " +
                       shortest_number_text(0.5 / tau0_s) + " Hz)");
    }
  }
  pipeline::RecordingAnalysisOptions options;
  pipeline::AxisAnalysisOptions& axis = options.axis;
  axis.confidence = confidence;
  axis.grid = analysis::parse_tau_grid(taus);
  axis.interval_source = bootstrap ? pipeline::ReplicateSource::simulated_record
                                   : pipeline::ReplicateSource::variance_distribution;
  axis.bootstrap_replicates = bootstrap ? *bootstrap : interval_draws;
  axis.bootstrap_setting = "bootstrap=N or interval_draws=N";
  axis.seed = seed;
  // None: automatic, as analyze without --gauss-markov / --no-gauss-markov.
  axis.fit.gauss_markov = !gauss_markov   ? analysis::GaussMarkovMode::automatic
                          : *gauss_markov ? analysis::GaussMarkovMode::on
                                          : analysis::GaussMarkovMode::off;
  axis.fit.tau_min_s = tau_min_s;
  axis.fit.tau_max_s = tau_max_s;
  axis.fit.sinusoid_frequencies_hz = sinusoid_hz;
  axis.auto_low_pass = low_pass_check;
  options.gaps = pipeline::parse_gap_policy(gaps, "gaps");
  options.gap_policy_setting = "gaps";
  options.threads = threads;
  return options;
}

py::dict curve_dict(const analysis::DeviationCurve& c) {
  const std::size_t n = c.points.size();
  py::array_t<double> tau(n), value(n), low(n), high(n), edf(n);
  for (std::size_t i = 0; i < n; ++i) {
    tau.mutable_at(i) = c.points[i].tau_s;
    value.mutable_at(i) = c.points[i].value;
    low.mutable_at(i) = c.points[i].ci_low;
    high.mutable_at(i) = c.points[i].ci_high;
    edf.mutable_at(i) = c.points[i].edf;
  }
  py::dict d;
  d["tau_s"] = tau;
  d["value"] = value;
  d["ci_low"] = low;
  d["ci_high"] = high;
  d["edf"] = edf;
  return d;
}

py::dict fit(const pipeline::Recording& recording, const std::string& taus, double confidence,
             int interval_draws, std::optional<int> bootstrap, std::uint64_t seed,
             std::optional<bool> gauss_markov, const std::vector<double>& sinusoid_hz,
             double tau_min_s, double tau_max_s, bool low_pass_check, const std::string& gaps,
             unsigned threads) {
  const pipeline::RecordingAnalysisOptions options =
      fit_options(recording.sample_period_s, taus, confidence, interval_draws, bootstrap, seed,
                  gauss_markov, sinusoid_hz, tau_min_s, tau_max_s, low_pass_check, gaps, threads);
  pipeline::RecordingAnalysis result;
  {
    py::gil_scoped_release unlocked;
    result = pipeline::analyze_recording(recording, recording.source_path, options);
  }
  py::dict axes;
  for (const pipeline::AxisAnalysis& a : result.axes) {
    py::dict d;
    d["oadev"] = curve_dict(a.oadev);
    d["ohdev"] = curve_dict(a.ohdev);
    d["psd"] = py::dict(
        py::arg("frequency_hz") =
            py::array_t<double>(a.psd.frequency_hz.size(), a.psd.frequency_hz.data()),
        py::arg("density") = py::array_t<double>(a.psd.density.size(), a.psd.density.data()),
        py::arg("dof") = py::array_t<double>(a.psd.dof.size(), a.psd.dof.data()));
    axes[py::str(a.model.name)] = d;
  }
  py::dict out;
  out["model_yaml"] = io::format_model_yaml(result.model);
  out["axes"] = axes;
  out["tau0_s"] = result.tau0_s;
  return out;
}

std::string export_text(const std::string& model_yaml, const std::string& source,
                        const std::string& format, double rate_hz, const std::string& axis,
                        bool conservative, const std::string& gm_convention,
                        double correction_interval_s) {
  const auto f = io::parse_export_format(format);
  if (!f) {
    std::string names;
    for (auto e : io::all_export_formats())
      names += (names.empty() ? "" : ", ") + std::string(io::export_format_name(e));
    throw InputError("format: unknown format '" + format + "'; choose one of " + names);
  }
  const auto a = models::axis_choices_by_name().find(axis);
  if (a == models::axis_choices_by_name().end()) {
    throw InputError("axis: expected worst, mean, x, y, z or each, got '" + axis + "'");
  }
  const auto convention = models::gm_conventions_by_name().find(gm_convention);
  if (convention == models::gm_conventions_by_name().end()) {
    throw InputError("gm_convention: unknown convention '" + gm_convention + "'");
  }
  const models::NoiseModel model = io::parse_model_yaml(model_yaml, source);
  io::ExportRequest request;
  request.format = *f;
  request.rate_hz = rate_hz;
  request.parameters.axis = a->second;
  request.parameters.conservative = conservative;
  request.parameters.gm_convention = convention->second;
  request.parameters.correction_interval_s = correction_interval_s;
  request.parameters.setting_names = {"axis", "correction_interval_s"};
  request.model_path = source;
  request.command = "imunoise.export(" + source + ", '" + format + "')";
  return io::export_config(model, request);
}

}  // namespace

void add_model_functions(py::module_& m) {
  m.def("fit", &fit, py::arg("recording"), py::kw_only(), py::arg("taus") = "log:10",
        py::arg("confidence") = 0.95, py::arg("interval_draws") = 200,
        py::arg("bootstrap") = py::none(), py::arg("seed") = 1,
        py::arg("gauss_markov") = py::none(), py::arg("sinusoid_hz") = std::vector<double>{},
        py::arg("tau_min_s") = 0.0, py::arg("tau_max_s") = 0.0, py::arg("low_pass_check") = true,
        py::arg("gaps") = "refuse", py::arg("threads") = 0u);
  m.def("export_config", &export_text, py::arg("model_yaml"), py::arg("source"), py::arg("format"),
        py::kw_only(), py::arg("rate_hz") = 0.0, py::arg("axis") = "worst",
        py::arg("conservative") = false, py::arg("gm_convention") = "peak_match",
        py::arg("correction_interval_s") = 0.0);
  m.def(
      "parse_model_yaml",
      [](const std::string& text, const std::string& source) {
        return io::format_model_yaml(io::parse_model_yaml(text, source));
      },
      py::arg("text"), py::arg("source"));
}

}  // namespace imunoise::python
