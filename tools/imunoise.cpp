/// @file
/// @brief The imunoise command-line tool: parse → dispatch to one subcommand. Library errors
/// arrive as typed exceptions and are reported here, once, on one line.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "common/errors.h"
#include "common/version.h"
#include "tools/commands.h"
#include "tools/invocation.h"

namespace {
/// Exit codes: 0 success (also --help, --version); these otherwise.
constexpr int kExitInputError = 2;     ///< bad file, flag, flag value or config
constexpr int kExitAnalysisError = 3;  ///< the data cannot give what was asked
constexpr int kExitInternalError = 4;  ///< a bug or resource exhaustion
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "imunoise — stationary-IMU recordings to Kalman-filter-ready stochastic error models.\n"
      "Run 'imunoise <command> --help' for the options of each command."};
  imunoise::tools::set_invocation(argc, argv);
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string(imunoise::kSoftwareVersion));
  imunoise::tools::register_analyze_command(app);
  imunoise::tools::register_allan_command(app);
  imunoise::tools::register_check_command(app);
  imunoise::tools::register_simulate_command(app);
  imunoise::tools::register_convert_command(app);
  imunoise::tools::register_export_command(app);
  imunoise::tools::register_discretize_command(app);
  imunoise::tools::register_drift_command(app);
  imunoise::tools::register_publish_command(app);
  imunoise::tools::register_live_command(app);
  imunoise::tools::register_report_command(app);
  imunoise::tools::register_fftw_wisdom_command(app);
  imunoise::tools::register_fleet_command(app);
  imunoise::tools::register_plan_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints the help, the version or the mistake. Help and version succeed; every
    // command-line mistake (unknown flag, bad value, missing argument) is bad input, exit 2 as
    // for every other bad input, not CLI11's own 105–109.
    return app.exit(e) == 0 ? 0 : kExitInputError;
  } catch (const imunoise::InputError& e) {
    std::fprintf(stderr, "imunoise: error: %s\n", e.what());
    return kExitInputError;
  } catch (const imunoise::AnalysisError& e) {
    std::fprintf(stderr, "imunoise: error: %s\n", e.what());
    return kExitAnalysisError;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "imunoise: error: out of memory\n");
    return kExitInternalError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "imunoise: internal error: %s\n", e.what());
    return kExitInternalError;
  }
  return 0;
}
