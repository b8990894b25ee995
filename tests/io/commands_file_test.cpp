// Tests of io/commands_file.h: a record written and read back is the same record, arguments
// a shell would split or expand included; the lines are what a POSIX shell runs.
#include "io/commands_file.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "test_support.h"

namespace imunoise::io {
namespace {

TEST(CommandsFile, RoundTripKeepsEveryArgumentExactly) {
  const auto dir = test::make_temp_dir("commands_file");
  const CommandRecord written{"/tmp/a dir/it's",
                              {"analyze", "rec ording.csv", "-o", "out", "", "it's", "a'b'c",
                               "$HOME", "--taus", "log:10", "ü", "\\n"}};
  write_command_file(dir.string(), written);
  const auto read = read_command_file(dir.string());
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->working_directory, written.working_directory);
  EXPECT_EQ(read->arguments, written.arguments);
  EXPECT_EQ(test::read_file_bytes(dir / "commands.txt"),
            "cd '/tmp/a dir/it'\\''s'\nimunoise analyze 'rec ording.csv' -o out '' 'it'\\''s' "
            "'a'\\''b'\\''c' '$HOME' --taus log:10 'ü' '\\n'\n");
}

TEST(CommandsFile, TheShellRunsTheLinesAsWritten) {
  // An independent reader: /bin/sh itself, printing each argument of the command line.
  const auto dir = test::make_temp_dir("commands_file_sh");
  const CommandRecord written{"", {"a b", "", "it's", "x\"y", "$HOME", "*"}};
  const std::vector<std::string> lines = command_file_lines(written);
  ASSERT_EQ(lines.size(), 1u);  // no directory: no cd line
  const std::string script =
      "imunoise() { for a in \"$@\"; do printf '[%s]' \"$a\"; done; }\n" + lines[0] + "\n";
  std::ofstream(dir / "run.sh") << script;
  FILE* p = popen(("sh " + test::quoted_for_shell(dir / "run.sh")).c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  for (int c; (c = std::fgetc(p)) != EOF;) out.push_back(static_cast<char>(c));
  pclose(p);
  EXPECT_EQ(out, "[a b][][it's][x\"y][$HOME][*]");
}

TEST(CommandsFile, AbsentIsEmptyAndAForeignFileIsALocatedError) {
  const auto dir = test::make_temp_dir("commands_file_bad");
  EXPECT_FALSE(read_command_file(dir.string()).has_value());
  std::ofstream(dir / "commands.txt") << "make all\n";
  test::expect_throw_containing<InputError>([&] { read_command_file(dir.string()); },
                                            "commands.txt:1: expected 'cd DIR'");
  std::ofstream(dir / "commands.txt") << "imunoise analyze 'open\n";
  test::expect_throw_containing<InputError>([&] { read_command_file(dir.string()); },
                                            "commands.txt:1: unterminated quote");
}

}  // namespace
}  // namespace imunoise::io
