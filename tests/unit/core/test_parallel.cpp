#include "core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>

namespace isoquad {
namespace {

TEST(RunInParallel, RunsBothOnTwoThreads) {
  std::thread::id a_thread, b_thread;
  int a = 0, b = 0;
  run_in_parallel([&] { a = 1, a_thread = std::this_thread::get_id(); },
                  [&] { b = 2, b_thread = std::this_thread::get_id(); });
  EXPECT_EQ(a, 1);
  EXPECT_EQ(b, 2);
  EXPECT_EQ(a_thread, std::this_thread::get_id());
  EXPECT_NE(b_thread, a_thread);
}

TEST(RunInParallel, RethrowsTheSecondsErrorOnceBothAreDone) {
  std::atomic<bool> a_done{false};
  EXPECT_THROW(run_in_parallel([&] { a_done = true; }, [] { throw std::runtime_error("b"); }),
               std::runtime_error);
  EXPECT_TRUE(a_done);
}

TEST(RunInParallel, RethrowsTheFirstsErrorWhenBothFail) {
  std::atomic<bool> b_done{false};
  try {
    run_in_parallel([] { throw std::runtime_error("a"); },
                    [&] {
                      b_done = true;
                      throw std::logic_error("b");
                    });
    FAIL() << "nothing was thrown";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "a");
  }
  EXPECT_TRUE(b_done);  // joined before the rethrow
}

}  // namespace
}  // namespace isoquad
