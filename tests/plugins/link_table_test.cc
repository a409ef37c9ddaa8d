// SPDX-License-Identifier: GPL-3.0-or-later
// The link's frame tables end to end: a robot with five ToF sensors and a gyro, a sensor the link
// knows nothing about, reaches a firmware through its send table alone, each frame in its order,
// encoding and period; incoming frames write the signals of the receive table, the failsafe
// zeroes them all; a reset forgets everything the link holds; a flood is read 64 KiB a step.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "frame_codec.h"
#include "inline_assets.h"
#include "link.h"
#include "plugin_rig.h"
#include "probe_components.h"
#include "pty_board.h"
#include "run_program.h"
#include "text_file.h"
#include "unimouse/errors.h"
#include "unimouse_protocol.h"

namespace unimouse {
namespace {

using testing::SignalValue;

// the original's frames, then the two side sensors and the gyro, every other step
constexpr const char* kFiveTofSend =
    "3 left.encoder_counts i16; 4 right.encoder_counts i16; 0 tof.left_m tof 0.03; "
    "1 tof.right_m tof 0.03; 2 tof.front_m tof 0.03; 16 tof.left_side_m tof 0.03; "
    "17 tof.right_side_m tof 0.03; 20 gyro.yaw_rate_rad_s f32 0.002";
constexpr const char* kFiveTofReport = "3:i16,4:i16,0:tof,1:tof,2:tof,16:tof,17:tof,20:f32";

struct Sent {
  int id;
  const char* signal;
  const char* encoding;
  int every_n_steps;
};
constexpr Sent kFiveTofFrames[] = {
    {3, "left.encoder_counts", "i16", 1}, {4, "right.encoder_counts", "i16", 1},
    {0, "tof.left_m", "tof", 30},         {1, "tof.right_m", "tof", 30},
    {2, "tof.front_m", "tof", 30},        {16, "tof.left_side_m", "tof", 30},
    {17, "tof.right_side_m", "tof", 30},  {20, "gyro.yaw_rate_rad_s", "f32", 2},
};

// one frame as the firmware reported it: "rx ID STEP VALUE"
struct Received {
  int id = -1;
  int step = -1;
  std::string value;
};

class LinkTableTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::FreshDirectory("link_table");
    registry_.AddStatic(ComponentType<testing::Gyro>());
  }
  void TearDown() override {
    kernel_.reset();
    std::filesystem::remove_all(dir_);
  }

  void Make(const std::string& robot_yaml, const Maze* maze = nullptr) {
    KernelOptions options;
    options.trust_robot_file = true;  // the test wrote the robot file
    options.seed = 9;
    options.output_dir = dir_;
    options.log_sink = [this](double, int level, const std::string&, const std::string& text) {
      messages_.push_back(text);
      if (level == UNIMOUSE_LOG_FIRMWARE && text.rfind("rx ", 0) == 0) {
        Received r;
        std::istringstream in(text.substr(3));
        in >> r.id >> r.step >> r.value;
        received_.push_back(r);
      }
    };
    kernel_ = Kernel::Create(ParseRobotSpec(robot_yaml, "robot.yaml"), maze, registry_, options);
  }

  // the five-ToF robot with a gyro, turning on the spot in the start cell, its firmware
  // reporting every table frame; the sent signals' values recorded after each step
  void RunFiveTofRobot(int steps) {
    const std::string yaml =
        testing::FiveTofRobot() + "  - { type: test.gyro, name: gyro }\n" +
        "  - { type: unimouse.link, name: link, params: { transport: 'native:" +
        UNIMOUSE_TEST_FIRMWARE + " --report " + kFiveTofReport + " --motors 400,-400', send: '" +
        kFiveTofSend + "' } }\n";
    Make(yaml, &maze_);
    for (int i = 0; i < steps; ++i) {
      kernel_->Step();
      for (const Sent& s : kFiveTofFrames) values_[s.id].push_back(SignalValue(*kernel_, s.signal));
    }
  }

  std::string LastMessageContaining(const std::string& part) const {
    for (auto it = messages_.rbegin(); it != messages_.rend(); ++it) {
      if (it->find(part) != std::string::npos) return *it;
    }
    return "";
  }

  int CountMessages(const std::string& start) const {
    int n = 0;
    for (const std::string& m : messages_) n += m.rfind(start, 0) == 0;
    return n;
  }

  std::string dir_;
  PluginRegistry registry_ = testing::BundledComponents();
  const Maze maze_ = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  std::unique_ptr<Kernel> kernel_;
  std::vector<std::string> messages_;
  std::vector<Received> received_;
  std::map<int, std::vector<double>> values_;  // frame id -> its signal after each step
};

TEST_F(LinkTableTest, EachTableFrameReachesTheFirmwareOnTheStepsOfItsPeriod) {
  RunFiveTofRobot(100);
  std::map<int, std::vector<int>> steps;
  for (const Received& r : received_) steps[r.id].push_back(r.step);
  for (const Sent& s : kFiveTofFrames) {
    std::vector<int> expected;
    for (int step = 0; step < 100; step += s.every_n_steps) expected.push_back(step);
    EXPECT_EQ(steps[s.id], expected) << "frame " << s.id;
  }
}

TEST_F(LinkTableTest, FramesGoOutInTheTablesOrderWithinAStep) {
  RunFiveTofRobot(31);
  std::map<int, std::vector<int>> order;  // step -> ids in arrival order
  for (const Received& r : received_) order[r.step].push_back(r.id);
  EXPECT_EQ(order[0], (std::vector<int>{3, 4, 0, 1, 2, 16, 17, 20}));
  EXPECT_EQ(order[1], (std::vector<int>{3, 4}));
  EXPECT_EQ(order[2], (std::vector<int>{3, 4, 20}));
  EXPECT_EQ(order[30], (std::vector<int>{3, 4, 0, 1, 2, 16, 17, 20}));
}

TEST_F(LinkTableTest, EachFrameCarriesItsSignalInItsEncoding) {
  RunFiveTofRobot(100);
  ASSERT_FALSE(received_.empty());
  int side_hits = 0, turning = 0;
  for (const Received& r : received_) {
    const Sent* sent = nullptr;
    for (const Sent& s : kFiveTofFrames) sent = s.id == r.id ? &s : sent;
    ASSERT_NE(sent, nullptr) << r.id;
    const double v = values_[r.id].at(static_cast<size_t>(r.step));
    const std::string encoding = sent->encoding;
    if (encoding == "tof") {
      EXPECT_EQ(std::stol(r.value), unimouse_tof_to_counts(v, 1.2)) << r.id << " at " << r.step;
      side_hits += (r.id == 16 || r.id == 17) && std::stol(r.value) < UNIMOUSE_TOF_NO_TARGET;
    } else if (encoding == "i16") {
      EXPECT_EQ(std::stol(r.value), std::lround(v)) << r.id << " at " << r.step;
    } else {
      EXPECT_EQ(std::strtof(r.value.c_str(), nullptr), static_cast<float>(v)) << r.step;
      turning += std::fabs(v) > 0.1;
    }
  }
  // the side sensors see the start cell's walls, and the gyro sees the turn
  EXPECT_EQ(side_hits, 8);
  EXPECT_GT(turning, 10);
}

// a robot whose link is a pty with the given extra parameters, and a board on it
std::string PtyLinkRobot(const std::string& path, const std::string& params) {
  return testing::ReadBundledRobot() +
         "  - { type: unimouse.link, name: link, params: { transport: 'pty:" + path + "'" + params +
         " } }\n";
}

// a frame of `id` whose payload is the bytes of `value`, little-endian as on this machine
template <class T>
std::vector<uint8_t> Frame(uint8_t id, T value) {
  std::vector<uint8_t> f(1 + sizeof(T));
  f[0] = id;
  std::memcpy(f.data() + 1, &value, sizeof(T));
  return f;
}

TEST_F(LinkTableTest, TheDefaultTablesSendTheOriginalsBytes) {
  Make(PtyLinkRobot(dir_ + "/board", ""));
  testing::PtyBoard board(dir_ + "/board");
  // what the original sent: both encoders every step, the three ToF sensors every 30th
  std::string expected;
  for (int step = 0; step < 65; ++step) {
    if (step % 20 == 0) board.Motors(700, 500);
    kernel_->Step();
    link::PutEncoderFrame(UNIMOUSE_ID_ENCODER_LEFT,
                          std::lround(SignalValue(*kernel_, "left.encoder_counts")), expected);
    link::PutEncoderFrame(UNIMOUSE_ID_ENCODER_RIGHT,
                          std::lround(SignalValue(*kernel_, "right.encoder_counts")), expected);
    if (step % 30 != 0) continue;
    int id = UNIMOUSE_ID_TOF_LEFT;
    for (const char* tof : {"tof.left_m", "tof.right_m", "tof.front_m"}) {
      link::PutTofFrame(static_cast<uint8_t>(id++), SignalValue(*kernel_, tof), 1.2, expected);
    }
  }
  const std::vector<uint8_t> sent = board.Bytes();
  EXPECT_EQ(std::string(sent.begin(), sent.end()), expected);
  EXPECT_GT(SignalValue(*kernel_, "left.encoder_counts"), 0);  // it moved: the counts are real
}

TEST_F(LinkTableTest, ReceivedFramesWriteTheSignalsOfTheReceiveTable) {
  Make(PtyLinkRobot(dir_ + "/board",
                    ", receive: '5 left.command motor; 6 right.command motor; "
                    "20 test.gain f32; 21 test.offset i16'"));
  testing::PtyBoard board(dir_ + "/board");
  const float gain = 2.5f;
  const int16_t offset = -1234;
  const int16_t too_fast = 2000;
  board.Send(Frame(20, gain));
  board.Send(Frame(21, offset));
  board.Send(Frame(UNIMOUSE_ID_MOTOR_LEFT, too_fast));
  for (int i = 0; i < 3; ++i) kernel_->Step();
  EXPECT_EQ(SignalValue(*kernel_, "test.gain"), 2.5);
  EXPECT_EQ(SignalValue(*kernel_, "test.offset"), -1234);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 1023);  // motor frames are clamped
}

TEST_F(LinkTableTest, TheFailsafeZeroesEveryReceivedSignal) {
  Make(PtyLinkRobot(dir_ + "/board",
                    ", receive: '5 left.command motor; 20 test.gain f32; 21 test.offset i16'"));
  testing::PtyBoard board(dir_ + "/board");
  const float gain = -0.5f;
  const int16_t offset = 7, left = 300;
  // it says it repeats its commands, so its silence stops them
  board.Send({UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_REPEATS_COMMANDS});
  board.Send(Frame(20, gain));
  board.Send(Frame(21, offset));
  board.Send(Frame(UNIMOUSE_ID_MOTOR_LEFT, left));
  for (int i = 0; i < 5; ++i) kernel_->Step();
  ASSERT_EQ(SignalValue(*kernel_, "test.gain"), -0.5);
  for (int i = 0; i < 101; ++i) kernel_->Step();  // 0.1 s of silence
  EXPECT_EQ(SignalValue(*kernel_, "test.gain"), 0);
  EXPECT_EQ(SignalValue(*kernel_, "test.offset"), 0);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 0);
}

TEST_F(LinkTableTest, AResetForgetsQueuedBytesCountersAndUnknownIds) {
  // 9600 baud carries under a byte a step: the queue fills with frames of a robot in motion
  Make(PtyLinkRobot(dir_ + "/board", ", baud: 9600"));
  testing::PtyBoard board(dir_ + "/board");
  board.Send({0xEE, UNIMOUSE_ID_DEBUG_VISITED, 1, 2});
  for (int i = 0; i < 40; ++i) {
    board.Motors(800, 800);
    for (int j = 0; j < 50; ++j) kernel_->Step();
  }
  kernel_->Finish();
  unsigned long frames = 0, unknown = 0, dropped = 0;
  ASSERT_EQ(std::sscanf(LastMessageContaining(" frames from the firmware, ").c_str(),
                        "%lu frames from the firmware, %lu unknown bytes; %lu bytes dropped",
                        &frames, &unknown, &dropped),
            3);
  EXPECT_EQ(frames, 81u);
  EXPECT_EQ(unknown, 1u);
  EXPECT_GT(dropped, 1000u);
  const std::string beliefs = dir_ + "/firmware_beliefs.json";
  EXPECT_NE(ReadTextFile(beliefs).find("\"visited\": [[1, 2]]"), std::string::npos);
  board.Bytes();

  kernel_->Reset();
  board.Send({0xEE});
  for (int i = 0; i < 20; ++i) kernel_->Step();
  // the first bytes out are the new run's: encoders at rest, then the left ToF frame
  const std::vector<uint8_t> bytes = board.Bytes();
  ASSERT_GE(bytes.size(), 7u);
  EXPECT_EQ(std::vector<uint8_t>(bytes.begin(), bytes.begin() + 7),
            (std::vector<uint8_t>{3, 0, 0, 4, 0, 0, 0}));
  EXPECT_LE(bytes.size(), 20u);  // and the line's budget started again from nothing
  kernel_->Finish();
  EXPECT_EQ(LastMessageContaining(" frames from the firmware, "),
            "0 frames from the firmware, 1 unknown bytes; 0 bytes dropped");
  EXPECT_NE(ReadTextFile(beliefs).find("\"visited\": []"), std::string::npos);
  // the unknown id and the board's arrival are news again after the reset
  EXPECT_EQ(CountMessages("unknown frame id 0xee"), 2);
  EXPECT_EQ(CountMessages("firmware connected"), 2);
}

TEST_F(LinkTableTest, AFirmwareThatFloodsIsReadAtMost64KiBAStep) {
  Make(testing::ReadBundledRobot() +
       "  - { type: unimouse.link, name: link, params: { transport: 'native:" +
       UNIMOUSE_TEST_FIRMWARE + " --flood 1000000' } }\n");
  try {
    kernel_->Step();
    FAIL() << "the flood went on";
  } catch (const RuntimeFault& e) {
    EXPECT_NE(std::string(e.what()).find("the firmware sent more than 65536 bytes at t=0.000 s"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(LinkTableTest, AFirmwareThatFloodsEveryStepEndsTheRunWithAFault) {
  // 40000 bytes before each step's answer, in lock-step, so that every step reads all of them
  Make(testing::ReadBundledRobot() +
       "  - { type: unimouse.link, name: link, params: { transport: 'native:" +
       UNIMOUSE_TEST_FIRMWARE + " --flood-every-step 40000' } }\n");
  int steps = 0;
  try {
    for (; steps < 500; ++steps) kernel_->Step();
    FAIL() << "the flood went on";
  } catch (const RuntimeFault& e) {
    EXPECT_NE(std::string(e.what()).find("the firmware floods the link: "), std::string::npos)
        << e.what();
  }
  // 1 MiB, plus 1048.576 bytes a 1 ms step, is past after 1048576 / (40000 - 1048.576) = 26.9
  // steps of it
  EXPECT_GE(steps, 26);
  EXPECT_LE(steps, 28);
}

TEST_F(LinkTableTest, RandomBytesFromAFirmwareGiveABoundedNumberOfWarnings) {
  // 256 KiB from a fixed generator: every unknown id and manager byte there is, many times
  std::string bytes;
  uint32_t x = 12345;
  for (int i = 0; i < 256 * 1024; ++i) {
    x = x * 1664525u + 1013904223u;
    bytes += static_cast<char>(x >> 24);
  }
  const std::string junk = dir_ + "/junk.bin";
  std::ofstream(junk, std::ios::binary) << bytes;
  Make(testing::ReadBundledRobot() +
       "  - { type: unimouse.link, name: link, params: { transport: 'native:/usr/bin/tail -c +1 "
       "-f " +
       junk + "', extensions: false } }\n");
  // tail sends the file, then stays, as a firmware would; the pauses give it the time to
  for (int i = 0; i < 200; ++i) {
    kernel_->Step();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  kernel_->Finish();
  // what random bytes warn of (the link's last line counts unknown bytes too, as information)
  int warnings = 0;
  for (const std::string& m : messages_) {
    warnings += m.find(" frames from the firmware, ") == std::string::npos &&
                (m.find("unknown") != std::string::npos || m.find("ignored") != std::string::npos);
  }
  EXPECT_LE(warnings, 100);
  const auto note = std::find(messages_.begin(), messages_.end(),
                              "more than 100 warnings: later ones are counted, not shown");
  EXPECT_NE(note, messages_.end());
  EXPECT_NE(std::find_if(messages_.begin(), messages_.end(),
                         [](const std::string& m) {
                           return m.find("more messages were not shown") != std::string::npos;
                         }),
            messages_.end());
}

TEST_F(LinkTableTest, ATableMistakeIsBadInputNamingTheParameterAndEntry) {
  try {
    Make(PtyLinkRobot(dir_ + "/board", ", send: '3 left.encoder_counts i16; 8 x f32'"));
    FAIL() << "the table was taken";
  } catch (const InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find("send entry 2 ('8 x f32'): id 8 is the protocol's log frame"),
        std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/board"));  // nothing was opened
}

}  // namespace
}  // namespace unimouse
