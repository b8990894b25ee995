/// @file
/// @brief parallel_for: the one worker pool of the pure layers and the readers. Items are
/// independent; each is run exactly once, so results never depend on the thread count.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

namespace imunoise {

/// THREADS as given, or all cores for 0 (at least 1).
inline unsigned resolve_threads(unsigned threads) {
  return threads != 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
}

/// Runs WORK(i) for i in [0, COUNT) on up to THREADS threads (0 = all cores), the caller
/// included; the caller runs AFTER_OWN() after each of its own items (so e.g. progress is
/// reported from the calling thread only). Items are handed out in increasing order. After the
/// first exception no new item starts; it is rethrown once every thread has stopped. When the
/// system refuses a thread, the threads already running share the items.
template <typename Work, typename AfterOwn>
void parallel_for(std::size_t count, unsigned threads, Work&& work, AfterOwn&& after_own) {
  std::atomic<std::size_t> next{0};
  std::mutex error_mutex;
  std::exception_ptr error;
  const auto loop = [&](bool caller) {
    try {
      for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
        work(i);
        if (caller) after_own();
      }
    } catch (...) {
      const std::lock_guard lock(error_mutex);
      if (!error) error = std::current_exception();
      next.store(count);
    }
  };
  std::vector<std::thread> pool;
  const std::size_t helpers =
      std::min<std::size_t>(resolve_threads(threads), count) - (count > 0 ? 1 : 0);
  for (std::size_t t = 0; t < helpers; ++t) {
    try {
      pool.emplace_back(loop, false);
    } catch (const std::system_error&) {
      break;
    }
  }
  loop(true);
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

/// parallel_for without a per-item callback.
template <typename Work>
void parallel_for(std::size_t count, unsigned threads, Work&& work) {
  parallel_for(count, threads, std::forward<Work>(work), [] {});
}

}  // namespace imunoise
