#include "io/terminal_progress_bar.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>

namespace imunoise::io {

namespace {

constexpr std::int64_t kRedrawIntervalNs = 100'000'000;  // at most ~10 draws per second
constexpr std::size_t kMaxBarWidth = 40;                 // a wider bar shows nothing more
constexpr std::size_t kMinBarWidth = 10;

/// "0:04", "12:30", "1:02:03".
std::string elapsed_text(double seconds) {
  const auto s = static_cast<long long>(std::max(0.0, std::floor(seconds)));
  char text[32];
  if (s >= 3600) {
    std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%lld:%02lld", s / 60, s % 60);
  }
  return text;
}

/// Writes all of `text` to stderr's descriptor in one go where possible (no stdio buffer, so
/// the bar never interleaves with a half-flushed message).
void write_stderr(const std::string& text) {
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(STDERR_FILENO, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // a progress bar is not worth an error
    written += static_cast<std::size_t>(n);
  }
}

std::int64_t nanoseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() -
                                                              start)
      .count();
}

}  // namespace

std::string render_progress_line(const ProgressLine& p, int columns) {
  const std::size_t width = columns > 1 ? static_cast<std::size_t>(columns - 1) : 0;
  const double fraction =
      p.total > 0 ? std::clamp(static_cast<double>(p.done) / static_cast<double>(p.total), 0.0, 1.0)
                  : 0.0;

  std::string head(p.label);
  if (!p.stage.empty()) {
    head.append(": ").append(p.stage);
    if (p.stage.size() < p.stage_width) head.append(p.stage_width - p.stage.size(), ' ');
  }
  char percent[8];
  // Floor, so "100%" appears only when everything is done.
  std::snprintf(percent, sizeof percent, "%3d%%", static_cast<int>(std::floor(100.0 * fraction)));
  std::string items;
  if (p.items_total > 0) {
    items.append("  ")
        .append(std::to_string(std::clamp(p.items_done, std::int64_t{0}, p.items_total)))
        .append("/")
        .append(std::to_string(p.items_total));
    if (!p.items_unit.empty()) items.append(" ").append(p.items_unit);
  }
  const std::string time = std::string("  ").append(elapsed_text(p.elapsed_s));

  const auto fixed = [&](const std::string& item_text) {
    return head.size() + 2 + 2 + std::char_traits<char>::length(percent) + item_text.size() +
           time.size();  // " [" "] "
  };
  if (fixed(items) + kMinBarWidth > width) items.clear();
  if (fixed(items) + kMinBarWidth <= width) {
    const std::size_t bar = std::min(kMaxBarWidth, width - fixed(items));
    const auto filled = static_cast<std::size_t>(std::floor(fraction * static_cast<double>(bar)));
    std::string line = head;
    line.append(" [")
        .append(filled, '#')
        .append(bar - filled, ' ')
        .append("] ")
        .append(percent)
        .append(items)
        .append(time);
    return line;
  }
  // Too narrow for a bar: the numbers alone, cut to the width.
  std::string line = head;
  line.append(" ").append(percent).append(time);
  if (line.size() > width) line.resize(width);
  return line;
}

int stderr_columns() {
  winsize size{};
  if (::ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return 80;
}

ProgressBar::ProgressBar(std::string label, bool enabled)
    : label_(std::move(label)),
      enabled_(enabled),
      start_(std::chrono::steady_clock::now()),
      last_draw_ns_(0) {}  // the first draw comes after 0.1 s: quick commands draw nothing

ProgressBar::~ProgressBar() {
  if (!enabled_ || finished_.exchange(true, std::memory_order_acq_rel)) return;
  std::lock_guard<std::mutex> lock(draw_mutex_);
  if (drawn_chars_ == 0) return;
  std::string out = "\r";
  out.append(drawn_chars_, ' ').append("\r");
  write_stderr(out);
}

void ProgressBar::update(std::string_view stage, std::int64_t done, std::int64_t total) {
  if (!enabled_ || finished_.load(std::memory_order_acquire)) return;
  {
    std::lock_guard<std::mutex> lock(text_mutex_);
    if (stage_ != stage) stage_.assign(stage);
  }
  if (total_.exchange(total) != total) {
    done_.store(done);
  } else {
    std::int64_t seen = done_.load();
    while (done > seen && !done_.compare_exchange_weak(seen, done)) {
    }
  }
  const std::int64_t now = nanoseconds_since(start_);
  std::int64_t last = last_draw_ns_.load();
  if (now - last < kRedrawIntervalNs) return;
  std::unique_lock<std::mutex> lock(draw_mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;  // another thread is drawing: skip, never wait
  if (finished_.load(std::memory_order_acquire)) return;
  if (!last_draw_ns_.compare_exchange_strong(last, now)) return;
  draw(false);
}

void ProgressBar::set_items(std::int64_t items_done, std::int64_t items_total,
                            std::string_view unit) {
  if (!enabled_) return;
  {
    std::lock_guard<std::mutex> lock(text_mutex_);
    if (items_unit_ != unit) items_unit_.assign(unit);
  }
  items_total_.store(items_total);
  items_done_.store(items_done);
}

ProgressCallback ProgressBar::callback() {
  if (!enabled_) return {};
  return [this](std::string_view stage, std::int64_t done, std::int64_t total) {
    update(stage, done, total);
  };
}

void ProgressBar::finish(std::string_view stage) {
  if (!enabled_ || finished_.exchange(true, std::memory_order_acq_rel)) return;
  std::lock_guard<std::mutex> lock(draw_mutex_);  // wait for a draw in progress
  if (drawn_chars_ == 0) return;                  // never drawn: leave the terminal alone
  {
    std::lock_guard<std::mutex> text_lock(text_mutex_);
    stage_.assign(stage);
  }
  const std::int64_t total = std::max<std::int64_t>(total_.load(), 1);
  total_.store(total);
  done_.store(total);
  if (items_total_.load() > 0) items_done_.store(items_total_.load());
  draw(true);
}

void ProgressBar::draw(bool final_line) {
  ProgressLine p;
  std::string stage, unit;
  {
    std::lock_guard<std::mutex> lock(text_mutex_);
    stage = stage_;
    unit = items_unit_;
  }
  stage_width_ = std::max(stage_width_, stage.size());
  p.label = label_;
  p.stage = stage;
  p.stage_width = stage_width_;
  p.total = total_.load();
  p.done = done_.load();
  p.items_total = items_total_.load();
  p.items_done = items_done_.load();
  p.items_unit = unit;
  p.elapsed_s = 1e-9 * static_cast<double>(nanoseconds_since(start_));
  const int columns = stderr_columns();
  const std::string line = render_progress_line(p, columns);

  std::string out = "\r";
  out.append(line);
  // Blank what is left of a longer previous line (no escape sequences needed), within the
  // current width.
  const std::size_t limit = columns > 1 ? static_cast<std::size_t>(columns - 1) : 0;
  const std::size_t blank_to = std::min(drawn_chars_, limit);
  if (line.size() < blank_to) out.append(blank_to - line.size(), ' ');
  drawn_chars_ = std::max<std::size_t>(line.size(), 1);
  if (final_line) out.append("\n");
  write_stderr(out);
}

}  // namespace imunoise::io
