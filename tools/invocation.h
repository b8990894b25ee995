/// @file
/// @brief The command line this process was started with, for the "commands to reproduce" of
/// reports: recorded once by main(), written as DIR/commands.txt (io/commands_file.h) by the
/// commands that write an output directory.
#pragma once

#include <string>

namespace imunoise::tools {

/// Records ARGV (called once by main before parsing).
void set_invocation(int argc, const char* const* argv);

/// Writes DIR/commands.txt (atomically): the current directory and the recorded arguments, so
/// that its two lines pasted into a shell redo this run. Nothing before set_invocation.
void write_command_file(const std::string& dir);

}  // namespace imunoise::tools
