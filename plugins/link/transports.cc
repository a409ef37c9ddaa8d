// SPDX-License-Identifier: GPL-3.0-or-later
// The one list of transports. It feeds the `transport` parameter's documentation (and so
// `unimouse run --help`), the error for an unknown scheme, and docs/protocol.md. A new
// transport is a new source file defining its opener, declared and listed here.
#include <signal.h>

#include <cstring>
#include <string>

#include "transport.h"
#include "unimouse/errors.h"

namespace unimouse::link {

// each defined in its own <scheme>_transport.cc
std::unique_ptr<Transport> OpenPty(const std::string& link_path);
std::unique_ptr<Transport> OpenSerial(const std::string& rest);
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
     &OpenPty},
    {"serial", "serial:PATH@BAUD",
     "a serial port, 8N1, no flow control; reopened when it comes back after being unplugged",
     &OpenSerial},
    {"tcp", "tcp::PORT or tcp:HOST:PORT",
     "a TCP server, one client at a time (boards on Wi-Fi, remote labs)", &OpenTcp},
    {"native", "native:PROGRAM [ARGS]",
     "a firmware program the simulator starts, talking on its stdin and stdout, in lock-step "
     "from the first step; stopped with the run; its death ends the run with an error that "
     "names the signal (`the firmware crashed: SIGSEGV ...`) or exit code, its hang after "
     "`lockstep_timeout_s`",
     &OpenNative},
    {"avr", "avr:PATH.elf",
     "the image one would flash onto an Arduino Mega 2560 or Uno, run on an emulated ATmega in "
     "step with the simulation (its clock, its UART at its baud rate); the part and clock from "
     "the image's AVR_MCU section, else the link's mcu and f_cpu_hz",
     &OpenAvr},
    {"inproc", "inproc:MODULE.so",
     "a firmware built as a module (NAME.so beside each PC-built example), loaded into the "
     "simulator and run on its own stack in lock-step from the first step: a step costs little "
     "more than its physics; a crash, exit() or hang of the firmware ends the run with an error",
     &OpenInproc},
};

}  // namespace

std::span<const TransportKind> Transports() { return kTransports; }

const char* TransportUsages() {
  static const std::string usages = [] {
    std::string text;
    const size_t n = std::size(kTransports);
    for (size_t i = 0; i < n; ++i) {
      text += i == 0 ? "" : i + 1 == n ? ", or " : ", ";
      text += kTransports[i].usage;
    }
    return text;
  }();
  return usages.c_str();
}

std::unique_ptr<Transport> OpenTransport(const std::string& spec) {
  const size_t colon = spec.find(':');
  const std::string scheme = spec.substr(0, colon);
  const std::string rest = colon == std::string::npos ? "" : spec.substr(colon + 1);
  for (const TransportKind& kind : kTransports) {
    if (scheme == kind.scheme) return kind.open(rest);
  }
  throw InputError("unknown transport '" + spec + "': " + TransportUsages());
}

}  // namespace unimouse::link
