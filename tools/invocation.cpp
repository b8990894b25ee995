/// @file
/// @brief The recorded command line (see invocation.h).
#include "tools/invocation.h"

#include <filesystem>
#include <mutex>
#include <vector>

#include "io/commands_file.h"

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

}  // namespace

void set_invocation(int argc, const char* const* argv) {
  std::lock_guard lock(invocation_mutex());
  auto& args = invocation_arguments();
  args.assign(argv, argv + argc);
}

void write_command_file(const std::string& dir) {
  io::CommandRecord record;
  {
    std::lock_guard lock(invocation_mutex());
    const auto& args = invocation_arguments();
    if (args.empty()) return;
    record.arguments.assign(args.begin() + 1, args.end());
  }
  std::error_code ec;
  const std::filesystem::path cwd = std::filesystem::current_path(ec);
  if (!ec) record.working_directory = cwd.string();
  io::write_command_file(dir, record);
}

}  // namespace imunoise::tools
