/// @file
/// @brief The CLI progress bar (io/terminal_progress_bar.h) in the real
/// `imunoise analyze` with stderr on a pseudo-terminal — the bar is drawn with '\r' redraws,
/// ends on a complete 100 % line and '\n', never exceeds the terminal width — and with stderr
/// on a pipe or with --quiet, where nothing of it appears.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <string>
#include <vector>

#include "test_support.h"

namespace imunoise::test {
namespace {

/// What a command wrote on a pseudo-terminal (stderr only; stdout and stdin are /dev/null).
struct TerminalRun {
  int exit_code = -1;
  std::string output;
};

/// Runs imunoise with ARGS, stderr on the slave side of a fresh pty of COLUMNS columns (raw:
/// no "\n" → "\r\n" translation, so the bytes are what imunoise wrote), reading the master
/// side until the child is gone.
TerminalRun run_on_terminal(const std::vector<std::string>& args, int columns) {
  TerminalRun run;
  termios raw{};
  cfmakeraw(&raw);
  winsize size{};
  size.ws_row = 40;
  size.ws_col = static_cast<unsigned short>(columns);
  int master = -1;
  int slave = -1;
  if (openpty(&master, &slave, nullptr, &raw, &size) != 0) {
    ADD_FAILURE() << "openpty failed: errno " << errno;
    return run;
  }
  EXPECT_EQ(ioctl(slave, TIOCSWINSZ, &size), 0);

  const std::string binary = imunoise_binary();
  std::vector<std::string> argv_text{binary};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);

  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_RDWR);
    dup2(null, STDIN_FILENO);
    dup2(null, STDOUT_FILENO);
    dup2(slave, STDERR_FILENO);
    close(null);
    close(slave);
    close(master);
    execv(binary.c_str(), argv.data());
    _exit(127);
  }
  close(slave);
  if (pid < 0) {
    close(master);
    ADD_FAILURE() << "fork failed";
    return run;
  }
  // Read until EOF/EIO (the slave closed when the child exited), with a generous deadline so
  // a hang fails the test instead of blocking it.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(10);
  char buffer[4096];
  for (;;) {
    pollfd fd{master, POLLIN, 0};
    const int ready = poll(&fd, 1, 500);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) {
      if (std::chrono::steady_clock::now() > deadline) {
        kill(pid, SIGKILL);
        ADD_FAILURE() << "imunoise did not finish within the deadline";
        break;
      }
      continue;
    }
    const ssize_t n = read(master, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // EIO on Linux once the slave side is closed
    run.output.append(buffer, static_cast<std::size_t>(n));
  }
  close(master);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

/// A 20-minute 100 Hz recording: long enough for the analysis to redraw the bar several times.
std::filesystem::path simulated_recording(const std::filesystem::path& dir) {
  const auto rec = dir / "rec.csv";
  // Built with append: GCC 12 warns falsely (-Warray-bounds) on "literal" + std::string here.
  std::string args = "simulate '";
  args.append(IMUNOISE_SOURCE_DIR)
      .append("/configs/reference-imu.yaml' --duration 20min --rate 100 --seed 3 -o '")
      .append(rec.string())
      .append("'");
  const CommandResult r = run_imunoise(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return rec;
}

/// The pieces between carriage returns and newlines: what occupied one terminal line.
std::vector<std::string> screen_pieces(const std::string& text) {
  std::vector<std::string> pieces(1);
  for (char c : text) {
    if (c == '\r' || c == '\n') {
      pieces.emplace_back();
    } else {
      pieces.back() += c;
    }
  }
  return pieces;
}

TEST(ProgressTerminal, AnalyzeDrawsTheBarOnATerminalAndEndsOnACleanLine) {
  const auto dir = make_temp_dir("progress_terminal");
  const auto rec = simulated_recording(dir);
  const TerminalRun run = run_on_terminal(
      {"analyze", rec.string(), "-o", (dir / "out").string(), "--bootstrap", "8"}, 100);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string& out = run.output;

  EXPECT_GE(std::count(out.begin(), out.end(), '\r'), 2) << "the bar is redrawn in place";
  EXPECT_NE(out.find("analyze: "), std::string::npos) << out;
  EXPECT_NE(out.find("100%"), std::string::npos) << out;
  EXPECT_EQ(out.find('\x1b'), std::string::npos) << "no escape sequences";

  // After the last '\r': the complete 100 % line, then '\n' and nothing else.
  const auto last_cr = out.rfind('\r');
  ASSERT_NE(last_cr, std::string::npos);
  const std::string tail = out.substr(last_cr + 1);
  ASSERT_FALSE(tail.empty());
  EXPECT_EQ(tail.back(), '\n') << tail;
  EXPECT_EQ(tail.find('\n'), tail.size() - 1) << "one line only: " << tail;
  EXPECT_EQ(tail.rfind("analyze: done", 0), 0u) << tail;
  const auto open = tail.find('[');
  const auto close = tail.find(']');
  ASSERT_NE(open, std::string::npos);
  ASSERT_NE(close, std::string::npos);
  EXPECT_EQ(tail.substr(open + 1, close - open - 1), std::string(close - open - 1, '#'))
      << "full bar: " << tail;
  EXPECT_NE(tail.find("] 100%  6/6 channels  "), std::string::npos) << tail;

  for (const std::string& piece : screen_pieces(out)) {
    EXPECT_LE(piece.size(), 99u) << "wider than the 100-column terminal: " << piece;
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "model.yaml"));
}

TEST(ProgressTerminal, NoBarWhenStderrIsAPipeOrWithQuiet) {
  const auto dir = make_temp_dir("progress_quiet");
  const auto rec = simulated_recording(dir);
  const CommandResult piped = run_imunoise("analyze '" + rec.string() + "' -o '" +
                                           (dir / "a").string() + "' --bootstrap 0");
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_EQ(piped.err.find('\r'), std::string::npos) << piped.err;
  EXPECT_EQ(piped.err.find("[#"), std::string::npos) << piped.err;
  EXPECT_EQ(piped.err.find('%'), std::string::npos) << piped.err;

  const TerminalRun quiet = run_on_terminal(
      {"analyze", rec.string(), "-o", (dir / "b").string(), "--bootstrap", "0", "--quiet"}, 100);
  ASSERT_EQ(quiet.exit_code, 0) << quiet.output;
  EXPECT_EQ(quiet.output.find('\r'), std::string::npos) << quiet.output;
  EXPECT_EQ(quiet.output.find('#'), std::string::npos) << quiet.output;
  EXPECT_EQ(quiet.output.find('%'), std::string::npos) << quiet.output;
}

}  // namespace
}  // namespace imunoise::test
