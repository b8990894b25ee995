#include "io/stage_progress.h"

#include "common/number_text.h"

namespace imunoise::io {

StageTimes::StageTimes() : start_(std::chrono::steady_clock::now()), last_mark_(start_) {}

void StageTimes::add(std::string_view stage, double seconds) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& [name, total] : stages_) {
    if (name == stage) {
      total += seconds;
      return;
    }
  }
  stages_.emplace_back(std::string(stage), seconds);
}

void StageTimes::mark(std::string_view stage) {
  const auto now = std::chrono::steady_clock::now();
  double seconds = 0.0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    seconds = std::chrono::duration<double>(now - last_mark_).count();
    last_mark_ = now;
  }
  add(stage, seconds);
}

double StageTimes::elapsed_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string StageTimes::text() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::string out;
  for (const auto& [name, seconds] : stages_) {
    if (!out.empty()) out.append(", ");
    out.append(name).append(" ").append(significant_number_text(seconds, 3)).append(" s");
  }
  return out;
}

}  // namespace imunoise::io
