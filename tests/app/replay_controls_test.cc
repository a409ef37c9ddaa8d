// SPDX-License-Identifier: GPL-3.0-or-later
// The replay window's keys and timeline, without a window: play, pause, a sample back and
// forward, the speeds, event jumps, scrubbing and the end of the recording.
#include "replay_controls.h"

#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

namespace unimouse {
namespace {

// 10 s sampled every 10 ms, with events at 2.5, 4 and 7.25 s
ReplayTimeline Timeline() {
  ReplayTimeline t;
  t.end_s = 10;
  for (int k = 0; k <= 1000; ++k) t.samples.push_back(k * 0.01);
  t.marks = {2.5, 4, 7.25};
  return t;
}

TEST(ReplayControlsTest, PlaysAtItsSpeedAndStopsPausedAtTheEnd) {
  const ReplayTimeline t = Timeline();
  ReplayControls c;
  c.Play(0.5, t);
  EXPECT_DOUBLE_EQ(c.cursor_s, 0.5);
  c.speed = 4;
  c.Play(0.5, t);
  EXPECT_DOUBLE_EQ(c.cursor_s, 2.5);
  c.Play(10, t);
  EXPECT_DOUBLE_EQ(c.cursor_s, 10);
  EXPECT_TRUE(c.paused);
  // Space at the end plays again from the start
  ASSERT_TRUE(c.Key(GLFW_KEY_SPACE, t));
  EXPECT_FALSE(c.paused);
  EXPECT_DOUBLE_EQ(c.cursor_s, 0);
  ASSERT_TRUE(c.Key(GLFW_KEY_SPACE, t));
  c.Play(1, t);
  EXPECT_DOUBLE_EQ(c.cursor_s, 0) << "paused, the cursor stays";
}

TEST(ReplayControlsTest, TheArrowsStepOneSampleAndPause) {
  const ReplayTimeline t = Timeline();
  ReplayControls c;
  c.cursor_s = 3.005;  // between two samples
  c.Key(GLFW_KEY_RIGHT, t);
  EXPECT_TRUE(c.paused);
  EXPECT_NEAR(c.cursor_s, 3.01, 1e-12);
  c.Key(GLFW_KEY_RIGHT, t);
  EXPECT_NEAR(c.cursor_s, 3.02, 1e-12);
  c.Key(GLFW_KEY_LEFT, t);
  c.Key(GLFW_KEY_LEFT, t);
  EXPECT_NEAR(c.cursor_s, 3.0, 1e-12);
  c.cursor_s = 0;
  c.Key(GLFW_KEY_LEFT, t);
  EXPECT_EQ(c.cursor_s, 0) << "nothing before the first sample";
}

TEST(ReplayControlsTest, PlusAndMinusGoThroughTheSpeedsAndStopAtTheirEnds) {
  const ReplayTimeline t = Timeline();
  ReplayControls c;
  for (double expected : {2.0, 4.0, 8.0, 16.0, 16.0}) {
    c.Key(GLFW_KEY_EQUAL, t);
    EXPECT_EQ(c.speed, expected);
  }
  c.Key(GLFW_KEY_0, t);
  EXPECT_EQ(c.speed, 1);
  for (double expected : {0.5, 0.25, 0.1, 0.1}) {
    c.Key(GLFW_KEY_MINUS, t);
    EXPECT_EQ(c.speed, expected);
  }
}

TEST(ReplayControlsTest, BracketsJumpBetweenEventsAndPause) {
  const ReplayTimeline t = Timeline();
  ReplayControls c;
  c.cursor_s = 1;
  c.Key(GLFW_KEY_RIGHT_BRACKET, t);
  EXPECT_EQ(c.cursor_s, 2.5);
  EXPECT_TRUE(c.paused);
  c.Key(GLFW_KEY_PAGE_DOWN, t);
  EXPECT_EQ(c.cursor_s, 4);
  c.Key(GLFW_KEY_RIGHT_BRACKET, t);
  c.Key(GLFW_KEY_RIGHT_BRACKET, t);
  EXPECT_EQ(c.cursor_s, 7.25) << "no event after the last";
  c.Key(GLFW_KEY_LEFT_BRACKET, t);
  EXPECT_EQ(c.cursor_s, 4);
  c.Key(GLFW_KEY_PAGE_UP, t);
  c.Key(GLFW_KEY_PAGE_UP, t);
  EXPECT_EQ(c.cursor_s, 2.5);
  c.Key(GLFW_KEY_END, t);
  EXPECT_EQ(c.cursor_s, 10);
  c.Key(GLFW_KEY_HOME, t);
  EXPECT_EQ(c.cursor_s, 0);
}

TEST(ReplayControlsTest, TheTimelinesBarMapsToTheRecordingsLength) {
  const ReplayTimeline t = Timeline();
  ReplayControls c;
  c.Scrub(0.25, t);
  EXPECT_DOUBLE_EQ(c.cursor_s, 2.5);
  c.Scrub(1.7, t);
  EXPECT_DOUBLE_EQ(c.cursor_s, 10);
  c.Scrub(-1, t);
  EXPECT_DOUBLE_EQ(c.cursor_s, 0);
}

TEST(ReplayControlsTest, TheOtherKeysToggleWhatTheyShowAndAnUnknownKeyDoesNothing) {
  const ReplayTimeline t = Timeline();
  ReplayControls c;
  c.Key(GLFW_KEY_R, t);
  c.Key(GLFW_KEY_B, t);
  c.Key(GLFW_KEY_U, t);
  c.Key(GLFW_KEY_F, t);
  c.Key(GLFW_KEY_2, t);
  c.Key(GLFW_KEY_S, t);
  EXPECT_FALSE(c.beams);
  EXPECT_FALSE(c.beliefs);
  EXPECT_FALSE(c.hud);
  EXPECT_TRUE(c.follow);
  EXPECT_EQ(c.preset, "chase");
  EXPECT_TRUE(c.screenshot);
  EXPECT_FALSE(c.Key(GLFW_KEY_Z, t));
  c.Key(GLFW_KEY_ESCAPE, t);
  EXPECT_TRUE(c.quit);
}

}  // namespace
}  // namespace unimouse
