/// @file
/// @brief commands.txt, the "commands to reproduce" of an output directory: the working
/// directory and the argument vector of the run that wrote it, as two lines a POSIX shell runs
/// (`cd '<dir>'`, `imunoise <args>`). Writer and reader over one typed record.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace imunoise::io {

/// What commands.txt records.
struct CommandRecord {
  std::string working_directory;       ///< "" when it was not known (no `cd` line)
  std::vector<std::string> arguments;  ///< the arguments after the program name
};

/// ARG as one shell word: bare when made only of safe characters, else single-quoted with
/// embedded quotes as '\''.
std::string shell_word(const std::string& arg);

/// The file's lines: `cd <dir>` (when the directory is known), then "imunoise" and each
/// argument as a shell word.
std::vector<std::string> command_file_lines(const CommandRecord& record);

/// Writes DIR/commands.txt (atomically): command_file_lines, one per line.
void write_command_file(const std::string& dir, const CommandRecord& record);

/// DIR/commands.txt as imunoise writes it, or empty when there is no such file. Throws
/// InputError "DIR/commands.txt:LINE: problem" for a file it did not write (no `imunoise`
/// command line, an unterminated quote).
std::optional<CommandRecord> read_command_file(const std::string& dir);

}  // namespace imunoise::io
