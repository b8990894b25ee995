// Tests of common/parallel_for.h: every item runs once whatever the thread count, each thread
// makes its state once, and an exception of any type from any thread reaches the caller.
#include "common/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace imunoise {
namespace {

TEST(ParallelFor, EveryItemRunsOnceAtAnyThreadCount) {
  for (unsigned threads : {1u, 2u, 3u, 8u}) {
    std::vector<std::atomic<int>> runs(1000);
    parallel_for(runs.size(), threads, [&](std::size_t i) { ++runs[i]; });
    for (const auto& r : runs) ASSERT_EQ(r.load(), 1) << threads;
  }
}

TEST(ParallelForWithState, EachThreadMakesItsStateOnceAndReusesIt) {
  std::mutex m;
  std::set<std::thread::id> makers;
  int states = 0;
  std::vector<int> owner(200, -1);
  parallel_for_with_state(
      owner.size(), 3,
      [&] {
        const std::lock_guard lock(m);
        EXPECT_TRUE(makers.insert(std::this_thread::get_id()).second) << "state made twice";
        return states++;
      },
      [&](int& state, std::size_t i) { owner[i] = state; });
  EXPECT_GE(states, 1);
  EXPECT_LE(states, 3);
  for (int o : owner) EXPECT_TRUE(o >= 0 && o < states);
}

TEST(ParallelForWithState, NoItemsMakesNoState) {
  int states = 0;
  parallel_for_with_state(
      0, 4, [&] { return ++states; }, [](int, std::size_t) {});
  EXPECT_EQ(states, 0);
}

TEST(ParallelForWithState, AnExceptionOfAnyTypeFromAHelperThreadReachesTheCaller) {
  // Over 20 rounds at 2 threads the throwing item lands on the helper thread in some of them.
  for (int round = 0; round < 20; ++round) {
    try {
      parallel_for_with_state(
          64, 2, [] { return 0; },
          [&](int, std::size_t i) {
            if (i == 1) throw 42;  // not a std::exception: would terminate a bare std::thread
          });
      ADD_FAILURE() << "no exception";
    } catch (int e) {
      EXPECT_EQ(e, 42);
    }
    try {
      parallel_for(64, 2, [](std::size_t i) {
        if (i == 3) throw std::runtime_error("item 3");
      });
      ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "item 3");
    }
  }
}

}  // namespace
}  // namespace imunoise
