/// Output safety (issue 9): a full disk and a read-only directory give a clear one-line error,
/// exit 2 and no partial or temporary file. Each case runs `imunoise analyze` inside a private
/// mount namespace (`unshare -m`) on a tmpfs of 64 KiB or a read-only one, so nothing outside
/// the test directory is touched; the test skips where unshare/mount are not permitted (CI
/// runs as root).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "test_support.h"

namespace imunoise::test {
namespace {

namespace fs = std::filesystem;

/// Runs SCRIPT with sh inside `unshare -m`; stdout and stderr of the whole script.
struct ShellRun {
  int exit_code = -1;
  std::string out;
};
ShellRun run_in_mount_namespace(const std::string& script, const fs::path& dir) {
  const fs::path script_path = dir / "script.sh";
  std::ofstream(script_path) << script;
  const fs::path out = dir / "script.out";
  std::string command = "unshare -m -- sh ";
  command.append(quoted_for_shell(script_path)).append(" >").append(quoted_for_shell(out));
  command.append(" 2>&1 </dev/null");
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128, read_file_bytes(out)};
}

TEST(OutputSafetyCli, FullDiskAndReadOnlyDirectoryGiveAClearErrorAndNoPartialFile) {
  const fs::path dir = make_temp_dir("output_safety");
  const fs::path mnt = dir / "mnt";
  fs::create_directories(mnt);
  // Scripts are built with a stream: GCC 12 warns falsely (-Wstringop-overflow, -Warray-bounds)
  // on long chains of std::string operator+.
  std::ostringstream probe_script;
  probe_script << "mount -t tmpfs -o size=64k tmpfs " << quoted_for_shell(mnt) << " && touch "
               << quoted_for_shell(mnt / "x");
  const ShellRun probe = run_in_mount_namespace(probe_script.str(), dir);
  if (probe.exit_code != 0) {
    GTEST_SKIP() << "needs 'unshare -m' and tmpfs mounts (root or CAP_SYS_ADMIN): " << probe.out;
  }
  const fs::path rec = dir / "rec.csv";
  std::ostringstream simulate;
  simulate << "simulate "
           << quoted_for_shell(fs::path(IMUNOISE_SOURCE_DIR) / "configs" / "reference-imu.yaml")
           << " --duration 10min --rate 50 --seed 4 -o " << quoted_for_shell(rec);
  const CommandResult sim = run_imunoise(simulate.str());
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  std::ostringstream analyze;
  analyze << quoted_for_shell(fs::path(imunoise_binary())) << " analyze " << quoted_for_shell(rec)
          << " --bootstrap 0 -q -o " << quoted_for_shell(mnt / "out");

  // 1. Disk full: 64 KiB hold the first outputs but not the report. The script reports the
  //    exit code, every file left behind, and the number of temporary files.
  std::ostringstream full_script;
  full_script << "mount -t tmpfs -o size=64k tmpfs " << quoted_for_shell(mnt) << " || exit 99\n"
              << analyze.str() << " 2>" << quoted_for_shell(dir / "full.err") << " >/dev/null\n"
              << "echo \"exit=$?\"\n"
              << "cd " << quoted_for_shell(mnt) << " && find . -type f | sort\n"
              << "echo \"temporaries=$(find . -name '*.tmp.*' | wc -l)\"\n";
  const ShellRun full = run_in_mount_namespace(full_script.str(), dir);
  ASSERT_EQ(full.exit_code, 0) << full.out;
  const std::string full_err = read_file_bytes(dir / "full.err");
  EXPECT_NE(full.out.find("exit=2\n"), std::string::npos) << full.out << full_err;
  EXPECT_NE(full_err.find("disk full"), std::string::npos) << full_err;
  EXPECT_NE(full_err.find(mnt.string()), std::string::npos) << "names the file: " << full_err;
  EXPECT_EQ(full_err.find('\n'), full_err.size() - 1) << "one line: " << full_err;
  EXPECT_NE(full.out.find("temporaries=0\n"), std::string::npos) << full.out;
  EXPECT_EQ(full.out.find("report.html"), std::string::npos) << "no report: " << full.out;

  // 2. Read-only file system: nothing can be created, the error says why.
  std::ostringstream ro_script;
  ro_script << "mount -t tmpfs -o ro,size=64k tmpfs " << quoted_for_shell(mnt) << " || exit 99\n"
            << analyze.str() << " 2>" << quoted_for_shell(dir / "ro.err") << " >/dev/null\n"
            << "echo \"exit=$?\"\n"
            << "echo \"files=$(find " << quoted_for_shell(mnt) << " -type f | wc -l)\"\n";
  const ShellRun read_only = run_in_mount_namespace(ro_script.str(), dir);
  ASSERT_EQ(read_only.exit_code, 0) << read_only.out;
  const std::string ro_err = read_file_bytes(dir / "ro.err");
  EXPECT_NE(read_only.out.find("exit=2\n"), std::string::npos) << read_only.out << ro_err;
  EXPECT_NE(read_only.out.find("files=0\n"), std::string::npos) << read_only.out;
  EXPECT_NE(ro_err.find("Read-only file system"), std::string::npos) << ro_err;
  EXPECT_NE(ro_err.find(mnt.string()), std::string::npos) << ro_err;
}

}  // namespace
}  // namespace imunoise::test
