// imunoise._core.deviation and .psd: one Allan-family curve of a series with its intervals
// (analysis::series_deviation, the computation of `imunoise allan`) and the multi-rate
// log-frequency PSD (analysis::multirate_psd, the PSD of `imunoise analyze`).
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "analysis/deviation.h"
#include "analysis/deviation_type.h"
#include "analysis/multirate_psd.h"
#include "analysis/series_deviation.h"
#include "analysis/tau_grid.h"
#include "common/errors.h"
#include "common/number_text.h"
#include "python/core_bindings.h"

namespace imunoise::python {
namespace {

void require_rate(double rate_hz) {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
    throw InputError("rate: expected a sample rate > 0 Hz, got " + shortest_number_text(rate_hz));
  }
}

/// The grid of TAUS: a grid name ("octave", "decade", "all", "log:N") or averaging factors.
analysis::TauGridSpec tau_grid_of(const py::object& taus) {
  if (py::isinstance<py::str>(taus)) return analysis::parse_tau_grid(taus.cast<std::string>());
  std::string text;
  for (const py::handle item : taus) {
    long long factor = 0;
    if (PyIndex_Check(item.ptr())) {  // int, numpy integers
      factor = py::reinterpret_steal<py::int_>(PyNumber_Index(item.ptr())).cast<long long>();
    } else if (py::isinstance<py::float_>(item) &&
               std::floor(item.cast<double>()) == item.cast<double>() &&
               std::abs(item.cast<double>()) < 9e15) {
      factor = static_cast<long long>(item.cast<double>());
    } else {
      throw InputError("taus: expected a grid name or whole averaging factors m, got " +
                       py::repr(item).cast<std::string>());
    }
    if (!text.empty()) text += ',';
    text += std::to_string(factor);
  }
  return analysis::parse_tau_grid(text);
}

py::dict deviation(const DoubleArray& x, const std::string& kind, double rate_hz,
                   const std::string& data, const py::object& taus, double confidence,
                   std::optional<int> alpha, bool bias_corrected, unsigned threads,
                   std::optional<double> tau0_s) {
  const auto type = analysis::parse_deviation_type(kind);
  if (!type) {
    throw InputError("kind: unknown deviation '" + kind +
                     "' (adev, oadev, mdev, tdev, hdev, ohdev, totdev, mtotdev, ttotdev, "
                     "htotdev, theo1)");
  }
  if (tau0_s) {
    if (!(*tau0_s > 0.0) || !std::isfinite(*tau0_s)) {
      throw InputError("tau0_s: expected a sample period > 0 s, got " +
                       shortest_number_text(*tau0_s));
    }
  } else {
    require_rate(rate_hz);
  }
  if (data != "rate" && data != "phase") {
    throw InputError("data: expected 'rate' or 'phase', got '" + data + "'");
  }
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw InputError("confidence: expected a level in (0, 1), got " +
                     shortest_number_text(confidence));
  }
  const auto series_kind =
      data == "phase" ? analysis::SeriesKind::kPhase : analysis::SeriesKind::kRate;
  const std::span<const double> values = finite_values(x, "x");
  if (values.size() < analysis::min_series_values(series_kind)) {
    throw InputError("x: " + std::to_string(values.size()) + " values; a " + data +
                     " series needs at least " +
                     std::to_string(analysis::min_series_values(series_kind)));
  }
  const analysis::TauGridSpec grid = tau_grid_of(taus);
  analysis::DeviationOptions options;
  options.type = *type;
  options.confidence = confidence;
  options.alpha = alpha;
  options.bias_corrected = bias_corrected;
  options.threads = threads;
  analysis::DeviationCurve curve;
  {
    py::gil_scoped_release unlocked;  // X stays referenced by the caller's frame
    curve = analysis::series_deviation(values, series_kind, tau0_s ? *tau0_s : 1.0 / rate_hz, grid,
                                       options, "x");
  }
  const std::size_t n = curve.points.size();
  py::array_t<std::int64_t> m(n), n_terms(n), alpha_used(n);
  py::array_t<double> tau(n), value(n), edf(n), low(n), high(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& p = curve.points[i];
    m.mutable_at(i) = p.m;
    n_terms.mutable_at(i) = p.n_terms;
    alpha_used.mutable_at(i) = p.alpha;
    tau.mutable_at(i) = p.tau_s;
    value.mutable_at(i) = p.value;
    edf.mutable_at(i) = p.edf;
    low.mutable_at(i) = p.ci_low;
    high.mutable_at(i) = p.ci_high;
  }
  py::dict out;
  out["kind"] = std::string(analysis::to_string(*type));
  out["confidence"] = curve.confidence;
  out["tau0_s"] = curve.tau0_s;
  out["m"] = m;
  out["tau_s"] = tau;
  out["value"] = value;
  out["n_terms"] = n_terms;
  out["alpha"] = alpha_used;
  out["edf"] = edf;
  out["ci_low"] = low;
  out["ci_high"] = high;
  return out;
}

py::dict psd(const DoubleArray& x, double rate_hz, int bins_per_decade,
             std::size_t level_segment_length) {
  require_rate(rate_hz);
  const std::span<const double> values = finite_values(x, "x");
  if (values.size() < 256) {
    throw InputError("x: " + std::to_string(values.size()) + " values; the PSD needs at least 256");
  }
  if (bins_per_decade < 1 || bins_per_decade > 1000) {
    throw InputError("bins_per_decade: expected 1 to 1000, got " + std::to_string(bins_per_decade));
  }
  if (level_segment_length < 256 || (level_segment_length & (level_segment_length - 1)) != 0) {
    throw InputError("level_segment_length: expected a power of two >= 256, got " +
                     std::to_string(level_segment_length));
  }
  analysis::MultirateOptions options;
  options.bins_per_decade = bins_per_decade;
  options.level_segment_length = level_segment_length;
  analysis::Spectrum s;
  {
    py::gil_scoped_release unlocked;
    s = analysis::multirate_psd(values, rate_hz, options);
  }
  py::dict out;
  out["frequency_hz"] = py::array_t<double>(s.frequency_hz.size(), s.frequency_hz.data());
  out["density"] = py::array_t<double>(s.density.size(), s.density.data());
  out["dof"] = py::array_t<double>(s.dof.size(), s.dof.data());
  out["resolution_hz"] = s.resolution_hz;
  out["segment_length"] = s.segment_length;
  out["sample_variance"] = s.sample_variance;
  out["integrated_power"] = s.integrated_power;
  return out;
}

/// The variance KIND at each factor of M of the phase PHASE (no stop ratio, no interval: the
/// plain estimator, for the allantools layer), with its term count; a factor without a term
/// is an InputError.
py::tuple variance_at(const DoubleArray& phase, const std::string& kind,
                      const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& m,
                      double tau0_s) {
  const auto type = analysis::parse_deviation_type(kind);
  if (!type) throw InputError("kind: unknown deviation '" + kind + "'");
  if (!(tau0_s > 0.0) || !std::isfinite(tau0_s)) {
    throw InputError("tau0_s: expected > 0, got " + shortest_number_text(tau0_s));
  }
  const std::span<const double> x = finite_values(phase, "phase");
  const auto n_phase = static_cast<std::int64_t>(x.size());
  const std::size_t count = static_cast<std::size_t>(m.size());
  std::vector<std::int64_t> factors(m.data(), m.data() + count);
  for (std::int64_t f : factors) {
    if (f < 1 || analysis::estimator_term_count(*type, n_phase, f) < 1) {
      throw InputError("m = " + std::to_string(f) + ": no term of " + kind + " on " +
                       std::to_string(n_phase) + " phase samples");
    }
  }
  py::array_t<double> variance(count);
  py::array_t<std::int64_t> terms(count);
  std::vector<analysis::VarianceEstimate> out(count);
  {
    py::gil_scoped_release unlocked;
    if (*type == analysis::DeviationType::oadev || *type == analysis::DeviationType::ohdev) {
      // The cache-sharing passes of the analysis, bit for bit allan_family_variance.
      out = analysis::overlapping_variances(*type, x, factors, tau0_s);
    } else {
      for (std::size_t i = 0; i < count; ++i) {
        out[i] = analysis::allan_family_variance(*type, x, factors[i], tau0_s);
      }
    }
  }
  for (std::size_t i = 0; i < count; ++i) {
    variance.mutable_at(i) = out[i].variance;
    terms.mutable_at(i) = out[i].n_terms;
  }
  return py::make_tuple(variance, terms);
}

}  // namespace

void add_deviation_functions(py::module_& m) {
  m.def("deviation", &deviation, py::arg("x"), py::arg("kind") = "oadev", py::arg("rate") = 1.0,
        py::arg("data") = "rate", py::arg("taus") = py::str("octave"),
        py::arg("confidence") = 0.683, py::arg("alpha") = py::none(),
        py::arg("bias_corrected") = false, py::arg("threads") = 0u, py::arg("tau0_s") = py::none());
  m.def("variance_at", &variance_at, py::arg("phase"), py::arg("kind"), py::arg("m"),
        py::arg("tau0_s"));
  m.def(
      "phase_from_rate",
      [](const DoubleArray& rate, double tau0_s) {
        const std::vector<double> x = analysis::phase_from_rate(finite_values(rate, "x"), tau0_s);
        return py::array_t<double>(x.size(), x.data());
      },
      py::arg("x"), py::arg("tau0_s"));
  m.def("psd", &psd, py::arg("x"), py::arg("rate"), py::arg("bins_per_decade") = 10,
        py::arg("level_segment_length") = 4096);
}

}  // namespace imunoise::python
