// SPDX-License-Identifier: GPL-3.0-or-later
// Two kinds of failure: bad input from a user (a clean one-line message and a defined exit code)
// and a broken invariant of our own (abort with file:line).
#ifndef UNIMOUSE_ERRORS_H_
#define UNIMOUSE_ERRORS_H_

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace unimouse {

/// Exit codes of `unimouse run` and the other commands.
enum ExitCode : int {
  kExitPassed = 0,
  kExitFailed = 1,        ///< the challenge was failed
  kExitBadInput = 2,      ///< bad file, option or parameter
  kExitRuntimeFault = 3,  ///< a script, plugin or firmware error during the run
};

/// Longest error message kept: a huge input echoed in one is cut.
inline constexpr size_t kMaxErrorMessage_bytes = 2000;

/// Returns `text`, or its first `max_bytes` followed by "... (N bytes in all)".
inline std::string Shortened(const std::string& text, size_t max_bytes) {
  if (text.size() <= max_bytes) return text;
  return text.substr(0, max_bytes) + "... (" + std::to_string(text.size()) + " bytes in all)";
}

/// Bad user input: a file, an option or a parameter. The message is one line, starting with
/// `file:line:col:` when there is a location, and at most kMaxErrorMessage_bytes long.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message)
      : std::runtime_error(Shortened(message, kMaxErrorMessage_bytes)) {}
  explicit InputError(const char* message) : InputError(std::string(message)) {}
};

/// A fault during a run: a plugin, script or firmware failed. The message is one line, at most
/// kMaxErrorMessage_bytes long.
class RuntimeFault : public std::runtime_error {
 public:
  explicit RuntimeFault(const std::string& message)
      : std::runtime_error(Shortened(message, kMaxErrorMessage_bytes)) {}
  explicit RuntimeFault(const char* message) : RuntimeFault(std::string(message)) {}
};

[[noreturn]] inline void AbortBrokenInvariant(const char* cond, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: internal error: '%s' does not hold; please report this\n", file,
               line, cond);
  std::abort();
}

}  // namespace unimouse

/// Throws InputError(message) unless cond holds.
#define UNIMOUSE_THROW_UNLESS(cond, message) \
  do {                                       \
    if (!(cond)) {                           \
      throw ::unimouse::InputError(message); \
    }                                        \
  } while (0)

/// Aborts with file:line unless cond holds; for our own invariants, never for user input.
#define UNIMOUSE_DEMAND(cond)                                      \
  do {                                                             \
    if (!(cond)) {                                                 \
      ::unimouse::AbortBrokenInvariant(#cond, __FILE__, __LINE__); \
    }                                                              \
  } while (0)

#endif  // UNIMOUSE_ERRORS_H_
