// SPDX-License-Identifier: GPL-3.0-or-later
// Where the program finds its plugins and data. The build tree mirrors the installed layout
// (bin/, lib/.../unimouse/plugins, share/unimouse), so both are found relative to the running
// executable and the same binary works from either.
#ifndef UNIMOUSE_CORE_INSTALL_PATHS_H_
#define UNIMOUSE_CORE_INSTALL_PATHS_H_

#include <string>

namespace unimouse {

/// Returns the directory of bundled plugin libraries.
std::string PluginDirectory();
/// Returns the directory of bundled data (robots/, mazes/, scenarios/).
std::string DataDirectory();
/// Returns the directory of the library's examples built for the PC (firmware programs).
std::string FirmwareDirectory();
/// Returns the directory of find_package(UnimouseFirmware): the CMake functions that build a
/// sketch against the Arduino library.
std::string FirmwareCMakeDirectory();

/// Returns `name` if it is an existing file; otherwise the bundled file
/// DataDirectory()/folder/name[extension]. Throws InputError naming both places when neither
/// exists.
std::string ResolveDataFile(const std::string& name, const std::string& folder,
                            const std::string& extension);

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_INSTALL_PATHS_H_
