// SPDX-License-Identifier: GPL-3.0-or-later
// The link end to end over a real pseudo-terminal, with a small client playing the board: motor
// frames drive the robot, sensor frames arrive at their rates, manager bytes are honoured,
// garbage is survived, a vanished board trips the failsafe and a returning one is heard again,
// and in lock-step two runs with the same seed and client are identical.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <termios.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <thread>

#include "inline_assets.h"
#include "plugin_rig.h"
#include "rng.h"
#include "unimouse_protocol.h"

namespace unimouse {
namespace {

using testing::SetSignal;
using testing::SignalValue;

// the board's side of the pty
class Board {
 public:
  explicit Board(const std::string& path) { Open(path); }
  ~Board() { Close(); }
  void Open(const std::string& path) {
    fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
    EXPECT_GE(fd_, 0) << path << ": " << std::strerror(errno);
    termios t{};
    ::tcgetattr(fd_, &t);
    ::cfmakeraw(&t);
    ::tcsetattr(fd_, TCSANOW, &t);
  }
  void Close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  int fd() const { return fd_; }
  void Send(std::vector<uint8_t> bytes) {
    ASSERT_EQ(::write(fd_, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  }
  void Motors(int16_t left, int16_t right) {
    uint8_t f[6] = {UNIMOUSE_ID_MOTOR_LEFT, 0, 0, UNIMOUSE_ID_MOTOR_RIGHT, 0, 0};
    unimouse_put_u16(f + 1, static_cast<uint16_t>(left));
    unimouse_put_u16(f + 4, static_cast<uint16_t>(right));
    Send({f, f + 6});
  }
  // everything the simulator has sent so far, frame ids counted
  std::map<int, int> Drain() {
    std::vector<uint8_t> bytes;
    uint8_t buffer[4096];
    ssize_t n;
    while ((n = ::read(fd_, buffer, sizeof(buffer))) > 0)
      bytes.insert(bytes.end(), buffer, buffer + n);
    std::map<int, int> ids;
    for (size_t i = 0; i < bytes.size(); i += 1 + unimouse_payload_size(bytes[i])) ++ids[bytes[i]];
    return ids;
  }

 private:
  int fd_ = -1;
};

class LinkTest : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = (std::filesystem::temp_directory_path() /
             ("unimouse_link_" + std::to_string(::getpid()) + "_" +
              ::testing::UnitTest::GetInstance()->current_test_info()->name()))
                .string();
    const std::string robot = testing::ReadBundledRobot();
    const std::string yaml =
        robot + "  - { type: unimouse.link, name: link, params: { transport: 'pty:" + path_ +
        "' } }\n";
    KernelOptions options;
    options.seed = 3;
    kernel_ = testing::MakeKernel(yaml, nullptr, options);
  }
  void Step(int n) {
    for (int i = 0; i < n; ++i) kernel_->Step();
  }
  Pose2D Pose() const { return kernel_->world().RobotPose(kernel_->state().data()); }

  std::string path_;
  std::unique_ptr<Kernel> kernel_;
};

TEST_F(LinkTest, MotorFramesMoveTheWheelsTheRightWay) {
  Board board(path_);
  // a board repeats its commands, as the Arduino library does, so the failsafe stays quiet
  for (int i = 0; i < 10; ++i) {
    board.Motors(800, 800);
    Step(50);
  }
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 800);
  EXPECT_GT(Pose().y_m, 0.1);  // facing north, it drove north
  for (int i = 0; i < 6; ++i) {
    board.Motors(800, -800);
    Step(50);
  }
  EXPECT_LT(kernel_->state().data().qvel[5], -1);  // left forward, right back: clockwise
}

TEST_F(LinkTest, EncoderFramesEveryStepToFFramesEvery30Ms) {
  Board board(path_);
  Step(90);
  const std::map<int, int> ids = board.Drain();
  EXPECT_EQ(ids.at(UNIMOUSE_ID_ENCODER_LEFT), 90);
  EXPECT_EQ(ids.at(UNIMOUSE_ID_ENCODER_RIGHT), 90);
  for (int tof : {UNIMOUSE_ID_TOF_LEFT, UNIMOUSE_ID_TOF_RIGHT, UNIMOUSE_ID_TOF_FRONT}) {
    EXPECT_EQ(ids.at(tof), 3);  // steps 0, 30 and 60
  }
  EXPECT_EQ(ids.count(UNIMOUSE_ID_CLOCK), 0u);  // no extension unless asked for
}

TEST_F(LinkTest, ManagerBytesTurnSensorFramesOffAndOn) {
  Board board(path_);
  board.Send({UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_SENSORS_OFF});
  Step(2);
  board.Drain();
  Step(100);
  EXPECT_TRUE(board.Drain().empty());
  board.Send({UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_SENSORS_ON});
  Step(10);
  EXPECT_GE(board.Drain()[UNIMOUSE_ID_ENCODER_LEFT], 9);
}

TEST_F(LinkTest, GarbageNeitherCrashesNorBlocksTheSimulation) {
  Board board(path_);
  RngStream rng(11, "garbage");
  for (int burst = 0; burst < 10; ++burst) {
    std::vector<uint8_t> noise(500);
    for (auto& b : noise) b = static_cast<uint8_t>(rng.NextBits());
    board.Send(noise);
    Step(20);
    board.Drain();
  }
  EXPECT_EQ(kernel_->state().step(), 200);
  // the stream is readable again once any half frame is flushed out by zeros
  board.Send(std::vector<uint8_t>(600, 0));
  Step(2);
  board.Motors(300, 300);
  Step(2);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 300);
}

TEST_F(LinkTest, AVanishedBoardTripsTheFailsafeAndAReturningOneIsHeard) {
  auto board = std::make_unique<Board>(path_);
  board->Motors(600, 600);
  Step(50);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 600);
  board.reset();  // unplugged
  Step(101);      // within 100 ms the motors are off
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 0);
  EXPECT_EQ(SignalValue(*kernel_, "right.command"), 0);
  Step(100);
  board = std::make_unique<Board>(path_);  // plugged back in
  board->Motors(400, 400);
  Step(5);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 400);
}

// a deterministic board, already in lock-step: waits for each clock frame, answers with a
// command from the front reading it got, and says the step is done
void LockstepBoard(Board& board, int steps) {
  std::vector<uint8_t> pending;
  int clocks = 0;
  uint16_t front = 0xFFFF;
  while (clocks < steps) {
    uint8_t buffer[512];
    const ssize_t got = ::read(board.fd(), buffer, sizeof(buffer));
    if (got <= 0) {
      std::this_thread::sleep_for(std::chrono::microseconds(50));
      continue;
    }
    pending.insert(pending.end(), buffer, buffer + got);
    size_t i = 0;
    while (i < pending.size()) {
      const int size = unimouse_payload_size(pending[i]);
      if (i + 1 + static_cast<size_t>(size) > pending.size()) break;
      if (pending[i] == UNIMOUSE_ID_TOF_FRONT) front = unimouse_get_u16(&pending[i + 1]);
      if (pending[i] == UNIMOUSE_ID_CLOCK) {
        ++clocks;
        const int16_t speed = front > 20000 ? 700 : 0;  // stop before the wall
        board.Motors(speed, static_cast<int16_t>(speed - 20));
        board.Send({UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_STEP_DONE});
      }
      i += 1 + size;
    }
    pending.erase(pending.begin(), pending.begin() + static_cast<long>(i));
  }
}

TEST_F(LinkTest, LockstepRunsWithTheSameSeedAndBoardAreIdentical) {
  std::vector<std::vector<mjtNum>> finals;
  for (int run = 0; run < 2; ++run) {
    if (run == 1) {
      kernel_.reset();
      SetUp();
    }
    Board board(path_);
    board.Send({UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_LOCKSTEP_ON});
    std::thread firmware(LockstepBoard, std::ref(board), 400);
    Step(400);
    firmware.join();
    EXPECT_EQ(SignalValue(*kernel_, "link.lockstep"), 1);
    const mjData& d = kernel_->state().data();
    finals.emplace_back(d.qpos, d.qpos + kernel_->mj_model().nq);
  }
  EXPECT_GT(finals[0][1], 0.05);  // it really drove
  EXPECT_EQ(std::memcmp(finals[0].data(), finals[1].data(), finals[0].size() * sizeof(mjtNum)), 0);
}

}  // namespace
}  // namespace unimouse
