// SPDX-License-Identifier: GPL-3.0-or-later
// Lua's string patterns (the Lua 5.4 manual, section 6.4.1) with their work counted. The
// standard library matches patterns inside C, where the instruction hook never runs, and a
// pattern that backtracks ("(.-)(.-)(.-)x" on a long string) can run for hours. This matcher
// does the same matching and reports every step to a counter, which may stop it by throwing;
// the scenario sandbox's string.find, match, gmatch and gsub use it, so that their work counts
// against the instruction budget like any other.
#ifndef UNIMOUSE_SCENARIO_LUA_PATTERNS_H_
#define UNIMOUSE_SCENARIO_LUA_PATTERNS_H_

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

namespace unimouse {

/// One capture of a match: a piece of the subject, or a position capture "()".
struct PatternCapture {
  size_t start = 0;       ///< 0-based offset in the subject
  size_t length = 0;      ///< bytes; 0 for a position capture
  bool position = false;  ///< "()": the capture is start + 1, a number
};

/// A match: the subject's bytes [start, end) and its captures.
struct PatternMatch {
  size_t start = 0;
  size_t end = 0;
  std::vector<PatternCapture> captures;
};

/// Matches one pattern against one subject. Throws std::runtime_error with Lua's words for a
/// malformed pattern ("malformed pattern (missing ']')"); `charge` is called with the number of
/// steps done, every so many steps and once at the end, and may throw to stop the search.
class PatternMatcher {
 public:
  /// The most captures a pattern may have, as in Lua.
  static constexpr int kMaxCaptures = 32;

  PatternMatcher(std::string_view subject, std::string_view pattern,
                 std::function<void(int64_t steps)> charge);
  PatternMatcher(const PatternMatcher&) = delete;
  PatternMatcher& operator=(const PatternMatcher&) = delete;

  /// Finds the first match starting at or after `from` (only at `from` when `anchored`). A
  /// match that is empty and starts at `skip_empty_at` does not count (gmatch and gsub never
  /// match an empty string right where the previous match ended).
  std::optional<PatternMatch> Find(size_t from, bool anchored,
                                   size_t skip_empty_at = std::string_view::npos);

  /// Whether `pattern` has none of the characters that make it more than plain text.
  static bool IsPlain(std::string_view pattern);
  /// Finds `needle` in `subject` from `from` on, byte by byte, charging each comparison.
  static std::optional<size_t> FindPlain(std::string_view subject, std::string_view needle,
                                         size_t from, const std::function<void(int64_t)>& charge);

 private:
  struct Open {
    size_t start;
    long length;  // kUnclosed while open, kPosition for "()"
  };

  // the end of a match of pattern[p...] at subject[s...], or npos
  size_t Match(size_t s, size_t p);
  size_t MaxExpand(size_t s, size_t p, size_t ep);
  size_t MinExpand(size_t s, size_t p, size_t ep);
  size_t StartCapture(size_t s, size_t p, long what);
  size_t EndCapture(size_t s, size_t p);
  size_t MatchBalance(size_t s, size_t p);
  size_t MatchCapture(size_t s, int letter);
  // the end of the single-character class at p
  size_t ClassEnd(size_t p) const;
  bool SingleMatch(size_t s, size_t p, size_t ep) const;
  bool MatchBracketClass(unsigned char c, size_t p, size_t ec) const;
  int CaptureToClose() const;
  void Step();

  std::string_view subject_;
  std::string_view pattern_;
  std::function<void(int64_t)> charge_;
  std::vector<Open> captures_;
  int depth_ = 0;
  int64_t uncharged_ = 0;
};

}  // namespace unimouse

#endif  // UNIMOUSE_SCENARIO_LUA_PATTERNS_H_
