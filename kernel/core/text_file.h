// SPDX-License-Identifier: GPL-3.0-or-later
#ifndef UNIMOUSE_CORE_TEXT_FILE_H_
#define UNIMOUSE_CORE_TEXT_FILE_H_

#include <string>

namespace unimouse {

/// Returns the whole content of a file; throws InputError "path: reason" when it cannot be read.
std::string ReadTextFile(const std::string& path);

/// Writes a file whole, through a temporary name so that readers never see half of it.
void WriteTextFile(const std::string& path, const std::string& content);

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_TEXT_FILE_H_
