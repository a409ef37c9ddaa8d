// SPDX-License-Identifier: GPL-3.0-or-later
// The one list of transports and the grammar of their specs. The list feeds the `transport`
// parameter's documentation (and so `unimouse run --help`), the error for an unknown scheme,
// and docs/protocol.md. A new transport is a new source file defining its opener, declared and
// listed here.
#include <signal.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "transport.h"
#include "transport_spec.h"
#include "unimouse/errors.h"

namespace unimouse::link {

// each defined in its own <scheme>_transport.cc
std::unique_ptr<Transport> OpenPty(const std::string& link_path);
std::unique_ptr<Transport> OpenSerial(const std::string& rest);
int SerialLineBaud(const std::string& rest);
std::unique_ptr<Transport> OpenTcp(const std::string& rest);
std::unique_ptr<Transport> OpenNative(const std::string& command);
std::unique_ptr<Transport> OpenAvr(const std::string& path);
std::unique_ptr<Transport> OpenInproc(const std::string& path);

std::string FirmwareSignalText(int sig) {
  switch (sig) {
    case SIGSEGV:
      return "SIGSEGV (a bad pointer or array index?)";
    case SIGFPE:
      return "SIGFPE (division by zero?)";
    case SIGILL:
      return "SIGILL (an illegal instruction: a function that returns no value?)";
    case SIGABRT:
      return "SIGABRT (abort(), a failed assert or an uncaught exception)";
    default:
      const char* name = sigabbrev_np(sig);
      return name ? "SIG" + std::string(name) : "signal " + std::to_string(sig);
  }
}

namespace {

constexpr TransportKind kTransports[] = {
    {"pty", "pty or pty:LINK",
     "a pseudo-terminal for a board emulator or terminal program; the console prints its path, "
     "and LINK becomes a symlink to it",
     FirmwareHost::kBoard, nullptr, /*wall_clock=*/true, /*argument_makes_path=*/true, &OpenPty},
    {"serial", "serial:PATH@BAUD",
     "a serial port, 8N1, no flow control; reopened when it comes back after being unplugged",
     FirmwareHost::kBoard, nullptr, true, false, &OpenSerial},
    {"tcp", "tcp::PORT or tcp:HOST:PORT",
     "a TCP server, one client at a time (boards on Wi-Fi, remote labs)", FirmwareHost::kBoard,
     nullptr, true, false, &OpenTcp},
    {"native", "native:PROGRAM [ARGS]",
     "a firmware program the simulator starts, talking on its stdin and stdout, in lock-step "
     "from the first step; stopped with the run; its death ends the run with an error that "
     "names the signal (`the firmware crashed: SIGSEGV ...`) or exit code, its hang after "
     "`lockstep_timeout_s`",
     FirmwareHost::kProcess, "", true, false, &OpenNative},
    {"avr", "avr:PATH.elf",
     "the image one would flash onto an Arduino Mega 2560 or Uno, run on an emulated ATmega in "
     "step with the simulation (its clock, its UART at its baud rate); the part and clock from "
     "the image's AVR_MCU section, else the link's mcu and f_cpu_hz",
     FirmwareHost::kEmulatedBoard, ".elf", false, false, &OpenAvr},
    {"inproc", "inproc:MODULE.so",
     "a firmware built as a module (NAME.so beside each PC-built example), loaded into the "
     "simulator and run on its own stack in lock-step from the first step: a step costs little "
     "more than its physics; a crash, exit() or hang of the firmware ends the run with an error",
     FirmwareHost::kInProcess, ".so", false, false, &OpenInproc},
};

std::string Usages(bool boards_only) {
  std::vector<const char*> usages;
  for (const TransportKind& kind : kTransports) {
    if (!boards_only || kind.firmware == FirmwareHost::kBoard) usages.push_back(kind.usage);
  }
  std::string text;
  for (size_t i = 0; i < usages.size(); ++i) {
    text += i == 0 ? "" : i + 1 == usages.size() ? ", or " : ", ";
    text += usages[i];
  }
  return text;
}

}  // namespace

std::span<const TransportKind> Transports() { return kTransports; }

const char* TransportUsages(bool boards_only) {
  static const std::string all = Usages(false), boards = Usages(true);
  return boards_only ? boards.c_str() : all.c_str();
}

TransportSpec ParseTransportSpec(const std::string& text) {
  TransportSpec spec;
  spec.text = text;
  const size_t colon = text.find(':');
  const std::string scheme = text.substr(0, colon);
  spec.rest = colon == std::string::npos ? "" : text.substr(colon + 1);
  for (const TransportKind& kind : kTransports) {
    if (scheme == kind.scheme) spec.kind = &kind;
  }
  if (spec.kind == nullptr) {
    throw InputError("unknown transport '" + text.substr(0, 200) + "': " + TransportUsages());
  }
  switch (spec.kind->firmware) {
    case FirmwareHost::kBoard:
      break;
    case FirmwareHost::kProcess: {
      // a program's arguments follow its name, as words
      const size_t space = std::min(spec.rest.find(' '), spec.rest.size());
      spec.firmware = spec.rest.substr(0, space);
      spec.arguments = spec.rest.substr(space);
      break;
    }
    case FirmwareHost::kInProcess:
    case FirmwareHost::kEmulatedBoard:
      spec.firmware = spec.rest;
      break;
  }
  return spec;
}

std::string TransportSpec::RefusedInDataFile() const {
  if (kind->firmware != FirmwareHost::kBoard) return "runs a firmware";
  if (kind->argument_makes_path && text != kind->scheme) return "makes a path";
  return "";
}

std::string TransportSpec::WithFirmware(const std::string& file) const {
  return std::string(kind->scheme) + ":" + file + arguments;
}

int TransportSpec::LineBaud() const { return kind->open == &OpenSerial ? SerialLineBaud(rest) : 0; }

namespace {

const TransportKind& KindRunning(FirmwareHost host) {
  const TransportKind* found = nullptr;
  for (const TransportKind& kind : kTransports) {
    if (kind.firmware == host && kind.bundled_suffix != nullptr) found = &kind;
  }
  UNIMOUSE_DEMAND(found != nullptr);
  return *found;
}

}  // namespace

std::string FirmwareSpec(FirmwareHost host, const std::string& file) {
  return std::string(KindRunning(host).scheme) + ":" + file;
}

std::string BundledFirmwareSpec(FirmwareHost host, const std::string& firmware_dir,
                                const std::string& name) {
  return FirmwareSpec(
      host,
      (std::filesystem::path(firmware_dir) / (name + KindRunning(host).bundled_suffix)).string());
}

std::string ResolveBundledFirmware(const std::string& text, const std::string& firmware_dir) {
  namespace fs = std::filesystem;
  TransportSpec spec;
  try {
    spec = ParseTransportSpec(text);
  } catch (const InputError&) {
    // opening it says what is wrong
    return text;
  }
  const std::string& name = spec.firmware;
  std::error_code error;  // a name the system cannot look up is no file, not an exception
  if (spec.kind->bundled_suffix == nullptr || name.find('/') != std::string::npos ||
      fs::is_regular_file(name, error)) {
    return text;
  }
  const fs::path bundled = fs::path(firmware_dir) / (name + spec.kind->bundled_suffix);
  return fs::is_regular_file(bundled, error) ? spec.WithFirmware(bundled.string()) : text;
}

std::unique_ptr<Transport> OpenTransport(const std::string& text) {
  const TransportSpec spec = ParseTransportSpec(text);
  return spec.kind->open(spec.rest);
}

std::string SpiImuPartProblem(const std::string& part) {
  if (part == "mpu6500" || part == "icm20602") return "";
  return "unknown SPI IMU '" + part.substr(0, 40) + "'; the bus carries mpu6500 or icm20602";
}

std::string PinProblem(const std::string& mcu, const std::string& pin) {
  const bool form = pin.size() == 3 && pin[0] == 'P' && pin[1] >= 'A' && pin[1] <= 'L' &&
                    pin[2] >= '0' && pin[2] <= '7';
  if (!form) return "'" + pin.substr(0, 20) + "' is not a pin: write its port and bit, e.g. PB0";
  const char port = pin[1];
  const int bit = pin[2] - '0';
  bool exists = true;
  if (mcu == "atmega328p") {
    exists = (port == 'B' || port == 'D') || (port == 'C' && bit <= 6);
  } else if (mcu == "atmega2560") {
    exists = port != 'I' && (port != 'G' || bit <= 5);
  }
  return exists ? "" : mcu + " has no pin " + pin;
}

}  // namespace unimouse::link
