// SPDX-License-Identifier: GPL-3.0-or-later
// What a transport spec means, as the run, batch and mms read it: which firmware file it runs,
// whether a robot file may name it, whether its peer lives on the wall clock.
#include "transport_spec.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse::link {
namespace {

namespace fs = std::filesystem;

TEST(TransportSpecTest, AProgramsSpecNamesItsFileAndKeepsItsArguments) {
  const TransportSpec spec = ParseTransportSpec("native:fw/alice --fast --seed 3");
  EXPECT_STREQ(spec.kind->scheme, "native");
  EXPECT_EQ(spec.firmware, "fw/alice");
  EXPECT_EQ(spec.arguments, " --fast --seed 3");
  EXPECT_EQ(spec.WithFirmware("/class/fw/alice"), "native:/class/fw/alice --fast --seed 3");
}

TEST(TransportSpecTest, AModuleOrAnImageIsTheWholeRestOfTheSpec) {
  EXPECT_EQ(ParseTransportSpec("inproc:my sketch.so").firmware, "my sketch.so");
  EXPECT_EQ(ParseTransportSpec("avr:build/wall_distance.elf").firmware, "build/wall_distance.elf");
  EXPECT_EQ(ParseTransportSpec("avr:a b.elf").arguments, "");
}

TEST(TransportSpecTest, ABoardRunsNoFileHereAndKeepsTheWallClock) {
  for (const char* text :
       {"pty", "pty:/tmp/board", "serial:/dev/ttyUSB0@115200", "tcp::5760", "tcp:127.0.0.1:5760"}) {
    SCOPED_TRACE(text);
    const TransportSpec spec = ParseTransportSpec(text);
    EXPECT_EQ(spec.kind->firmware, FirmwareHost::kBoard);
    EXPECT_EQ(spec.firmware, "");
    EXPECT_TRUE(spec.kind->wall_clock);
  }
  // a program keeps its own time until it asks for lock-step; a module and the emulated board
  // live in the simulation's
  EXPECT_TRUE(ParseTransportSpec("native:./fw").kind->wall_clock);
  EXPECT_FALSE(ParseTransportSpec("inproc:fw.so").kind->wall_clock);
  EXPECT_FALSE(ParseTransportSpec("avr:fw.elf").kind->wall_clock);
}

TEST(TransportSpecTest, ARobotFileMayNameAPortOrAServerButNoProgramAndNoPath) {
  EXPECT_EQ(ParseTransportSpec("pty").RefusedInDataFile(), "");
  EXPECT_EQ(ParseTransportSpec("serial:/dev/ttyACM0@115200").RefusedInDataFile(), "");
  EXPECT_EQ(ParseTransportSpec("tcp::5760").RefusedInDataFile(), "");
  EXPECT_EQ(ParseTransportSpec("pty:/home/student/.bashrc").RefusedInDataFile(), "makes a path");
  EXPECT_EQ(ParseTransportSpec("pty:").RefusedInDataFile(), "makes a path");
  EXPECT_EQ(ParseTransportSpec("native:/usr/bin/python3 bot.py").RefusedInDataFile(),
            "runs a firmware");
  EXPECT_EQ(ParseTransportSpec("inproc:x.so").RefusedInDataFile(), "runs a firmware");
  EXPECT_EQ(ParseTransportSpec("avr:x.elf").RefusedInDataFile(), "runs a firmware");
}

TEST(TransportSpecTest, AnUnknownSchemeIsBadInputThatListsEveryTransport) {
  try {
    ParseTransportSpec("carrier-pigeon:coo");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              std::string("unknown transport 'carrier-pigeon:coo': ") + TransportUsages());
  }
  EXPECT_EQ(std::string(TransportUsages(/*boards_only=*/true)),
            "pty or pty:LINK, serial:PATH@BAUD, or tcp::PORT or tcp:HOST:PORT");
}

TEST(TransportSpecTest, ABundledFirmwaresNameBecomesItsFileAndAnythingElseStaysAsGiven) {
  const fs::path dir = fs::temp_directory_path() / "transport_spec_firmware";
  fs::create_directories(dir);
  WriteTextFile((dir / "micromouse").string(), "");
  WriteTextFile((dir / "micromouse.so").string(), "");
  WriteTextFile((dir / "micromouse.elf").string(), "");
  const std::string d = dir.string();
  EXPECT_EQ(ResolveBundledFirmware("native:micromouse --fast", d),
            "native:" + d + "/micromouse --fast");
  EXPECT_EQ(ResolveBundledFirmware("inproc:micromouse", d), "inproc:" + d + "/micromouse.so");
  EXPECT_EQ(ResolveBundledFirmware("avr:micromouse", d), "avr:" + d + "/micromouse.elf");
  // a path, a name with no bundled file, a board, an unknown scheme: as given
  EXPECT_EQ(ResolveBundledFirmware("native:./micromouse", d), "native:./micromouse");
  EXPECT_EQ(ResolveBundledFirmware("native:follower", d), "native:follower");
  EXPECT_EQ(ResolveBundledFirmware("tcp::5760", d), "tcp::5760");
  EXPECT_EQ(ResolveBundledFirmware("smoke-signals:micromouse", d), "smoke-signals:micromouse");
  EXPECT_EQ(BundledFirmwareSpec(FirmwareHost::kInProcess, d, "micromouse"),
            "inproc:" + d + "/micromouse.so");
  EXPECT_EQ(BundledFirmwareSpec(FirmwareHost::kEmulatedBoard, d, "micromouse"),
            "avr:" + d + "/micromouse.elf");
  fs::remove_all(dir);
}

TEST(TransportSpecTest, ASerialSpecNamesItsLineRateAndOtherTransportsHaveNone) {
  EXPECT_EQ(ParseTransportSpec("serial:/dev/ttyACM0@1000000").LineBaud(), 1000000);
  EXPECT_EQ(ParseTransportSpec("serial:/dev/ttyACM0").LineBaud(), 115200);
  EXPECT_EQ(ParseTransportSpec("tcp::5760").LineBaud(), 0);
  EXPECT_EQ(ParseTransportSpec("pty").LineBaud(), 0);
}

}  // namespace
}  // namespace unimouse::link
