// SPDX-License-Identifier: GPL-3.0-or-later
// The grammar of a transport spec ("tcp::5760", "native:./fw --fast", "avr:wall_distance") and
// what each kind of transport is, as the host needs to know it before anything opens: whether
// it runs a firmware and where that firmware's file is in the spec, whether its peer lives on
// the wall clock. One table holds it (transports.cc); nothing outside this library spells a
// scheme.
#ifndef UNIMOUSE_TRANSPORT_TRANSPORT_SPEC_H_
#define UNIMOUSE_TRANSPORT_TRANSPORT_SPEC_H_

#include <memory>
#include <span>
#include <string>

namespace unimouse::link {

class Transport;

/// Where a transport's firmware is: on a board elsewhere, or a file this machine runs.
enum class FirmwareHost {
  kBoard,          ///< a board or program at the other end of a port: no file here
  kProcess,        ///< a program the simulator starts: the spec's first word, then its arguments
  kInProcess,      ///< a module loaded into the simulator: the whole rest of the spec
  kEmulatedBoard,  ///< an image run on an emulated MCU: the whole rest of the spec
};

/// One kind of transport, an entry of the transport table.
struct TransportKind {
  const char* scheme;   ///< what its spec starts with: "tcp"
  const char* usage;    ///< how a spec is written: "tcp::PORT or tcp:HOST:PORT"
  const char* summary;  ///< what it is, in a sentence for the docs
  FirmwareHost firmware;
  /// the suffix of a bundled firmware's file (NAME + suffix in the firmware directory)
  const char* bundled_suffix;
  /// its peer keeps its own time in real time (a board, a program): a run paces to the wall
  /// clock unless the firmware asks for lock-step
  bool wall_clock;
  /// an argument after the scheme makes a path on this machine (pty:LINK)
  bool argument_makes_path;
  /// opens it from what follows "scheme:" ("" for the bare scheme); throws InputError
  std::unique_ptr<Transport> (*open)(const std::string& rest);
};

/// The transport a link has when none is named: a pseudo-terminal for whatever opens it.
inline constexpr const char* kDefaultTransportSpec = "pty";

/// Returns every transport, in the order the help lists them.
std::span<const TransportKind> Transports();

/// Returns the usages of every transport ("pty or pty:LINK, serial:PATH@BAUD, ..."), or of the
/// boards only; lives for the program.
const char* TransportUsages(bool boards_only = false);

/// A spec, parsed.
struct TransportSpec {
  const TransportKind* kind = nullptr;
  std::string text;       ///< as given
  std::string rest;       ///< what follows "scheme:"
  std::string firmware;   ///< the firmware file it runs, "" for a board elsewhere
  std::string arguments;  ///< a program's arguments, with their leading space

  /// Returns "" when a data file (a robot file) may name this transport, else why not: it runs
  /// a firmware or makes a path, which only the person running the simulator chooses.
  std::string RefusedInDataFile() const;
  /// Returns the spec with its firmware file replaced by `file`.
  std::string WithFirmware(const std::string& file) const;
  /// Returns the rate in baud of the line the spec names (a serial port's, given or its
  /// default), or 0 for a transport without a line rate of its own. Throws InputError for a
  /// rate that is not one.
  int LineBaud() const;
};

/// Parses a spec, "SCHEME" or "SCHEME:REST"; throws InputError for an unknown scheme. A
/// firmware transport without its file parses (its `firmware` is ""): opening it says so.
TransportSpec ParseTransportSpec(const std::string& spec);

/// Returns the spec that runs the firmware `file` on `host` (not kBoard): "native:FILE".
std::string FirmwareSpec(FirmwareHost host, const std::string& file);

/// Returns the spec that runs the bundled firmware `name` (e.g. "micromouse") from
/// `firmware_dir` on `host`.
std::string BundledFirmwareSpec(FirmwareHost host, const std::string& firmware_dir,
                                const std::string& name);

/// Returns `spec` with a bundled firmware's name replaced by its file in `firmware_dir`
/// ("native:micromouse" -> "native:DIR/micromouse"); any other spec as given. A name is bundled
/// when it has no '/', is not a file in the working directory and its file exists there.
std::string ResolveBundledFirmware(const std::string& spec, const std::string& firmware_dir);

}  // namespace unimouse::link

#endif  // UNIMOUSE_TRANSPORT_TRANSPORT_SPEC_H_
