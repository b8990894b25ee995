/// @file
/// @brief `imunoise report DIR`: rewrites DIR/report.html (and DIR/plots/) from the results
/// saved there by `imunoise analyze` and `imunoise drift` — e.g. after adding exports or a
/// drift run to an analysis directory.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <string>

#include "report/write_report.h"
#include "tools/commands.h"
#include "tools/verbosity.h"

namespace imunoise::tools {

void register_report_command(CLI::App& app) {
  struct Args {
    std::string dir;
    Verbosity verbosity;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Write DIR/report.html — one self-contained page with the coefficient table (SI and "
      "datasheet units), the Allan, PSD, drift and sampling plots (SVG, with the CSV behind "
      "each in DIR/plots/), the findings, the files written and the commands that wrote them — "
      "from the results saved in DIR");
  cmd->add_option("DIR", args->dir,
                  "output directory of 'imunoise analyze' (with drift results in DIR/drift, if "
                  "any) or of 'imunoise drift'")
      ->required();
  add_verbosity_options(*cmd, args->verbosity);
  cmd->footer(
      "Example:\n"
      "  imunoise analyze rec.csv -o out\n"
      "  imunoise drift rec.csv --model out/model.yaml -o out/drift\n"
      "  imunoise report out        # out/report.html now has the drift section too");
  cmd->callback([args] {
    const report::ReportOutput out = report::write_report(args->dir);
    if (!args->verbosity.quiet) {
      std::cout << "wrote " << out.html_path << " (" << out.figures << " figures)\n";
    }
  });
}

}  // namespace imunoise::tools
