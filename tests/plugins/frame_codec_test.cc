// SPDX-License-Identifier: GPL-3.0-or-later
// Golden byte vectors of the link protocol (docs/protocol.md), both directions, with the
// boundaries: no target, clamps, frames and log lines split across reads, garbage.
#include "frame_codec.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <string>
#include <vector>

#include "rng.h"

namespace unimouse::link {
namespace {

std::vector<uint8_t> Bytes(const std::string& s) { return {s.begin(), s.end()}; }

std::vector<FirmwareFrame> Decode(const std::vector<uint8_t>& bytes) {
  FrameDecoder decoder;
  std::vector<FirmwareFrame> frames;
  decoder.Feed(bytes, frames);
  return frames;
}

TEST(FrameCodecTest, TofFramesCarryCountsOfTheFullScale) {
  std::string out;
  PutTofFrame(UNIMOUSE_ID_TOF_FRONT, 0.6, 1.2, out);  // half scale: round(32767.5) = 32768
  PutTofFrame(UNIMOUSE_ID_TOF_LEFT, 0.0, 1.2, out);
  PutTofFrame(UNIMOUSE_ID_TOF_RIGHT, 1.2, 1.2, out);  // full scale is "no target"
  PutTofFrame(UNIMOUSE_ID_TOF_RIGHT, 5.0, 1.2, out);
  EXPECT_EQ(Bytes(out), (std::vector<uint8_t>{0x02, 0x00, 0x80, 0x00, 0x00, 0x00, 0x01, 0xFF, 0xFF,
                                              0x01, 0xFF, 0xFF}));
  // 0.05 m: round(0.05 / 1.2 * 65535) = round(2730.625) = 2731 = 0x0AAB, little-endian
  out.clear();
  PutTofFrame(UNIMOUSE_ID_TOF_FRONT, 0.05, 1.2, out);
  EXPECT_EQ(Bytes(out), (std::vector<uint8_t>{0x02, 0xAB, 0x0A}));
}

TEST(FrameCodecTest, EncoderFramesAreSignedLittleEndianDeltas) {
  std::string out;
  PutEncoderFrame(UNIMOUSE_ID_ENCODER_LEFT, 4, out);
  PutEncoderFrame(UNIMOUSE_ID_ENCODER_RIGHT, -4, out);
  PutEncoderFrame(UNIMOUSE_ID_ENCODER_LEFT, 70000, out);  // clamped to int16
  EXPECT_EQ(Bytes(out),
            (std::vector<uint8_t>{0x03, 0x04, 0x00, 0x04, 0xFC, 0xFF, 0x03, 0xFF, 0x7F}));
}

TEST(FrameCodecTest, ClockFramesCarryMicroseconds) {
  std::string out;
  PutClockFrame(1234567, out);  // 0x0012D687
  EXPECT_EQ(Bytes(out), (std::vector<uint8_t>{0x09, 0x87, 0xD6, 0x12, 0x00}));
}

TEST(FrameCodecTest, MazeInfoFramesCarrySizeCellInMillimetresAndGoalRectangle) {
  std::string out;
  BindContext::MazeInfo maze;
  maze.width_cells = 32;
  maze.height_cells = 32;
  maze.cell_m = 0.09;
  maze.goal_x0 = 1;
  maze.goal_y0 = 2;
  maze.goal_x1 = 3;
  maze.goal_y1 = 4;
  PutMazeInfoFrame(maze, out);
  EXPECT_EQ(Bytes(out), (std::vector<uint8_t>{0x0E, 32, 32, 0x5A, 0x00, 1, 2, 3, 4}));
  out.clear();
  maze.cell_m = 0.18;
  PutMazeInfoFrame(maze, out);
  EXPECT_EQ(Bytes(out)[3], 0xB4);  // 180 mm
}

TEST(FrameCodecTest, MazeSizeFramesFromTheFirmwareCarryWidthAndHeight) {
  const auto f = Decode({0x0F, 16, 16, 0x07, 0x13});
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].id, UNIMOUSE_ID_MAZE_SIZE);
  EXPECT_EQ(f[0].data, (std::vector<uint8_t>{16, 16}));
  EXPECT_EQ(f[1].value, UNIMOUSE_MANAGER_MAZE_INFO);
}

TEST(FrameCodecTest, MotorCommandsAreClampedTo1023) {
  const auto f = Decode({0x05, 0xFF, 0x03, 0x06, 0x01, 0xFC, 0x05, 0xD0, 0x07, 0x06, 0x00, 0x80});
  ASSERT_EQ(f.size(), 4u);
  EXPECT_EQ(f[0].id, UNIMOUSE_ID_MOTOR_LEFT);
  EXPECT_EQ(f[0].value, 1023);
  EXPECT_EQ(f[1].id, UNIMOUSE_ID_MOTOR_RIGHT);
  EXPECT_EQ(f[1].value, -1023);
  EXPECT_EQ(f[2].value, 1023);   // 2000
  EXPECT_EQ(f[3].value, -1023);  // -32768
}

TEST(FrameCodecTest, ManagerBytes) {
  const auto f = Decode({0x07, 0x02, 0x07, 0x03, 0x07, 0x10, 0x07, 0x11});
  ASSERT_EQ(f.size(), 4u);
  EXPECT_EQ(f[0].value, UNIMOUSE_MANAGER_SENSORS_ON);
  EXPECT_EQ(f[1].value, UNIMOUSE_MANAGER_SENSORS_OFF);
  EXPECT_EQ(f[2].value, UNIMOUSE_MANAGER_LOCKSTEP_ON);
  EXPECT_EQ(f[3].value, UNIMOUSE_MANAGER_STEP_DONE);
}

TEST(FrameCodecTest, FramesAndLogLinesSplitAcrossReadsWait) {
  FrameDecoder decoder;
  std::vector<FirmwareFrame> f;
  const std::vector<uint8_t> stream = {0x05, 0x20, 0x03, 0x08, 'h',  'e', 'l',
                                       'l',  'o',  0x00, 0x06, 0xE0, 0xFC};
  // one byte at a time: nothing is lost, nothing is early
  for (size_t i = 0; i < stream.size(); ++i) {
    decoder.Feed(std::span<const uint8_t>(&stream[i], 1), f);
    if (i < 2) {
      EXPECT_TRUE(f.empty());
    }
  }
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0].value, 800);
  EXPECT_EQ(f[1].id, UNIMOUSE_ID_LOG);
  EXPECT_EQ(f[1].text, "hello");
  EXPECT_EQ(f[2].value, -800);
}

TEST(FrameCodecTest, OverlongLogLinesAreCutAndTheRestSkipped) {
  std::vector<uint8_t> bytes = {0x08};
  bytes.insert(bytes.end(), 300, 'x');
  bytes.push_back(0x00);
  bytes.insert(bytes.end(), {0x05, 0x01, 0x00});
  const auto f = Decode(bytes);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].text.size(), static_cast<size_t>(UNIMOUSE_LOG_MAX));
  EXPECT_EQ(f[1].value, 1);
}

TEST(FrameCodecTest, UnknownIdsAreCountedAndSkipped) {
  FrameDecoder decoder;
  std::vector<FirmwareFrame> f;
  // 0x03 is a sensor id, never sent by firmware; 0xEE is nothing
  const std::vector<uint8_t> bytes = {0xEE, 0x03, 0x05, 0x10, 0x00, 0xEE};
  decoder.Feed(bytes, f);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].value, 16);
  EXPECT_EQ(decoder.unknown_bytes(), 3u);
  EXPECT_EQ(decoder.unknown_ids(), (std::vector<uint8_t>{0xEE, 0x03}));
}

// Serial.println("t=12 left=0.500") on a board, between the library's frames: "\r\n" would
// otherwise read as a debug value ('\r' = 0x0D) and a debug walls frame ('\n' = 0x0A)
TEST(FrameCodecTest, PrintedTextBetweenFramesIsReadAsLogLinesWhateverTheReadsPieces) {
  std::vector<uint8_t> bytes = Bytes("t=12 left=0.500\r\n");
  bytes.insert(bytes.end(), {0x05, 0x64, 0x00});  // left motor 100
  bytes.push_back('x');                           // a print without its newline
  bytes.insert(bytes.end(), {0x07, 0x01, 0x08, 'h', 'i', 0x00, 0x0B, 2, 3});
  for (const size_t piece : {bytes.size(), size_t{1}, size_t{4}}) {
    FrameDecoder decoder;
    std::vector<FirmwareFrame> f;
    for (size_t at = 0; at < bytes.size(); at += piece) {
      decoder.Feed(std::span(bytes).subspan(at, std::min(piece, bytes.size() - at)), f);
    }
    ASSERT_EQ(f.size(), 6u) << piece;
    EXPECT_EQ(f[0].id, UNIMOUSE_ID_LOG);
    EXPECT_TRUE(f[0].plain_text);
    EXPECT_EQ(f[0].text, "t=12 left=0.500");
    EXPECT_EQ(f[1].value, 100);
    EXPECT_EQ(f[2].text, "x");
    EXPECT_TRUE(f[2].plain_text);
    EXPECT_EQ(f[3].id, UNIMOUSE_ID_MANAGER);
    EXPECT_EQ(f[4].text, "hi");
    EXPECT_FALSE(f[4].plain_text);
    EXPECT_EQ(f[5].data, (std::vector<uint8_t>{2, 3}));
    EXPECT_EQ(decoder.unknown_bytes(), 0u);
    EXPECT_EQ(decoder.text_lines(), 2u);
  }
}

TEST(FrameCodecTest, DebugFrames) {
  std::vector<uint8_t> value = {0x0D};
  const float speed = 0.75f;
  const auto* raw = reinterpret_cast<const uint8_t*>(&speed);
  value.insert(value.end(), raw, raw + 4);
  value.insert(value.end(), {'v', 0x00});
  std::vector<uint8_t> bytes = {0x0A, 3, 4, 0x0B, 0x0F, 0x0B, 3, 4, 0x0C, 2, 0, 0, 0, 1};
  bytes.insert(bytes.end(), value.begin(), value.end());
  const auto f = Decode(bytes);
  ASSERT_EQ(f.size(), 4u);
  EXPECT_EQ(f[0].data, (std::vector<uint8_t>{3, 4, 0x0B, 0x0F}));
  EXPECT_EQ(f[1].data, (std::vector<uint8_t>{3, 4}));
  EXPECT_EQ(f[2].data, (std::vector<uint8_t>{0, 0, 0, 1}));
  EXPECT_EQ(f[3].text, "v");
  EXPECT_EQ(f[3].number, 0.75f);
}

TEST(FrameCodecTest, GarbageNeverStopsTheDecoder) {
  RngStream rng(7, "garbage");
  FrameDecoder decoder;
  std::vector<FirmwareFrame> f;
  std::vector<uint8_t> noise(20000);
  for (auto& b : noise) b = static_cast<uint8_t>(rng.NextBits());
  decoder.Feed(noise, f);
  // then, after any garbage, a log line's end and a clean frame get through
  const std::vector<uint8_t> clean = {0x00, 0x05, 0x64, 0x00};
  std::vector<FirmwareFrame> after;
  decoder.Reset();
  decoder.Feed(clean, after);
  ASSERT_FALSE(after.empty());
  EXPECT_EQ(after.back().value, 100);
  EXPECT_GT(decoder.unknown_bytes(), 0u);
}

}  // namespace
}  // namespace unimouse::link
