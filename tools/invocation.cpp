/// @file
/// @brief The recorded command line (see invocation.h).
#include "tools/invocation.h"

#include <filesystem>
#include <fstream>
#include <mutex>

#include "io/atomic_output.h"

namespace imunoise::tools {

namespace {

std::mutex& invocation_mutex() {
  static std::mutex m;
  return m;
}

std::vector<std::string>& invocation_arguments() {
  static std::vector<std::string> args;
  return args;
}

/// ARG as one shell word: bare when made only of safe characters, else single-quoted with
/// embedded quotes as '\''.
std::string shell_word(const std::string& arg) {
  const bool safe = !arg.empty() && arg.find_first_not_of(
                                        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                        "0123456789_-+=.,/:@%^") == std::string::npos;
  if (safe) return arg;
  std::string out = "'";
  for (char c : arg) {
    if (c == '\'') {
      out.append("'\\''");
    } else {
      out.push_back(c);
    }
  }
  out.push_back('\'');
  return out;
}

}  // namespace

void set_invocation(int argc, const char* const* argv) {
  std::lock_guard lock(invocation_mutex());
  auto& args = invocation_arguments();
  args.assign(argv, argv + argc);
}

std::string invocation_command_line() {
  std::lock_guard lock(invocation_mutex());
  const auto& args = invocation_arguments();
  if (args.empty()) return "";
  std::string line = "imunoise";  // argv[0] may be a build path; the installed name reads better
  for (std::size_t i = 1; i < args.size(); ++i) line.append(" ").append(shell_word(args[i]));
  return line;
}

void write_command_file(const std::string& dir) {
  const std::string command = invocation_command_line();
  if (command.empty()) return;
  std::error_code ec;
  const std::filesystem::path cwd = std::filesystem::current_path(ec);
  std::string text;
  if (!ec) text.append("cd ").append(shell_word(cwd.string())).append("\n");
  text.append(command).append("\n");
  io::write_file_atomically((std::filesystem::path(dir) / "commands.txt").string(), text);
}

std::vector<std::string> read_command_file(const std::string& dir) {
  std::ifstream in(std::filesystem::path(dir) / "commands.txt");
  std::vector<std::string> lines;
  std::string line;
  while (in && std::getline(in, line)) {
    if (!line.empty()) lines.push_back(line);
  }
  return lines;
}

}  // namespace imunoise::tools
