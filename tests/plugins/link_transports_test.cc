// SPDX-License-Identifier: GPL-3.0-or-later
// The link's one list of transports: the help and the error for an unknown scheme show every
// entry; checking a robot file opens none of them, and a robot file cannot ask for one that runs
// a firmware or makes a path.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "inline_assets.h"
#include "plugin_rig.h"
#include "run_program.h"
#include "text_file.h"
#include "transport.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

TEST(LinkTransportsTest, RunHelpListsEveryTransportWithItsUsage) {
  const testing::Outcome o = testing::Unimouse("run --help");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  ASSERT_GE(link::Transports().size(), 4u);
  for (const link::TransportKind& kind : link::Transports()) {
    EXPECT_NE(o.output.find(kind.usage), std::string::npos) << kind.scheme << "\n" << o.output;
  }
  EXPECT_NE(o.output.find(std::string("connect firmware: ") + link::TransportUsages()),
            std::string::npos)
      << o.output;
}

TEST(LinkTransportsTest, AnUnknownSchemeIsRefusedWithTheListOfTransports) {
  try {
    link::OpenTransport("carrier-pigeon:coop");
    FAIL() << "a pigeon was taken";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("unknown transport 'carrier-pigeon:coop': ", 0), 0u) << what;
    for (const link::TransportKind& kind : link::Transports()) {
      EXPECT_NE(what.find(kind.usage), std::string::npos) << what;
    }
  }
}

TEST(LinkTransportsTest, EachTransportSaysWhetherItPacesFromTheFirstStepAndItsLineRate) {
  const auto pty = link::OpenTransport("pty");
  EXPECT_FALSE(pty->lockstep_from_start());
  EXPECT_EQ(pty->line_baud(), 0);
  const auto native = link::OpenTransport(std::string("native:") + UNIMOUSE_TEST_FIRMWARE);
  EXPECT_TRUE(native->lockstep_from_start());
  EXPECT_EQ(native->line_baud(), 0);
}

// the cores a thread may run on, as the kernel lists them ("0-1", "3")
std::string AllowedCores(const std::string& status_text) {
  const size_t at = status_text.find("Cpus_allowed_list:");
  return at == std::string::npos ? "" : status_text.substr(at, status_text.find('\n', at) - at);
}

TEST(LinkTransportsTest, ANativeFirmwareSharesTheSimulatorsCoreWhileTheLinkIsOpen) {
  const std::string dir = testing::FreshDirectory("native_core");
  const std::string seen = dir + "/firmware_status";
  WriteTextFile(dir + "/firmware.sh", "cat /proc/self/status > " + seen + ".part && mv " + seen +
                                          ".part " + seen + "\nexec cat\n");
  const std::string before = AllowedCores(ReadTextFile("/proc/thread-self/status"));
  {
    const auto native = link::OpenTransport("native:/bin/sh " + dir + "/firmware.sh");
    for (int i = 0; i < 500 && !std::filesystem::exists(seen); ++i) ::usleep(10000);
    const std::string shared = AllowedCores(ReadTextFile("/proc/thread-self/status"));
    // one core, no list or range, and the firmware's is the same one
    EXPECT_EQ(shared.find_first_of(",-"), std::string::npos) << shared;
    EXPECT_EQ(AllowedCores(ReadTextFile(seen)), shared);
  }
  EXPECT_EQ(AllowedCores(ReadTextFile("/proc/thread-self/status")), before);
}

TEST(LinkTransportsTest, TheProtocolDocumentListsEveryTransportInTheTablesWords) {
  const std::string doc = ReadTextFile(UNIMOUSE_SOURCE_DIR "/docs/protocol.md");
  for (const link::TransportKind& kind : link::Transports()) {
    const std::string row = std::string("| ") + kind.usage + " | " + kind.summary + " |";
    EXPECT_NE(doc.find(row), std::string::npos) << "docs/protocol.md lacks the row\n" << row;
  }
}

class CheckOpensNothingTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::FreshDirectory("check_link"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // a robot file in the test's directory whose link uses `transport`
  std::string RobotFile(const std::string& transport) {
    const std::string path = dir_ + "/robot.yaml";
    std::ofstream(path) << testing::ReadBundledRobot()
                        << "  - { type: unimouse.link, name: link, params: { transport: '"
                        << transport << "', beliefs_out: beliefs.json } }\n";
    return path;
  }

  std::string dir_;
};

TEST_F(CheckOpensNothingTest, CheckingANativeLinkStartsNoProgram) {
  const std::string started = dir_ + "/started";
  const std::string robot = RobotFile("native:/bin/touch " + started);
  const testing::Outcome check = testing::Unimouse("check " + robot);
  EXPECT_EQ(check.exit_code, 2) << check.output;
  EXPECT_NE(check.output.find("robot.yaml:"), std::string::npos) << check.output;
  EXPECT_NE(check.output.find("runs a firmware: a robot file may not ask for that"),
            std::string::npos)
      << check.output;
  EXPECT_FALSE(std::filesystem::exists(started));
}

TEST_F(CheckOpensNothingTest, ARobotFileCannotStartAProgramInARunEither) {
  const std::string started = dir_ + "/started";
  const testing::Outcome run =
      testing::Unimouse("run --robot " + RobotFile("native:/bin/touch " + started) +
                        " --maze none --duration 0.01 --no-pictures --out " + dir_ + "/out");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_FALSE(std::filesystem::exists(started));
  // the same program from the command line does start: the mark is a true witness
  const testing::Outcome allowed = testing::Unimouse(
      "run --maze none --duration 0.01 --no-pictures --out " + dir_ +
      "/out --link 'native:" + UNIMOUSE_TEST_FIRMWARE + " --touch " + started + "'");
  EXPECT_EQ(allowed.exit_code, 0) << allowed.output;
  EXPECT_TRUE(std::filesystem::exists(started));
}

TEST_F(CheckOpensNothingTest, ALinkSetValueIsTakenAsWrittenNotReadAsYaml) {
  const testing::Outcome run =
      testing::Unimouse("run --maze none --duration 0.01 --no-pictures --out " + dir_ +
                        "/out --link 'native:" + UNIMOUSE_TEST_FIRMWARE +
                        "' --link-set \"beliefs_out=b: {x}'s.json\"");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(std::filesystem::exists(dir_ + "/out/b: {x}'s.json")) << run.output;
}

TEST_F(CheckOpensNothingTest, ARobotFileCannotLoadOrEmulateAFirmware) {
  for (const std::string transport : {"inproc:/tmp/x.so", "avr:/tmp/x.elf"}) {
    const testing::Outcome check = testing::Unimouse("check " + RobotFile(transport));
    EXPECT_EQ(check.exit_code, 2) << check.output;
    EXPECT_NE(check.output.find("runs a firmware"), std::string::npos) << check.output;
  }
}

TEST_F(CheckOpensNothingTest, ARobotFileMayNameAPortButNotMakeAPtyPath) {
  EXPECT_EQ(testing::Unimouse("check " + RobotFile("serial:/dev/ttyUSB0@115200")).exit_code, 0);
  const testing::Outcome check = testing::Unimouse("check " + RobotFile("pty:" + dir_ + "/board"));
  EXPECT_EQ(check.exit_code, 2) << check.output;
  EXPECT_NE(check.output.find("makes a path"), std::string::npos) << check.output;
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(dir_ + "/board")));
  // and writes nothing beside the robot file
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_)) ++files;
  EXPECT_EQ(files, 1);
}

TEST_F(CheckOpensNothingTest, APtyLinkNeverReplacesAFileThatIsNotOneOfItsLinks) {
  const std::string path = dir_ + "/notes.txt";
  std::ofstream(path) << "mine";
  EXPECT_THROW(link::OpenTransport("pty:" + path), InputError);
  std::ifstream in(path);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "mine");
  // a link to a pseudo-terminal left by an earlier run does make way
  const std::string stale = dir_ + "/board";
  std::filesystem::create_symlink("/dev/pts/999999", stale);
  auto pty = link::OpenTransport("pty:" + stale);
  EXPECT_NE(std::filesystem::read_symlink(stale).string(), "/dev/pts/999999");
}

TEST_F(CheckOpensNothingTest, ALinkNeverStartedNeitherSendsNorWrites) {
  KernelOptions options;
  options.output_dir = dir_;
  options.start_components = false;
  options.trust_robot_file = true;  // the test wrote the robot file
  auto kernel = testing::MakeKernel(testing::ReadBundledRobot() +
                                        "  - { type: unimouse.link, name: link, params: { "
                                        "transport: 'pty:" +
                                        dir_ + "/board' } }\n",
                                    nullptr, options);
  for (int i = 0; i < 5; ++i) kernel->Step();
  kernel->Finish();
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(dir_ + "/board")));
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/firmware_beliefs.json"));
}

}  // namespace
}  // namespace unimouse
