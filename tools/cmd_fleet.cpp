/// @file
/// @brief `imunoise fleet MODEL.yaml… -o DIR [--spec FILE]`: many units of one IMU model side
/// by side — per axis and term the distribution over the units with robust outliers, and each
/// unit against a datasheet spec with its interval (pipeline/fleet.h); writes DIR/fleet.csv
/// (io/fleet_csv.h) and DIR/fleet.html (report/fleet_page.h), prints the summary.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/errors.h"
#include "io/atomic_output.h"
#include "io/fleet_csv.h"
#include "io/fleet_spec.h"
#include "io/noise_model_yaml.h"
#include "pipeline/fleet.h"
#include "report/fleet_page.h"
#include "report/write_report.h"
#include "tools/commands.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

namespace {

/// A unit's name: the directory of DIR/model.yaml, else the file's stem.
std::string unit_name(const std::filesystem::path& model_path) {
  if (model_path.filename() == "model.yaml" && model_path.has_parent_path() &&
      !model_path.parent_path().filename().empty())
    return model_path.parent_path().filename().string();
  return model_path.stem().string();
}

}  // namespace

void register_fleet_command(CLI::App& app) {
  struct Args {
    std::vector<std::string> models;
    std::string output;
    std::string spec;
    Verbosity verbosity;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "fleet",
      "Compare many units of one IMU model: per axis and term the median, range and spread over "
      "the units with robust outliers (MAD of log10), and with --spec each unit's pass / fail / "
      "undecided against a datasheet maximum by its interval; writes DIR/fleet.csv and "
      "DIR/fleet.html");
  cmd->add_option("MODEL", args->models,
                  "fitted model.yaml of each unit (imunoise analyze), or its results directory")
      ->required();
  cmd->add_option("-o,--output", args->output, "output directory (created if needed)")->required();
  cmd->add_option("--spec", args->spec,
                  "datasheet spec YAML: per sensor and term a maximum in datasheet units "
                  "(docs/batch.md; keys e.g. gyro: arw_deg_per_sqrt_h)");
  add_verbosity_options(*cmd, args->verbosity);
  cmd->footer(
      "Example:\n"
      "  imunoise fleet out/unit*/model.yaml --spec datasheet.yaml -o out/fleet\n"
      "pass: the interval's upper end <= the maximum; fail: its lower end > the maximum;\n"
      "undecided: the interval straddles it (record longer).");
  cmd->callback([args] {
    std::vector<pipeline::FleetUnit> units;
    for (const std::string& given : args->models) {
      std::filesystem::path path(given);
      if (std::filesystem::is_directory(path)) path /= "model.yaml";
      std::string name = unit_name(path);
      for (const pipeline::FleetUnit& u : units)
        if (u.name == name) name = path.string();  // two units of one name: the path tells them
      units.push_back({name, io::load_model_yaml(path.string())});
    }
    std::optional<pipeline::FleetSpec> spec;
    if (!args->spec.empty()) spec = io::read_fleet_spec(args->spec);
    const pipeline::FleetResult result = pipeline::analyze_fleet(units, spec);
    io::create_output_directory(args->output);
    const std::filesystem::path dir(args->output);
    io::write_fleet_csv((dir / "fleet.csv").string(), io::fleet_table(result));
    const std::string html = report::write_fleet_report(args->output, result);
    std::cout << report::fleet_summary_text(result);
    if (!args->verbosity.quiet)
      std::cout << "wrote " << (dir / "fleet.csv").string() << ", " << html << "\n";
  });
}

}  // namespace imunoise::tools
