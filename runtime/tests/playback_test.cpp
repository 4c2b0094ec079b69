// Playback: the window's frame counter (rate, loop, pause, step).
#include <gtest/gtest.h>

#include "walkrad/runtime/playback.h"

namespace walkrad {
namespace {

TEST(Playback, AdvancesAtTheFrameRateAndLoops) {
  Playback p(4, 10.0);  // 0.1 s per frame
  p.advance(0.05);
  EXPECT_EQ(p.frame(), 0u);
  p.advance(0.06);  // the two halves add up to one frame
  EXPECT_EQ(p.frame(), 1u);
  p.advance(0.3);
  EXPECT_EQ(p.frame(), 0u);  // 1 + 3 wraps past the last frame
}

TEST(Playback, PauseStopsTime) {
  Playback p(4, 10.0);
  p.toggle_pause();
  p.advance(1.0);
  EXPECT_EQ(p.frame(), 0u);
  EXPECT_TRUE(p.paused());
  p.toggle_pause();
  p.advance(0.1);
  EXPECT_EQ(p.frame(), 1u);
}

TEST(Playback, StepPausesAndWrapsBothWays) {
  Playback p(3, 30.0);
  p.step(-1);
  EXPECT_TRUE(p.paused());
  EXPECT_EQ(p.frame(), 2u);
  p.step(+1);
  EXPECT_EQ(p.frame(), 0u);
  p.step(+4);
  EXPECT_EQ(p.frame(), 1u);
}

}  // namespace
}  // namespace walkrad
