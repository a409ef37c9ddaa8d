// SPDX-License-Identifier: GPL-3.0-or-later
// A firmware that starts over inside a run (docs/protocol.md, "Restarts"), over a real
// pseudo-terminal and a real TCP socket, with a small client playing the board: this project's
// start-up codes again, or the first frame on a link that came back, is a restart; the motors
// stop until the new firmware commands them, lock-step comes back when it asks again, the
// scenario hears of it, and a firmware or client that keeps starting over ends the run.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <pty.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <thread>

#include "inline_assets.h"
#include "plugin_rig.h"
#include "pty_board.h"
#include "run_program.h"
#include "unimouse/errors.h"
#include "unimouse_protocol.h"

namespace unimouse {
namespace {

using testing::SignalValue;
using Board = testing::PtyBoard;

// what SimulationRobot::begin() sends, without lock-step
const std::vector<uint8_t> kStartUp = {UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_FRAME_SIZES,
                                       UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_SENSORS_ON,
                                       UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_REPEATS_COMMANDS};
const std::vector<uint8_t> kLockstepOn = {UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_LOCKSTEP_ON};
const std::vector<uint8_t> kStepDone = {UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_STEP_DONE};

class LinkRestartTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::FreshDirectory("link_restart");
    Make("pty:" + dir_ + "/board", "");
  }
  void TearDown() override {
    kernel_.reset();
    std::filesystem::remove_all(dir_);
  }
  void Make(const std::string& transport, const std::string& params) {
    kernel_.reset();
    const std::string yaml = testing::ReadBundledRobot() +
                             "  - { type: unimouse.link, name: link, params: { transport: '" +
                             transport + "'" + params + " } }\n";
    KernelOptions options;
    options.trust_robot_file = true;  // the test wrote the robot file
    options.log_sink = [this](double, int, const std::string&, const std::string& text) {
      lines_.push_back(text);
    };
    kernel_ = testing::MakeKernel(yaml, nullptr, options);
    kernel_->AddReportListener([this](const std::string&, int, const unimouse_report& r) {
      if (r.kind == UNIMOUSE_REPORT_RESTART) restarts_.push_back(static_cast<int>(r.value));
    });
  }
  void Step(int n) {
    for (int i = 0; i < n; ++i) kernel_->Step();
  }
  long Count(const std::string& line) const {
    return std::count(lines_.begin(), lines_.end(), line);
  }
  std::string board() const { return dir_ + "/board"; }

  std::string dir_;
  std::unique_ptr<Kernel> kernel_;
  std::vector<std::string> lines_;
  std::vector<int> restarts_;  // the count each restart report carried
};

TEST_F(LinkRestartTest, TheLibrarysStartUpCodesAgainMidRunAreARestartThatStopsTheMotors) {
  Board b(board());
  // a sketch may ask for the maze before its begin(); the first begin() of a run is no restart
  b.Send({UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_MAZE_INFO});
  b.Send(kStartUp);
  b.Motors(600, 600);
  Step(50);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 600);
  EXPECT_TRUE(restarts_.empty());
  // the reset button of a board whose USB port stays open: begin() again, nothing else yet
  b.Send(kStartUp);
  Step(1);
  EXPECT_EQ(Count("the firmware restarted at t=0.050 s (its start-up frames again): motors "
                  "stopped until it commands them; restart 1"),
            1);
  EXPECT_EQ(restarts_, std::vector<int>{1});
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 0);
  EXPECT_EQ(SignalValue(*kernel_, "right.command"), 0);
  Step(20);  // held at 0 while the new firmware says nothing
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 0);
  b.Motors(300, 300);
  Step(1);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 300);
  EXPECT_EQ(restarts_, std::vector<int>{1});
}

TEST_F(LinkRestartTest, AReopenedPtyIsARestartOfAnyFirmwareAtItsFirstFrame) {
  // firmware in the original's style: no start-up codes, a command only when it changes
  auto b = std::make_unique<Board>(board());
  b->Motors(600, 600);
  Step(50);
  b.reset();  // the other side closes: a board emulator quits, a cable is pulled
  Step(20);
  EXPECT_EQ(Count("firmware disconnected: motors stopped"), 1);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 0);
  EXPECT_TRUE(restarts_.empty());
  b = std::make_unique<Board>(board());  // and opens it again
  Step(5);
  EXPECT_TRUE(restarts_.empty());  // connected, but no firmware has spoken yet
  b->Motors(400, 400);
  Step(1);
  EXPECT_EQ(Count("the firmware restarted at t=0.075 s (its first frame after the link came "
                  "back): motors stopped until it commands them; restart 1"),
            1);
  EXPECT_EQ(restarts_, std::vector<int>{1});
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 400);  // its first frame counts
  // its commands are held through silence, as the original's were
  Step(300);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 400);
}

TEST_F(LinkRestartTest, LockstepEndsWithTheFirmwareThatAskedAndComesBackWhenTheNextAsks) {
  auto b = std::make_unique<Board>(board());
  b->Send(kStartUp);
  b->Send(kLockstepOn);
  b->Send(kStepDone);
  Step(1);
  EXPECT_TRUE(kernel_->firmware_paced());
  for (int i = 0; i < 10; ++i) {
    // a step's commands and its end, sent ahead: the step reads them before it waits
    b->Motors(500, 500);
    b->Send(kStepDone);
    Step(1);
  }
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 500);
  b.reset();
  // the step does not wait 5 s for a firmware that is gone, and the run goes on without it
  Step(10);
  EXPECT_FALSE(kernel_->firmware_paced());
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 0);
  b = std::make_unique<Board>(board());
  b->Send(kStartUp);
  b->Send(kLockstepOn);
  b->Send(kStepDone);
  Step(1);
  EXPECT_EQ(restarts_, std::vector<int>{1});
  EXPECT_TRUE(kernel_->firmware_paced());
  EXPECT_EQ(Count("lock-step on: the simulation waits for the firmware"), 2);
}

TEST_F(LinkRestartTest, AFirmwareThatKeepsRestartingEndsTheRunAfterMaxRestarts) {
  Make("pty:" + board(), ", max_restarts: 3");
  Board b(board());
  b.Send(kStartUp);
  b.Motors(100, 100);
  Step(1);
  try {
    // a board that resets every 10 ms
    for (int i = 0; i < 10; ++i) {
      b.Send(kStartUp);
      b.Motors(100, 100);
      Step(10);
    }
    FAIL() << "the run went on";
  } catch (const RuntimeFault& e) {
    EXPECT_EQ(std::string(e.what()),
              "component 'link' failed at t=0.031 s: the firmware restarted 4 times, more than "
              "max_restarts (3)");
  }
  EXPECT_EQ(restarts_, (std::vector<int>{1, 2, 3, 4}));
}

int ConnectTo(int port) {
  const int s = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(::connect(s, reinterpret_cast<sockaddr*>(&a), sizeof(a)), 0);
  return s;
}

void Write(int fd, const std::vector<uint8_t>& bytes) {
  ASSERT_EQ(::write(fd, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
}

TEST_F(LinkRestartTest, ATcpClientThatDialsAgainCarriesOnTheSameRunAsARestart) {
  const int port = 41000 + ::getpid() % 20000;
  Make("tcp:127.0.0.1:" + std::to_string(port), "");
  int client = ConnectTo(port);
  Write(client, kStartUp);
  const std::vector<uint8_t> go = {UNIMOUSE_ID_MOTOR_LEFT,  0x58, 0x02,
                                   UNIMOUSE_ID_MOTOR_RIGHT, 0x58, 0x02};  // 600 each
  Write(client, go);
  Step(20);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 600);
  ::close(client);  // Wi-Fi drops
  Step(10);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 0);
  client = ConnectTo(port);  // the board dials again and starts over
  Write(client, kStartUp);
  Step(1);
  EXPECT_EQ(restarts_, std::vector<int>{1});
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 0);
  Write(client, go);
  Step(1);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 600);
  ::close(client);
}

TEST_F(LinkRestartTest, AClientThatConnectsSendsAndClosesWithinOneStepIsSeenComeAndGo) {
  const int port = 43000 + ::getpid() % 20000;
  Make("tcp:127.0.0.1:" + std::to_string(port), "");
  const std::vector<uint8_t> go = {UNIMOUSE_ID_MOTOR_LEFT,  0x58, 0x02,
                                   UNIMOUSE_ID_MOTOR_RIGHT, 0x58, 0x02};  // 600 each
  int client = ConnectTo(port);
  Write(client, kStartUp);
  Write(client, go);
  Step(5);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 600);
  ::close(client);
  Step(2);
  // three visits, each over before the simulator's next read: it accepts the client, reads its
  // frames and its end in one go
  for (int i = 0; i < 3; ++i) {
    client = ConnectTo(port);
    Write(client, kStartUp);
    Write(client, go);
    ::close(client);
    // loopback hands the bytes over within microseconds, but on a loaded host the kernel may
    // finish the delivery a little later: the run is stepped by hand, so waiting costs it nothing
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    Step(1);
    // the visit's command lasted no longer than the link it came on
    EXPECT_EQ(SignalValue(*kernel_, "left.command"), 0) << "visit " << i;
  }
  EXPECT_EQ(restarts_, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(Count("firmware connected"), 4);
  EXPECT_EQ(Count("firmware disconnected: motors stopped"), 4);
}

TEST_F(LinkRestartTest, AClientThatKeepsDiallingEndsTheRunAfterMaxRestarts) {
  const int port = 42000 + ::getpid() % 20000;
  Make("tcp:127.0.0.1:" + std::to_string(port), ", max_restarts: 5");
  try {
    for (int i = 0; i < 50; ++i) {
      const int client = ConnectTo(port);
      Write(client, kStartUp);
      Step(1);
      ::close(client);
      Step(1);
    }
    FAIL() << "the run went on";
  } catch (const RuntimeFault& e) {
    const std::string what = e.what();
    // one connection every two steps: the sixth comes back at 12 ms
    EXPECT_EQ(what,
              "component 'link' failed at t=0.012 s: the firmware's link came back 6 times, more "
              "than max_restarts (5)");
  }
}

// a USB serial adapter as the kernel shows one: a tty whose stable name (udev's
// /dev/serial/by-id link) points at whatever device it got this time
struct UsbSerial {
  int board = -1;  // the board's end: the pty master
  std::string device;
  void PlugIn(const std::string& link) {
    int slave = -1;
    char name[256];
    ASSERT_EQ(::openpty(&board, &slave, name, nullptr, nullptr), 0);
    termios t{};
    ::tcgetattr(board, &t);
    ::cfmakeraw(&t);
    ::tcsetattr(board, TCSANOW, &t);
    ::fcntl(board, F_SETFL, O_NONBLOCK);
    ::close(slave);
    device = name;
    std::filesystem::remove(link);
    std::filesystem::create_symlink(device, link);
  }
  void Unplug() {
    ::close(board);  // the device vanishes: the simulator's reads fail
    board = -1;
  }
};

TEST_F(LinkRestartTest, ASerialPortUnpluggedAndPluggedBackCarriesOnTheSameRunAsARestart) {
  const std::string port = dir_ + "/ttyACM-board";
  UsbSerial usb;
  usb.PlugIn(port);
  Make("serial:" + port + "@1000000", "");
  Write(usb.board, kStartUp);
  Write(usb.board, {UNIMOUSE_ID_MOTOR_LEFT, 0xF4, 0x01, UNIMOUSE_ID_MOTOR_RIGHT, 0xF4, 0x01});
  Step(20);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 500);
  usb.Unplug();
  Step(20);
  EXPECT_EQ(Count("firmware disconnected: motors stopped"), 1);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 0);
  usb.PlugIn(port);  // back, maybe as another device
  // the link looks for the port twice a second of wall time: step until it has, a bounded while
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (SignalValue(*kernel_, "left.command") != 300 &&
         std::chrono::steady_clock::now() < give_up) {
    Write(usb.board, {UNIMOUSE_ID_MOTOR_LEFT, 0x2C, 0x01, UNIMOUSE_ID_MOTOR_RIGHT, 0x2C, 0x01});
    Step(10);
    ::usleep(10000);
  }
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 300);
  EXPECT_EQ(Count("firmware connected"), 2);
  EXPECT_EQ(restarts_, std::vector<int>{1});
  EXPECT_EQ(std::count_if(lines_.begin(), lines_.end(),
                          [](const std::string& l) {
                            return l.find(
                                       "(its first frame after the link came back): motors "
                                       "stopped until it commands them; restart 1") !=
                                   std::string::npos;
                          }),
            1);
  usb.Unplug();
}

// what a Mega's bootloader and a reset put on the line before the sketch runs: STK500 answers
// (0x14 0x10) and noise, a motor frame's id among it
const std::vector<uint8_t> kBootloaderNoise = {0x14, 0x10, 0x00, 0xFF, 0x05, 0xE8, 0x03, 0x14,
                                               0x10, 0xF0, 0x07, 0x99, 0x42, 0x00, 0x1B, 0x06};

TEST_F(LinkRestartTest, WaitingForTheFirmwareSkipsTheBootloadersBytesWithoutAWarning) {
  const std::string port = dir_ + "/ttyACM-board";
  UsbSerial usb;
  usb.PlugIn(port);
  Make("serial:" + port + "@1000000", ", wait_for_firmware_s: 10");
  Write(usb.board, kBootloaderNoise);
  Write(usb.board, kStartUp);
  Write(usb.board, {UNIMOUSE_ID_MOTOR_LEFT, 0x2C, 0x01, UNIMOUSE_ID_MOTOR_RIGHT, 0x2C, 0x01});
  Step(5);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 300);
  EXPECT_EQ(std::count_if(lines_.begin(), lines_.end(),
                          [](const std::string& l) {
                            return l.find(
                                       "; 16 bytes before them skipped (a bootloader's, or a "
                                       "reset's noise)") != std::string::npos;
                          }),
            1);
  for (const std::string& line : lines_) {
    EXPECT_EQ(line.find("unknown"), std::string::npos) << line;
  }
  EXPECT_TRUE(restarts_.empty());
  usb.Unplug();
}

TEST_F(LinkRestartTest, WithoutTheWaitTheBootloadersBytesAreReadAsFrames) {
  // the contrast: its 05 E8 03 is a motor command of 1000
  const std::string port = dir_ + "/ttyACM-board";
  UsbSerial usb;
  usb.PlugIn(port);
  Make("serial:" + port + "@1000000", "");
  Write(usb.board, kBootloaderNoise);
  Step(5);
  EXPECT_EQ(SignalValue(*kernel_, "left.command"), 1000);
  usb.Unplug();
}

TEST_F(LinkRestartTest, AFirmwareThatNeverStartsEndsTheWaitWithAReason) {
  const std::string port = dir_ + "/ttyACM-board";
  UsbSerial usb;
  usb.PlugIn(port);
  Make("serial:" + port + "@1000000", ", wait_for_firmware_s: 0.3");
  Write(usb.board, kBootloaderNoise);
  try {
    Step(1);
    FAIL() << "the run started without its firmware";
  } catch (const RuntimeFault& e) {
    EXPECT_EQ(std::string(e.what()),
              "component 'link' failed at t=0 s: no start-up frames from the firmware within 0.3 "
              "s (wait_for_firmware_s); 16 bytes came before");
  }
  usb.Unplug();
}

TEST(LinkRestartParamsTest, WrongRestartParametersAreBadInputWithOneLine) {
  const std::string dir = testing::FreshDirectory("link_restart_params");
  for (const auto& [set, line] : std::vector<std::pair<std::string, std::string>>{
           {"reset_cause=lightning",
            "unimouse: error: --link-set reset_cause=lightning: component 'link' (unimouse.link): "
            "reset_cause must be one of external|brownout, not 'lightning'\n"},
           {"max_restarts=0",
            "unimouse: error: --link-set max_restarts=0: component 'link' (unimouse.link): "
            "max_restarts must be within [1, 1e+06], not 0\n"},
           {"board_reset=ignore",
            "unimouse: error: --link-set board_reset=ignore: component 'link' (unimouse.link): "
            "board_reset must be one of restart|fail, not 'ignore'\n"}}) {
    const testing::Outcome o = testing::Unimouse("run --duration 0.01 --no-pictures --out " + dir +
                                                 " --link pty:" + dir + "/board --link-set " + set);
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_EQ(o.output, line);
  }
}

}  // namespace
}  // namespace unimouse
