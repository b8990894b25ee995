/// @file
/// @brief `imunoise export`: a fitted model.yaml → the noise section of a filter or simulator
/// config (io/filter_export.h, docs/exports.md), to stdout, a file, or — with `--to all` —
/// every format into a directory.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "common/errors.h"
#include "common/number_text.h"
#include "io/atomic_output.h"
#include "io/filter_export.h"
#include "io/noise_model_yaml.h"
#include "tools/commands.h"
#include "tools/gm_convention_option.h"
#include "tools/invocation.h"
#include "tools/verbosity.h"

namespace imunoise::tools {
namespace {

struct ExportArgs {
  std::string model_path;
  std::string to;
  double rate_hz = 0.0;
  std::string axis = "worst";
  bool conservative = false;
  bool strict = false;
  std::string gm_convention = "peak_match";
  double correction_interval_s = 0.0;
  std::string output;
  Verbosity verbosity;
};

std::string format_names() {
  std::string names;
  for (auto f : io::all_export_formats())
    names += (names.empty() ? "" : ", ") + std::string(io::export_format_name(f));
  return names;
}

/// The command as the user would type it again, for the file header.
std::string command_text(const ExportArgs& a, const std::string& to) {
  std::string s = "imunoise export " + a.model_path + " --to " + to;
  if (a.rate_hz > 0.0) s += " --rate " + shortest_number_text(a.rate_hz);
  if (a.axis != "worst") s += " --axis " + a.axis;
  if (a.conservative) s += " --conservative";
  if (a.strict) s += " --strict";
  if (a.gm_convention != "peak_match") s += " --gm-convention " + a.gm_convention;
  if (a.correction_interval_s > 0.0)
    s += " --correction-interval " + shortest_number_text(a.correction_interval_s);
  return s;
}

void run_export(const ExportArgs& a, bool axis_given) {
  const auto model = io::load_model_yaml(a.model_path);
  io::ExportRequest request;
  request.rate_hz = a.rate_hz;
  request.parameters.axis = models::axis_choices_by_name().at(a.axis);
  request.parameters.conservative = a.conservative;
  request.parameters.gm_convention = gm_conventions().at(a.gm_convention);
  request.parameters.correction_interval_s = a.correction_interval_s;
  request.parameters.setting_names = {"--axis", "--correction-interval"};
  request.model_path = a.model_path;
  request.strict = a.strict;
  // One warning per upper bound used in place of a term not identified (also in the header).
  const auto warn = [](const io::ExportOutput& out) {
    for (const auto& w : out.warnings) std::cerr << "imunoise: warning: " << w << '\n';
  };

  if (a.to == "all") {
    if (a.output.empty()) throw InputError("--to all writes one file per format and needs -o DIR");
    std::error_code ec;
    std::filesystem::create_directories(a.output, ec);
    if (ec) throw InputError(a.output + ": cannot create the directory: " + ec.message());
    for (auto format : io::all_export_formats()) {
      if (format == io::ExportFormat::native && (a.conservative || axis_given)) continue;
      request.format = format;
      request.command = command_text(a, std::string(io::export_format_name(format)));
      const auto path =
          (std::filesystem::path(a.output) / io::default_export_file_name(format)).string();
      const auto out = io::export_file(model, request);
      warn(out);
      io::write_file_atomically(path, out.text);
      std::cout << path << '\n';
    }
    write_command_file(a.output);
    return;
  }
  const auto format = io::parse_export_format(a.to);
  if (!format)
    throw InputError("--to: unknown format '" + a.to + "'; choose one of " + format_names() +
                     ", or all");
  if (*format == io::ExportFormat::native && axis_given)
    throw InputError("--axis does not apply to --to native (a lossless copy of the model)");
  request.format = *format;
  request.command = command_text(a, a.to);
  const auto out = io::export_file(model, request);
  warn(out);
  if (a.output.empty()) {
    std::cout << out.text;
  } else {
    io::write_file_atomically(a.output, out.text);
  }
}

}  // namespace

void register_export_command(CLI::App& app) {
  auto args = std::make_shared<ExportArgs>();
  CLI::App* sub = app.add_subcommand(
      "export",
      "Write the noise section of a filter or simulator config from a fitted model.yaml.\n"
      "Example: imunoise export out/model.yaml --to kalibr --rate 200 -o imu.yaml");
  sub->add_option("model", args->model_path, "fitted model.yaml (from imunoise analyze)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--to", args->to, "format: " + format_names() + ", or all (needs -o DIR)")
      ->required();
  sub->add_option("--rate", args->rate_hz,
                  "rate [Hz] of the discrete values (default: the model's sample rate; PX4: its "
                  "100 Hz filter rate; ArduPilot: EKF3's 83.33 Hz step)")
      ->check(CLI::PositiveNumber);
  CLI::Option* axis =
      sub->add_option("--axis", args->axis,
                      "how x, y, z become one value: worst (largest, default), mean (root mean "
                      "square), x, y, z, or each (per-axis slots)")
          ->check(CLI::IsMember(models::axis_choices_by_name()));
  sub->add_flag("--conservative", args->conservative,
                "overbounding set: upper interval ends, and B/GM/Q/R folded into N and K for "
                "white + random-walk filters (rule written into the file)");
  sub->add_flag("--strict", args->strict,
                "refuse a term the format carries that is not identified (default: its upper "
                "bound, named in the header and warned about on stderr)");
  sub->add_option("--gm-convention", args->gm_convention,
                  "bias instability as one Gauss-Markov term (theory.md §4.4): "
                  "min_adev_at_tau_min, peak_match (default), sigma_equals_b")
      ->check(CLI::IsMember(gm_conventions()));
  sub->add_option("--correction-interval", args->correction_interval_s,
                  "T [s] of the conservative B fold (default: the τ of the ADEV minimum)")
      ->check(CLI::PositiveNumber);
  sub->add_option("-o,--output", args->output,
                  "output file (default: stdout); a directory for --to all");
  add_verbosity_options(*sub, args->verbosity);
  sub->callback([args, axis] {
    io::StageTimes times;
    run_export(*args, axis->count() > 0);
    times.mark("load, select and write");
    print_timings(args->verbosity, "export", times);
  });
}

}  // namespace imunoise::tools
