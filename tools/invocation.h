/// @file
/// @brief The command line this process was started with, for the "commands to reproduce" of
/// reports: recorded once by main(), written as DIR/commands.txt by the commands that write an
/// output directory.
#pragma once

#include <string>
#include <vector>

namespace imunoise::tools {

/// Records ARGV (called once by main before parsing).
void set_invocation(int argc, const char* const* argv);

/// The command as a shell line: "imunoise" then each argument, single-quoted where the shell
/// would split or expand it ("" before set_invocation).
std::string invocation_command_line();

/// Writes DIR/commands.txt (atomically): `cd '<current directory>'` and the command line, so
/// that the two lines pasted into a shell redo this run.
void write_command_file(const std::string& dir);

/// The lines of DIR/commands.txt, or none when there is no such file.
std::vector<std::string> read_command_file(const std::string& dir);

}  // namespace imunoise::tools
