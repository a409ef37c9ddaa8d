// SPDX-License-Identifier: GPL-3.0-or-later
// The link end to end over a real pseudo-terminal, with a small client playing the board: motor
// frames drive the robot, sensor frames arrive at their rates, manager bytes are honoured,
// garbage is survived, a vanished board trips the failsafe and a returning one is heard again,
// and in lock-step two runs with the same seed and client are identical.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <pty.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "inline_assets.h"
#include "plugin_rig.h"
#include "pty_board.h"
#include "rng.h"
#include "run_program.h"
#include "unimouse/errors.h"
#include "unimouse_protocol.h"

namespace unimouse {
namespace {

using testing::SetSignal;
using testing::SignalValue;

using Board = testing::PtyBoard;

class LinkTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::FreshDirectory("link");
    path_ = dir_ + "/board";
    Make("", nullptr);
  }
  // the bundled robot with a pty link given more parameters, on an open floor or in a maze
  void Make(const std::string& params, const Maze* maze) {
    kernel_.reset();
    const std::string yaml =
        testing::ReadBundledRobot() +
        "  - { type: unimouse.link, name: link, params: { transport: 'pty:" + path_ + "'" + params +
        " } }\n";
    KernelOptions options;
    options.trust_robot_file = true;  // the test wrote the robot file
    options.seed = 3;
    options.log_sink = [this](double, int level, const std::string&, const std::string& text) {
      if (level == UNIMOUSE_LOG_WARNING) warnings_.push_back(text);
    };
    kernel_ = testing::MakeKernel(yaml, maze, options);
  }
  void TearDown() override {
    kernel_.reset();
    std::filesystem::remove_all(dir_);
  }
  void Step(int n) {
    for (int i = 0; i < n; ++i) kernel_->Step();
  }
  Pose2D Pose() const { return kernel_->world().RobotPose(kernel_->state().data()); }

  std::string dir_;
  std::string path_;
  std::unique_ptr<Kernel> kernel_;
  std::vector<std::string> warnings_;
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

TEST_F(LinkTest, AFirmwareThatAsksForTheMazeIsToldItsSizeCellAndGoalOnce) {
  // a 32 x 32 maze is half-size: 90 mm cells; its goal, the 3 x 3 cells (1, 2) to (3, 4)
  Maze maze(32, 32);
  std::vector<Cell> goal;
  for (int x = 1; x <= 3; ++x) {
    for (int y = 2; y <= 4; ++y) goal.push_back({x, y});
  }
  maze.set_goals(goal);
  Make(", send: '3 left.encoder_counts i16'", &maze);
  Board board(path_);
  Step(2);
  EXPECT_EQ(board.Bytes(), (std::vector<uint8_t>{3, 0, 0, 3, 0, 0}));  // nothing unasked
  board.Send({UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_MAZE_INFO});
  Step(1);
  // the step's encoder frame, then the answer
  EXPECT_EQ(board.Bytes(), (std::vector<uint8_t>{3, 0, 0, 14, 32, 32, 90, 0, 1, 2, 3, 4}));
  Step(2);
  EXPECT_EQ(board.Bytes().size(), 6u);  // once
  EXPECT_TRUE(warnings_.empty());
}

TEST_F(LinkTest, AFirmwareWhoseMazeIsAnotherSizeThanTheWorldsIsWarnedAbout) {
  const Maze maze(32, 32);
  Make("", &maze);
  Board board(path_);
  board.Send({UNIMOUSE_ID_MAZE_SIZE, 32, 32});
  Step(2);
  EXPECT_TRUE(warnings_.empty());
  board.Send({UNIMOUSE_ID_MAZE_SIZE, 16, 16});
  Step(2);
  ASSERT_EQ(warnings_.size(), 1u);
  EXPECT_EQ(warnings_[0],
            "the firmware works with a 16 x 16 maze, but the world's maze is 32 x 32: it cannot "
            "know the whole maze");
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

TEST_F(LinkTest, SilenceFromFirmwareThatNeverSaidItRepeatsItsCommandsHoldsThem) {
  Board board(path_);
  board.Motors(600, 600);  // once, as the original's library did, and then nothing
  Step(500);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 600);
  EXPECT_EQ(SignalValue(*kernel_, "right.command"), 600);
  EXPECT_GT(Pose().y_m, 0.1);  // still driving north after half a second of silence
}

TEST_F(LinkTest, SilenceFromFirmwareThatRepeatsItsCommandsStopsTheMotorsWithin100ms) {
  Board board(path_);
  board.Send({UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_REPEATS_COMMANDS});
  board.Motors(600, 600);
  Step(50);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 600);
  Step(55);  // more than 100 ms since its last frame
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 0);
  EXPECT_EQ(SignalValue(*kernel_, "right.command"), 0);
  board.Motors(300, 300);  // and it is heard again
  Step(2);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 300);
}

// what the simulator sent: its frames' ids, and the last front ToF frame's counts
struct SentFrames {
  std::vector<uint8_t> ids;
  uint16_t last_front = 0;
};
SentFrames ReadFrames(const std::vector<uint8_t>& bytes) {
  SentFrames sent;
  for (size_t i = 0; i < bytes.size();) {
    const int size = unimouse_payload_size(bytes[i]);
    if (size < 0 || i + 1 + static_cast<size_t>(size) > bytes.size()) break;
    sent.ids.push_back(bytes[i]);
    if (bytes[i] == UNIMOUSE_ID_TOF_FRONT) sent.last_front = unimouse_get_u16(&bytes[i + 1]);
    i += 1 + static_cast<size_t>(size);
  }
  return sent;
}

TEST_F(LinkTest, TheOriginalsProfileSpeaksItsScaleHoldsCommandsAndIgnoresExtensions) {
  const Maze maze = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  Make(", profile: unimousesim-0.1", &maze);
  Board board(path_);
  // what a firmware of ours would say: the original's link does not answer it
  board.Send({UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_REPEATS_COMMANDS});
  board.Send({UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_LOCKSTEP_ON});
  Step(31);  // the ToF frames of steps 0 and 30; the reading of step 30 is still the signal's
  const SentFrames sent = ReadFrames(board.Bytes());
  const double front_m = SignalValue(*kernel_, "tof.front_m");
  ASSERT_LT(front_m, 1.0);  // a wall in sight
  // counts at the original library's 1.0 m full scale, not 1.2 m
  EXPECT_EQ(sent.last_front, unimouse_tof_to_counts(front_m, 1.0));
  EXPECT_FALSE(kernel_->firmware_paced());  // no lock-step, so no clock frame either
  EXPECT_EQ(std::count(sent.ids.begin(), sent.ids.end(), UNIMOUSE_ID_CLOCK), 0);
  EXPECT_EQ(std::count(sent.ids.begin(), sent.ids.end(), UNIMOUSE_ID_TOF_FRONT), 2);
  board.Motors(600, 600);
  Step(300);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 600);  // silence holds the commands
  board.Close();                                          // but a lost link stops them
  Step(2);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 0);
  EXPECT_EQ(SignalValue(*kernel_, "right.command"), 0);
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
  std::vector<std::vector<uint64_t>> traces(2);
  for (int run = 0; run < 2; ++run) {
    if (run == 1) {
      kernel_.reset();
      SetUp();
    }
    Board board(path_);
    board.Send({UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_LOCKSTEP_ON});
    std::thread firmware(LockstepBoard, std::ref(board), 400);
    for (int i = 0; i < 400; ++i) {
      kernel_->Step();
      traces[static_cast<size_t>(run)].push_back(kernel_->state().Hash());
    }
    firmware.join();
    EXPECT_TRUE(kernel_->firmware_paced());
    const mjData& d = kernel_->state().data();
    finals.emplace_back(d.qpos, d.qpos + kernel_->mj_model().nq);
  }
  EXPECT_GT(finals[0][1], 0.05);    // it really drove
  EXPECT_EQ(traces[0], traces[1]);  // step by step, the whole state
  EXPECT_EQ(std::memcmp(finals[0].data(), finals[1].data(), finals[0].size() * sizeof(mjtNum)), 0);
}

// a kernel whose link uses `transport`
std::unique_ptr<Kernel> KernelWithLink(const std::string& transport) {
  const std::string yaml = testing::ReadBundledRobot() +
                           "  - { type: unimouse.link, name: link, params: { transport: '" +
                           transport + "' } }\n";
  KernelOptions options;
  options.trust_robot_file = true;  // the test wrote the robot file
  return testing::MakeKernel(yaml, nullptr, options);
}

std::vector<uint8_t> MotorFrames(int16_t left, int16_t right) {
  std::vector<uint8_t> f = {UNIMOUSE_ID_MOTOR_LEFT, 0, 0, UNIMOUSE_ID_MOTOR_RIGHT, 0, 0};
  unimouse_put_u16(&f[1], static_cast<uint16_t>(left));
  unimouse_put_u16(&f[4], static_cast<uint16_t>(right));
  return f;
}

size_t ReadAll(int fd) {
  uint8_t buffer[4096];
  size_t total = 0;
  ssize_t n;
  while ((n = ::read(fd, buffer, sizeof(buffer))) > 0) total += static_cast<size_t>(n);
  return total;
}

TEST(LinkTransportTest, ASerialPortCarriesTheProtocolAtItsBaudRate) {
  // a pty's slave side is a real tty: the link opens it as a serial port, the test is the board
  int board = -1, slave = -1;
  char name[256];
  ASSERT_EQ(::openpty(&board, &slave, name, nullptr, nullptr), 0);
  termios t{};
  ::tcgetattr(board, &t);
  ::cfmakeraw(&t);
  ::tcsetattr(board, TCSANOW, &t);
  ::fcntl(board, F_SETFL, O_NONBLOCK);
  auto kernel = KernelWithLink(std::string("serial:") + name + "@115200");
  const auto f = MotorFrames(500, 500);
  ASSERT_EQ(::write(board, f.data(), f.size()), 6);
  for (int i = 0; i < 100; ++i) kernel->Step();
  EXPECT_EQ(SignalValue(*kernel, "left.command"), 500);
  // 100 steps of encoder frames (600 bytes) and 4 sets of ToF frames (36 bytes) fit 115200 baud
  EXPECT_EQ(ReadAll(board), 636u);
  ::close(board);
  ::close(slave);
}

TEST(LinkTransportTest, ASlowLineDropsWhatItCannotCarry) {
  int board = -1, slave = -1;
  char name[256];
  ASSERT_EQ(::openpty(&board, &slave, name, nullptr, nullptr), 0);
  ::fcntl(board, F_SETFL, O_NONBLOCK);
  termios t{};
  ::tcgetattr(board, &t);
  ::cfmakeraw(&t);
  ::tcsetattr(board, TCSANOW, &t);
  // 9600 baud carries 0.96 bytes a millisecond, the encoders alone want 6
  auto kernel = KernelWithLink(std::string("serial:") + name + "@9600");
  for (int i = 0; i < 1000; ++i) kernel->Step();
  const size_t got = ReadAll(board);
  EXPECT_LE(got, 960u + 16u);  // never faster than the line
  EXPECT_GE(got, 900u);        // and it keeps the line busy
  ::close(board);
  ::close(slave);
}

TEST(LinkTransportTest, ATcpClientDrivesTheRobotAndCanComeBack) {
  const int port = 40000 + ::getpid() % 20000;
  auto kernel = KernelWithLink("tcp:127.0.0.1:" + std::to_string(port));
  auto connect_client = [&] {
    const int s = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(::connect(s, reinterpret_cast<sockaddr*>(&a), sizeof(a)), 0);
    return s;
  };
  int client = connect_client();
  const auto f = MotorFrames(450, 450);
  ASSERT_EQ(::write(client, f.data(), f.size()), 6);
  for (int i = 0; i < 20; ++i) kernel->Step();
  EXPECT_EQ(SignalValue(*kernel, "left.command"), 450);
  ::close(client);
  for (int i = 0; i < 150; ++i) kernel->Step();
  EXPECT_EQ(SignalValue(*kernel, "left.command"), 0);  // failsafe
  client = connect_client();
  const auto g = MotorFrames(-300, -300);
  ASSERT_EQ(::write(client, g.data(), g.size()), 6);
  for (int i = 0; i < 20; ++i) kernel->Step();
  EXPECT_EQ(SignalValue(*kernel, "left.command"), -300);
  ::close(client);
}

TEST(LinkTransportTest, BadTransportSpecsAreBadInput) {
  EXPECT_THROW(KernelWithLink("carrier-pigeon"), InputError);
  EXPECT_THROW(KernelWithLink("serial:/dev/no_such_port@115200"), InputError);
  EXPECT_THROW(KernelWithLink("tcp::99999"), InputError);
  EXPECT_THROW(KernelWithLink("native:/no/such/program"), InputError);
}

// the gyro robot with a link on a serial port (which `check` never opens) sending `send`
std::string RobotWithSerialLink(const std::string& send, const std::string& line) {
  const std::string path = testing::FreshDirectory("link_bandwidth") + "/robot.yaml";
  std::ofstream(path) << testing::GyroRobotWith(
      "  - { type: unimouse.imu, name: imu, params: { site: imu } }\n"
      "  - { type: unimouse.link, name: link,\n"
      "      params: { transport: '" +
      line + "', send: '" + send + "' } }\n");
  return path;
}

constexpr const char* kSixAxes =
    "20 imu.gyro_x_counts i16; 21 imu.gyro_y_counts i16; 22 imu.gyro_z_counts i16; "
    "23 imu.accel_x_counts i16; 24 imu.accel_y_counts i16; 25 imu.accel_z_counts i16";

TEST(LinkBandwidthTest, CheckWarnsWhenSixImuAxesAtOneKilohertzOutrunA115200BaudLine) {
  const testing::Outcome o =
      testing::Unimouse("check " + RobotWithSerialLink(kSixAxes, "serial:/dev/ttyUSB9@115200"));
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("the send table needs 18000 bytes a second at its periods, more than "
                          "the 11520 a 115200 baud line carries"),
            std::string::npos)
      << o.output;
}

TEST(LinkBandwidthTest, CheckIsQuietWhenTheLineCarriesTheTable) {
  // a megabaud line carries 100,000 B/s; gyro z alone at 1 kHz is 3,000 B/s on 115200 baud
  for (const auto& [send, line] :
       {std::pair<std::string, std::string>{kSixAxes, "serial:/dev/ttyUSB9@1000000"},
        {"22 imu.gyro_z_counts i16", "serial:/dev/ttyUSB9@115200"}}) {
    const testing::Outcome o = testing::Unimouse("check " + RobotWithSerialLink(send, line));
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_EQ(o.output.find("send table needs"), std::string::npos) << o.output;
  }
}

}  // namespace
}  // namespace unimouse
