// SPDX-License-Identifier: GPL-3.0-or-later
// The link's frame tables: what a good table reads as, and the one-line reason for each kind of
// mistake, naming the parameter and the entry.
#include "frame_table.h"

#include <gtest/gtest.h>

#include "unimouse/errors.h"

namespace unimouse::link {
namespace {

// the message a table is refused with, or "" when it is accepted
std::string ErrorOf(std::vector<TableEntry> (*parse)(const std::string&), const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string SendError(const std::string& text) { return ErrorOf(&ParseSendTable, text); }
std::string ReceiveError(const std::string& text) { return ErrorOf(&ParseReceiveTable, text); }

TEST(FrameTableTest, TheDefaultSendTableIsTheOriginalsEncodersThenToFsEvery30Ms) {
  const std::vector<TableEntry> t = ParseSendTable(kOriginalSend);
  ASSERT_EQ(t.size(), 5u);
  const int ids[] = {3, 4, 0, 1, 2};
  const char* signals[] = {"left.encoder_counts", "right.encoder_counts", "tof.left_m",
                           "tof.right_m", "tof.front_m"};
  for (size_t i = 0; i < t.size(); ++i) {
    EXPECT_EQ(t[i].id, ids[i]);
    EXPECT_EQ(t[i].signal, signals[i]);
    EXPECT_EQ(t[i].encoding, i < 2 ? Encoding::kI16 : Encoding::kTof);
    EXPECT_EQ(t[i].period_s, i < 2 ? 0 : 0.03);
  }
}

TEST(FrameTableTest, TheDefaultReceiveTableIsTheOriginalsMotorCommands) {
  const std::vector<TableEntry> t = ParseReceiveTable(kOriginalReceive);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].id, 5);
  EXPECT_EQ(t[0].signal, "left.command");
  EXPECT_EQ(t[0].encoding, Encoding::kMotor);
  EXPECT_EQ(t[1].id, 6);
  EXPECT_EQ(t[1].signal, "right.command");
}

TEST(FrameTableTest, SpacesTabsAndLineBreaksSeparateWordsAndABlankTableIsEmpty) {
  const std::vector<TableEntry> t =
      ParseSendTable("  20\tgyro.yaw_rate_rad_s   f32 0.002 ;\n 255 x i16 0 ");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].id, 20);
  EXPECT_EQ(t[0].encoding, Encoding::kF32);
  EXPECT_EQ(t[0].period_s, 0.002);
  EXPECT_EQ(t[1].id, 255);
  EXPECT_EQ(t[1].period_s, 0);
  EXPECT_TRUE(ParseSendTable("").empty());
  EXPECT_TRUE(ParseReceiveTable("  \n ").empty());
}

TEST(FrameTableTest, EachEncodingBelongsToItsDirection) {
  EXPECT_EQ(SendError("0 a tof; 1 b i16; 2 c f32"), "");
  EXPECT_EQ(ReceiveError("5 a motor; 6 b i16; 16 c f32"), "");
  EXPECT_EQ(SendError("5 left.command motor"),
            "send entry 1 ('5 left.command motor'): unknown encoding 'motor'; send takes tof, "
            "i16 or f32");
  EXPECT_EQ(ReceiveError("0 tof.left_m tof"),
            "receive entry 1 ('0 tof.left_m tof'): unknown encoding 'tof'; receive takes motor, "
            "i16 or f32");
  EXPECT_EQ(SendError("3 left.encoder_counts i16; 4 right.encoder_counts i17"),
            "send entry 2 ('4 right.encoder_counts i17'): unknown encoding 'i17'; send takes "
            "tof, i16 or f32");
}

TEST(FrameTableTest, ControlIdsCannotBeTaken) {
  EXPECT_EQ(
      SendError("7 a i16"),
      "send entry 1 ('7 a i16'): id 7 is the protocol's manager frame (ids 7 to 15 and 127 are "
      "taken)");
  EXPECT_EQ(
      ReceiveError("8 a i16"),
      "receive entry 1 ('8 a i16'): id 8 is the protocol's log frame (ids 7 to 15 and 127 are "
      "taken)");
  EXPECT_NE(SendError("9 a f32").find("clock frame"), std::string::npos);
  EXPECT_NE(SendError("127 a i16").find("frame size frame"), std::string::npos);
  for (int id = 10; id <= 13; ++id) {
    EXPECT_NE(ReceiveError(std::to_string(id) + " a i16").find("debug frame"), std::string::npos);
  }
}

TEST(FrameTableTest, AnIdAppearsOncePerDirection) {
  EXPECT_EQ(SendError("3 a i16; 4 b i16; 3 c tof"),
            "send entry 3 ('3 c tof'): id 3 is already in send entry 1 ('3 a i16')");
  EXPECT_EQ(ReceiveError("5 a motor; 5 b motor"),
            "receive entry 2 ('5 b motor'): id 5 is already in receive entry 1 ('5 a motor')");
  // the two directions are separate
  EXPECT_EQ(SendError("5 a i16"), "");
}

TEST(FrameTableTest, AReceivedSignalHasOneEntry) {
  EXPECT_EQ(ReceiveError("5 left.command motor; 6 left.command motor"),
            "receive entry 2 ('6 left.command motor'): signal 'left.command' is already written "
            "by receive entry 1 ('5 left.command motor')");
  // one signal may go out twice, in two encodings
  EXPECT_EQ(SendError("0 tof.left_m tof; 20 tof.left_m f32"), "");
}

TEST(FrameTableTest, IdsAreWholeNumbersUpTo255) {
  for (const char* bad : {"256 a i16", "-1 a i16", "x a i16", "3.0 a i16", "0x10 a i16"}) {
    const std::string e = SendError(bad);
    EXPECT_NE(e.find("is not a frame id (0 to 255)"), std::string::npos) << bad << ": " << e;
    EXPECT_EQ(e.rfind(std::string("send entry 1 ('") + bad + "')", 0), 0u) << e;
  }
}

TEST(FrameTableTest, EntriesHaveTheirWordsAndNoEmptyOnes) {
  EXPECT_EQ(SendError("3 a"), "send entry 1 ('3 a'): write ID SIGNAL ENCODING [PERIOD_S]");
  EXPECT_EQ(SendError("3 a i16 0.001 extra"),
            "send entry 1 ('3 a i16 0.001 extra'): write ID SIGNAL ENCODING [PERIOD_S]");
  EXPECT_EQ(ReceiveError("5 a motor 0.01"),
            "receive entry 1 ('5 a motor 0.01'): write ID SIGNAL ENCODING");
  EXPECT_EQ(SendError("3 a i16;; 4 b i16"),
            "send entry 2 (''): empty entry; entries are separated by one ';'");
  EXPECT_EQ(SendError("3 a i16;"),
            "send entry 2 (''): empty entry; entries are separated by one ';'");
}

TEST(FrameTableTest, PeriodsAreNonNegativeSeconds) {
  for (const char* bad : {"abc", "-0.03", "0.03s", "nan", "inf"}) {
    EXPECT_EQ(SendError(std::string("0 a tof ") + bad),
              std::string("send entry 1 ('0 a tof ") + bad + "'): '" + bad +
                  "' is not a period in seconds (0 or more)");
  }
}

TEST(FrameTableTest, APeriodIsAWholeNumberOfLinkSteps) {
  const std::vector<TableEntry> t = ParseSendTable("3 a i16; 0 b tof 0.03; 20 c f32 0");
  EXPECT_EQ(StepsPerFrame(t[0], 0.001), 1);
  EXPECT_EQ(StepsPerFrame(t[1], 0.001), 30);
  EXPECT_EQ(StepsPerFrame(t[1], 0.002), 15);
  EXPECT_EQ(StepsPerFrame(t[2], 0.002), 1);
  const std::vector<TableEntry> odd = ParseSendTable("3 a i16; 0 b tof 0.0305");
  try {
    StepsPerFrame(odd[1], 0.001);
    FAIL() << "a period of 30.5 steps was taken";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "send entry 2 ('0 b tof 0.0305'): period 0.0305 s is not a whole number of the "
              "link's 0.001 s steps");
  }
  EXPECT_THROW(StepsPerFrame(ParseSendTable("0 b tof 0.0005")[0], 0.001), InputError);
}

TEST(FrameTableTest, SixImuAxesAtOneKilohertzNeedEighteenThousandBytesASecond) {
  // six int16 frames of 3 bytes (id and payload) every 1 ms step: 18,000 B/s, more than the
  // 11,520 a 115200 baud line carries at 10 bits a byte
  const std::vector<TableEntry> six = ParseSendTable(
      "20 imu.gyro_x_counts i16; 21 imu.gyro_y_counts i16; 22 imu.gyro_z_counts i16; "
      "23 imu.accel_x_counts i16; 24 imu.accel_y_counts i16; 25 imu.accel_z_counts i16");
  EXPECT_DOUBLE_EQ(SendBytesPerSecond(six, 0.001), 18000);
  // the original's table: 2 encoders every step and 3 ToF sensors every 30 ms
  EXPECT_DOUBLE_EQ(SendBytesPerSecond(ParseSendTable(kOriginalSend), 0.001), 6000 + 300);
  // gyro z alone, and a float every 10 ms
  EXPECT_DOUBLE_EQ(
      SendBytesPerSecond(ParseSendTable("22 imu.gyro_z_counts i16; 30 x f32 0.01"), 0.001),
      3000 + 500);
}

}  // namespace
}  // namespace unimouse::link
