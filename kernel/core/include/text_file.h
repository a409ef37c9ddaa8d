// SPDX-License-Identifier: GPL-3.0-or-later
#ifndef UNIMOUSE_CORE_TEXT_FILE_H_
#define UNIMOUSE_CORE_TEXT_FILE_H_

#include <string>
#include <string_view>

namespace unimouse {

/// Largest input file unimouse reads (a robot, scenario, controller or maze): 16 MiB, far above
/// the largest maze (about 1 MB) and any hand-written file.
inline constexpr size_t kMaxInputFile_bytes = 16 << 20;

/// Whether a path names a regular file, a directory, or anything at all. A name the system cannot
/// look up (longer than PATH_MAX, a component longer than NAME_MAX, no permission) is none of
/// them: these never throw, because the names come from users' files.
bool IsRegularFile(const std::string& path) noexcept;
bool IsDirectory(const std::string& path) noexcept;
bool PathExists(const std::string& path) noexcept;

/// Returns the whole content of a file; throws InputError "path: reason" when it cannot be read
/// or is larger than kMaxInputFile_bytes.
std::string ReadTextFile(const std::string& path);

/// Writes a file whole, through a temporary name so that readers never see half of it.
void WriteTextFile(const std::string& path, const std::string& content);

/// Returns text safe between XML or HTML tags and inside a quoted attribute value: & < > " '
/// escaped, and control characters other than tab and newline (which XML 1.0 does not allow)
/// replaced by spaces. For names from robot files, job reasons from firmware, any text.
std::string XmlEscaped(std::string_view text);

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_TEXT_FILE_H_
