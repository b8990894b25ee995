#include "io/commands_file.h"

#include <filesystem>
#include <fstream>

#include "common/errors.h"
#include "io/atomic_output.h"

namespace imunoise::io {

namespace {

/// The words of LINE as a POSIX shell splits the forms shell_word writes (bare words, '…'
/// and the '\'' escape); empty when a quote is not closed.
std::optional<std::vector<std::string>> shell_words(const std::string& line) {
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == ' ') {
      if (in_word) words.push_back(word);
      word.clear();
      in_word = false;
    } else if (c == '\'') {
      const std::size_t close = line.find('\'', i + 1);
      if (close == std::string::npos) return std::nullopt;
      word.append(line, i + 1, close - i - 1);
      in_word = true;
      i = close;
    } else if (c == '\\' && i + 1 < line.size()) {
      word.push_back(line[++i]);
      in_word = true;
    } else {
      word.push_back(c);
      in_word = true;
    }
  }
  if (in_word) words.push_back(word);
  return words;
}

}  // namespace

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

std::vector<std::string> command_file_lines(const CommandRecord& record) {
  std::vector<std::string> lines;
  if (!record.working_directory.empty()) {
    lines.push_back("cd " + shell_word(record.working_directory));
  }
  // argv[0] may be a build path; the installed name reads better.
  std::string command = "imunoise";
  for (const std::string& arg : record.arguments) command.append(" ").append(shell_word(arg));
  lines.push_back(command);
  return lines;
}

void write_command_file(const std::string& dir, const CommandRecord& record) {
  std::string text;
  for (const std::string& line : command_file_lines(record)) text.append(line).append("\n");
  write_file_atomically((std::filesystem::path(dir) / "commands.txt").string(), text);
}

std::optional<CommandRecord> read_command_file(const std::string& dir) {
  const std::string path = (std::filesystem::path(dir) / "commands.txt").string();
  std::ifstream in(path);
  if (!in) return std::nullopt;
  CommandRecord record;
  bool command_seen = false;
  std::string line;
  for (std::int64_t number = 1; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    const auto words = shell_words(line);
    if (!words) throw InputError(located_message(path, number, 0, "unterminated quote"));
    if (!command_seen && words->size() == 2 && words->front() == "cd" &&
        record.working_directory.empty()) {
      record.working_directory = (*words)[1];
    } else if (!command_seen && !words->empty() && words->front() == "imunoise") {
      record.arguments.assign(words->begin() + 1, words->end());
      command_seen = true;
    } else {
      throw InputError(
          located_message(path, number, 0, "expected 'cd DIR' and an 'imunoise ...' command line"));
    }
  }
  if (!command_seen) throw InputError(located_message(path, 0, 0, "no 'imunoise ...' line"));
  return record;
}

}  // namespace imunoise::io
