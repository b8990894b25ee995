/// @file
/// @brief parallel_for and parallel_for_with_state: the one worker pool of the pure layers and
/// the readers. Items are
/// independent; each is run exactly once, so results never depend on the thread count.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <optional>
#include <system_error>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace imunoise {

/// THREADS as given, or all cores for 0 (at least 1).
inline unsigned resolve_threads(unsigned threads) {
  return threads != 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
}

/// Runs WORK(state, i) for i in [0, COUNT) on up to THREADS threads (0 = all cores), the caller
/// included, each thread with a STATE of its own made by MAKE_STATE() before its first item
/// (scratch buffers reused across the items of one thread; a thread that gets no item makes
/// none); the caller runs AFTER_OWN() after each of its own items (so e.g. progress is
/// reported from the calling thread only). Items are handed out in increasing order. After the
/// first exception (of any type, from WORK or MAKE_STATE, in any thread) no new item starts;
/// it is rethrown once every thread has stopped. When the system refuses a thread, the
/// threads already running share the items.
template <typename MakeState, typename Work, typename AfterOwn>
void parallel_for_with_state(std::size_t count, unsigned threads, MakeState&& make_state,
                             Work&& work, AfterOwn&& after_own) {
  using State = std::invoke_result_t<MakeState&>;
  std::atomic<std::size_t> next{0};
  std::mutex error_mutex;
  std::exception_ptr error;
  const auto loop = [&](bool caller) {
    try {
      std::optional<State> state;
      for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
        if (!state) state.emplace(make_state());
        work(*state, i);
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

/// parallel_for_with_state without a per-item callback.
template <typename MakeState, typename Work>
void parallel_for_with_state(std::size_t count, unsigned threads, MakeState&& make_state,
                             Work&& work) {
  parallel_for_with_state(count, threads, std::forward<MakeState>(make_state),
                          std::forward<Work>(work), [] {});
}

/// Runs WORK(i) for i in [0, COUNT) on up to THREADS threads: parallel_for_with_state without
/// a state (same order, exceptions and caller callback AFTER_OWN).
template <typename Work, typename AfterOwn>
void parallel_for(std::size_t count, unsigned threads, Work&& work, AfterOwn&& after_own) {
  parallel_for_with_state(
      count, threads, [] { return 0; }, [&work](int, std::size_t i) { work(i); },
      std::forward<AfterOwn>(after_own));
}

/// parallel_for without a per-item callback.
template <typename Work>
void parallel_for(std::size_t count, unsigned threads, Work&& work) {
  parallel_for(count, threads, std::forward<Work>(work), [] {});
}

}  // namespace imunoise
