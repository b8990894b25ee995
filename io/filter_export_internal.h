/// @file
/// @brief Private to io/filter_export*.cpp: the file header under construction (Config), the
/// number form every consumer parses, the white + random-walk pair shared by the Kalibr-like
/// formats, the lines and refusals for terms not identified, and the writers of the robotics
/// family (io/filter_export_robotics.cpp).
#pragma once

#include <initializer_list>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/noise_term.h"
#include "common/sensor_kind.h"
#include "io/filter_export.h"
#include "models/filter_parameters.h"
#include "models/noise_model.h"

namespace imunoise::io::detail {

constexpr double kMilliGal = 1e-5;  ///< m/s² per mGal (KF-GINS abstd)

/// The consumer named in the first header line ("Kalibr (imu.yaml)", …).
std::string_view export_consumer_name(ExportFormat format);

/// Six significant digits, always with a decimal point and a lowercase exponent: OpenCV's
/// FileStorage (OpenVINS, VINS, ORB-SLAM3, OKVIS, Kimera) reads "200" as an integer and "1E-3"
/// as 1, and PyYAML (Kalibr, ROS 1 parameters) reads "1e-05" as a string; "1.0e-05" and "200.0"
/// are reals to all, and to JSON parsers.
std::string real(double x);
/// "[I]" or "(I)" — built piecewise (GCC 12 warns falsely on "[" + std::to_string(i)).
std::string bracketed(int i, char open, char close);

/// The terms of a model axis that FORMAT writes (others it drops or folds): N and K for the
/// white + random-walk filters, N and B for the Gauss–Markov ones, N, B, K for MATLAB.
std::vector<NoiseTerm> carried_terms(ExportFormat format);

/// One line per term FORMAT carries that is not identified (docs/exports.md "Terms not
/// identified"): its upper bound used in its place, or 0 written when the model has none.
/// @throws InputError naming format, axis and term when STRICT (no upper bound in place of a
///   term), or when the model has no upper bound and the consumer refuses 0 (Kalibr, Kimera,
///   Basalt, LIO-SAM, GTSAM).
std::vector<std::string> unidentified_lines(const models::FilterParameters& p, ExportFormat format,
                                            bool strict);

/// The header and body of one config under construction.
class Config {
 public:
  /// Opens the header: consumer, model, command, rate, density convention.
  Config(std::string comment, const models::NoiseModel& model, const ExportRequest& request,
         double rate_hz);

  void line(const std::string& text) { header_ << comment_ << ' ' << text << '\n'; }
  /// The rules of P, then the lines of unidentified_lines() (terms not identified).
  void rules(const models::FilterParameters& p);
  /// One conversion: KEY = FORMULA = VALUE UNIT.
  void conversion(const std::string& key, const std::string& formula, double value,
                  const std::string& unit);
  std::ostringstream& body() { return body_; }
  /// The header lines without comment marks, in order (for formats without comments: JSON).
  std::vector<std::string> header_lines() const;
  /// FIRST_LINE (if any), the header, the conversions, the body.
  std::string text(const std::string& first_line = "");

 private:
  std::string comment_;
  ExportFormat format_;
  bool strict_ = false;
  std::ostringstream header_, body_;
  std::vector<std::string> conversions_;
};

/// P's values of KIND, or InputError naming what FORMAT lacks.
const models::SensorParameters& need(const std::optional<models::SensorParameters>& s,
                                     SensorKind kind, ExportFormat format);
/// "a, b, c": member M of the three slots of S divided by SCALE.
std::string triple(const models::SensorParameters& s, double models::SensorAxisParameters::*m,
                   double scale, const char* separator = ", ");

/// Values and lines shared by the white + random-walk formats (Kalibr family).
struct RwOnly {
  double n_g, k_g, n_a, k_a;
};
/// The white + RW pair of both sensors (needs both), with the header line of what is dropped.
RwOnly rw_only(const models::FilterParameters& p, Config& c, ExportFormat format,
               bool conservative);

/// One member of RwOnly: gyro or accel, white noise or random walk.
enum class Slot { n_g, n_a, k_g, k_a };

/// The white + RW pair as the per-sample σ of a discrete filter at RATE (N·√rate, K·√rate),
/// with one header conversion line per key in the order given (VINS, PX4, ArduPilot).
RwOnly per_sample(Config& c, const RwOnly& v, double rate,
                  std::initializer_list<std::pair<const char*, Slot>> keys);

/// Everything a format writer reads.
struct ExportContext {
  const models::NoiseModel& model;
  const ExportRequest& request;
  const models::FilterParameters& p;
  double rate;
  std::vector<std::string>& warnings;  ///< for the caller to show (ArduPilot's range clamps)
};

/// @name The robotics family (io/filter_export_robotics.cpp; keys in docs/exports.md)
/// @{
std::string lio_sam(const ExportContext& x);
std::string fast_lio(const ExportContext& x);
std::string basalt(const ExportContext& x);
std::string gtsam(const ExportContext& x);
std::string ardupilot(const ExportContext& x);
std::string kimera(const ExportContext& x);
std::string imu_utils(const ExportContext& x);
/// @}

}  // namespace imunoise::io::detail
