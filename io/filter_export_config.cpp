// The parts of io/filter_export shared by its writers (io/filter_export_internal.h): the
// header under construction, the number form, the white + random-walk pair, and the lines
// and refusals for terms not identified.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/errors.h"
#include "io/filter_export_internal.h"

namespace imunoise::io::detail {
namespace {

using models::FilterParameters;
using models::SensorAxisParameters;
using models::SensorParameters;

/// Formats whose consumer refuses or breaks on a 0 it carries: Kalibr's ImuParameters and
/// Kimera's ImuFrontend reject it, Basalt divides by it (bias weight 1/std), LIO-SAM and GTSAM
/// build a zero-sigma noise model from it.
bool refuses_zero(ExportFormat f) {
  return f == ExportFormat::kalibr || f == ExportFormat::kimera || f == ExportFormat::basalt ||
         f == ExportFormat::lio_sam || f == ExportFormat::gtsam;
}

}  // namespace

std::string real(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  std::string s(buffer);
  if (s.find_first_of("ni") != std::string::npos || s.find('.') != std::string::npos) return s;
  const auto e = s.find('e');
  if (e == std::string::npos) return s + ".0";
  return s.insert(e, ".0");
}

std::string bracketed(int i, char open, char close) {
  std::string s(1, open);
  s += std::to_string(i);
  s += close;
  return s;
}

std::vector<NoiseTerm> carried_terms(ExportFormat format) {
  switch (format) {
    case ExportFormat::native:
      return {};
    case ExportFormat::kf_gins:
    case ExportFormat::gnss_ins_sim:
    case ExportFormat::imu_utils:
      return {NoiseTerm::white_noise, NoiseTerm::bias_instability};
    case ExportFormat::matlab:
      return {NoiseTerm::white_noise, NoiseTerm::bias_instability, NoiseTerm::random_walk};
    default:
      return {NoiseTerm::white_noise, NoiseTerm::random_walk};
  }
}

std::vector<std::string> unidentified_lines(const FilterParameters& p, ExportFormat format,
                                            bool strict) {
  const auto carried = carried_terms(format);
  const std::string name(export_format_name(format));
  std::vector<std::string> lines;
  std::vector<std::pair<std::string, NoiseTerm>> seen;
  for (const auto* s : {&p.gyro, &p.accel}) {
    if (!*s) continue;
    for (const auto& slot : (*s)->axes) {
      for (const auto& u : slot.unidentified) {
        if (std::find(carried.begin(), carried.end(), u.term) == carried.end()) continue;
        if (std::find(seen.begin(), seen.end(), std::pair{u.axis, u.term}) != seen.end()) continue;
        seen.emplace_back(u.axis, u.term);
        const std::string what =
            u.axis + " " + std::string(term_name(u.term)) + " (" + term_symbol(u.term) + ")";
        const std::string unit(models::term_si_unit(u.term, (*s)->kind));
        if (strict)
          throw InputError(name + ": " + what + " is not identified, and --strict refuses " +
                           (u.upper_bound > 0.0
                                ? "to use its upper bound " + real(u.upper_bound) + " " + unit
                                : std::string("a term the model has no value for")));
        if (u.substituted) {
          lines.push_back("upper bound: " + what + " is not identified; its upper bound " +
                          real(u.upper_bound) + " " + unit +
                          " is used in its place (--strict refuses instead)");
        } else if (u.upper_bound > 0.0) {
          lines.push_back("not identified: " + what +
                          " — a fitted Gauss-Markov term stands for the bias; 0 is written");
        } else if (refuses_zero(format)) {
          throw InputError(name + ": " + what +
                           " is not identified and the model has no upper bound for it; " +
                           std::string(export_consumer_name(format)) +
                           " needs a value > 0 — analyse a longer recording, or give the term a "
                           "value in the model");
        } else {
          lines.push_back("not identified: " + what +
                          " has neither a value nor an upper bound in the model: 0 is written");
        }
      }
    }
  }
  return lines;
}

Config::Config(std::string comment, const models::NoiseModel& model, const ExportRequest& request,
               double rate_hz)
    : comment_(std::move(comment)), format_(request.format), strict_(request.strict) {
  line(std::string("imunoise export for ") + std::string(export_consumer_name(request.format)));
  line("model: " + (request.model_path.empty() ? std::string("(in memory)") : request.model_path) +
       " — sensor \"" + model.sensor_name + "\", fitted from \"" + model.source + "\", " +
       real(model.duration_s) + " s at " + real(model.sample_rate_hz) + " Hz, written by " +
       model.software);
  if (!request.command.empty()) line("command: " + request.command);
  line("rate of the discrete values below: " + real(rate_hz) + " Hz (dt = " + real(1.0 / rate_hz) +
       " s)");
  line("noise densities are two-sided (S = N^2, theory.md §1.2), as Kalibr's sigma_g");
}

void Config::rules(const FilterParameters& p) {
  line("rules:");
  for (const auto& r : p.rules) line("  " + r);
  for (const auto& l : unidentified_lines(p, format_, strict_)) line(l);
}

void Config::conversion(const std::string& key, const std::string& formula, double value,
                        const std::string& unit) {
  conversions_.push_back(key + " = " + formula + " = " + real(value) + " " + unit);
}

std::vector<std::string> Config::header_lines() const {
  std::vector<std::string> out;
  std::istringstream in(header_.str());
  for (std::string l; std::getline(in, l);) out.push_back(l.substr(comment_.size() + 1));
  if (!conversions_.empty()) {
    out.emplace_back("conversions (model SI values -> this file):");
    for (const auto& c : conversions_) out.push_back("  " + c);
  }
  return out;
}

std::string Config::text(const std::string& first_line) {
  std::ostringstream out;
  if (!first_line.empty()) out << first_line << '\n';
  out << header_.str();
  if (!conversions_.empty()) {
    out << comment_ << " conversions (model SI values -> this file):\n";
    for (const auto& c : conversions_) out << comment_ << "   " << c << '\n';
  }
  out << body_.str();
  return out.str();
}

const SensorParameters& need(const std::optional<SensorParameters>& s, SensorKind kind,
                             ExportFormat format) {
  if (!s)
    throw InputError(std::string("the model has no ") + std::string(sensor_name(kind)) + " axes; " +
                     std::string(export_format_name(format)) + " needs both sensors");
  return *s;
}

std::string triple(const SensorParameters& s, double SensorAxisParameters::*m, double scale,
                   const char* separator) {
  return real(s.axes[0].*m / scale) + separator + real(s.axes[1].*m / scale) + separator +
         real(s.axes[2].*m / scale);
}

RwOnly rw_only(const FilterParameters& p, Config& c, ExportFormat format, bool conservative) {
  const auto& g = need(p.gyro, SensorKind::gyro, format).one();
  const auto& a = need(p.accel, SensorKind::accel, format).one();
  c.line(conservative
             ? "this format has white noise and a random-walk bias only: B, GM, Q and R are "
               "folded into N and K (rule above)"
             : "this format has white noise and a random-walk bias only: B, GM terms, Q and R "
               "are not carried (best estimates; --conservative folds them into N and K)");
  if (!conservative && (g.bias_instability > 0.0 || a.bias_instability > 0.0))
    c.line("  dropped: gyro B = " + real(g.bias_instability) +
           " rad/s, accel B = " + real(a.bias_instability) +
           " m/s^2 (do not put B into the random-walk keys: theory.md §1.4)");
  return {g.rw_only_white_noise, g.rw_only_random_walk, a.rw_only_white_noise,
          a.rw_only_random_walk};
}

RwOnly per_sample(Config& c, const RwOnly& v, double rate,
                  std::initializer_list<std::pair<const char*, Slot>> keys) {
  const double s = std::sqrt(rate);
  const RwOnly d{v.n_g * s, v.k_g * s, v.n_a * s, v.k_a * s};
  for (const auto& [key, slot] : keys) {
    switch (slot) {
      case Slot::n_g:
        c.conversion(key, "N_g*sqrt(rate)", d.n_g, "rad/s");
        break;
      case Slot::n_a:
        c.conversion(key, "N_a*sqrt(rate)", d.n_a, "m/s^2");
        break;
      case Slot::k_g:
        c.conversion(key, "K_g*sqrt(rate)", d.k_g, "rad/s^2");
        break;
      case Slot::k_a:
        c.conversion(key, "K_a*sqrt(rate)", d.k_a, "m/s^3");
        break;
    }
  }
  return d;
}
}  // namespace imunoise::io::detail
