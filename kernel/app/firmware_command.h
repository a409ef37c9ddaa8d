// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse firmware build`: a student's sketch built against the Arduino library, for the PC
// (a program and an in-process module) or for the emulated Mega 2560, through the CMake functions
// of find_package(UnimouseFirmware) that build the bundled examples.
#ifndef UNIMOUSE_APP_FIRMWARE_COMMAND_H_
#define UNIMOUSE_APP_FIRMWARE_COMMAND_H_

#include <string>

namespace unimouse {

class CommandLine;

struct FirmwareBuildOptions {
  std::string sketch;   ///< a sketch folder (NAME/NAME.ino) or a .ino, .cc or .cpp file
  std::string out_dir;  ///< where the built files go, "" beside the sketch; the build tree under it
  std::string board = "pc";  ///< pc, or mega2560 for the emulated board
  std::string name;          ///< of the built files; "" for the sketch's name
};

/// Builds the sketch, printing the build's own output and then how to run the result. Throws
/// InputError when the sketch or the tools are missing or the sketch does not build.
int FirmwareBuild(const FirmwareBuildOptions& options);

/// Adds `unimouse firmware build`.
void AddFirmwareCommands(CommandLine& cli);

}  // namespace unimouse

#endif  // UNIMOUSE_APP_FIRMWARE_COMMAND_H_
