/// @file
/// @brief Registration of the imunoise subcommands; one cmd_<name>.cpp per subcommand.
/// A subcommand's callback throws imunoise::InputError / AnalysisError on bad input; main()
/// prints the message on one line and exits non-zero.
#pragma once

namespace CLI {
class App;
}

namespace imunoise::tools {

void register_allan_command(CLI::App& app);        ///< imunoise allan
void register_analyze_command(CLI::App& app);      ///< imunoise analyze (the whole job)
void register_check_command(CLI::App& app);        ///< imunoise check (sampling report)
void register_convert_command(CLI::App& app);      ///< imunoise convert (CSV/LCM/binary)
void register_export_command(CLI::App& app);       ///< imunoise export (filter configs)
void register_live_command(CLI::App& app);         ///< imunoise live (LCM node)
void register_publish_command(CLI::App& app);      ///< imunoise publish (LCM)
void register_discretize_command(CLI::App& app);   ///< imunoise discretize (Phi, Qd)
void register_drift_command(CLI::App& app);        ///< imunoise drift (INS drift vs model)
void register_simulate_command(CLI::App& app);     ///< imunoise simulate
void register_report_command(CLI::App& app);       ///< imunoise report (report.html)
void register_fftw_wisdom_command(CLI::App& app);  ///< imunoise fftw-wisdom (PSD plans)
void register_fleet_command(CLI::App& app);        ///< imunoise fleet (many units, spec)
void register_plan_command(CLI::App& app);         ///< imunoise plan (how long to record)

}  // namespace imunoise::tools
