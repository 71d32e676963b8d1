#include "core/stage_clock.h"

#include <gtest/gtest.h>

#include <cstring>
#include <chrono>
#include <memory>
#include <thread>

namespace isoquad {
namespace {

constexpr std::size_t kBig = 300u << 20;  // 300 MB

// Allocates and touches n bytes, holds them for a few samples, then frees them.
void touch_and_free(std::size_t n) {
  std::unique_ptr<char[]> p(new char[n]);
  std::memset(p.get(), 1, n);
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  volatile char sink = p[n / 2];
  (void)sink;
}

TEST(StageClock, EachStageHasItsOwnPeak) {
  std::vector<StageTime> stages;
  StageClock clock(stages);
  touch_and_free(kBig);
  clock.lap("big");
  touch_and_free(kBig / 30);
  clock.lap("small");
  ASSERT_EQ(stages.size(), 2u);
  EXPECT_EQ(stages[0].stage, "big");
  EXPECT_EQ(stages[1].stage, "small");
  EXPECT_GE(stages[0].seconds, 0.0);
  EXPECT_GE(stages[0].peak_mb, 300.0);
  EXPECT_GE(process_peak_mb(), stages[0].peak_mb - 1.0);
#ifdef __linux__
  // The 300 MB were freed before the second stage began: its peak is its own.
  ASSERT_TRUE(stage_peaks_supported());
  EXPECT_LT(stages[1].peak_mb, stages[0].peak_mb - 200.0);
#endif
}

}  // namespace
}  // namespace isoquad
