// SPDX-License-Identifier: GPL-3.0-or-later
#include "lua_patterns.h"

#include <cctype>
#include <cstring>
#include <stdexcept>
#include <string>

namespace unimouse {

namespace {

constexpr size_t kNone = std::string_view::npos;
constexpr long kUnclosed = -1;
constexpr long kPosition = -2;
constexpr int kMaxDepth = 200;          // as Lua's matcher: deeper is "pattern too complex"
constexpr int64_t kChargeEvery = 1000;  // steps between two reports

[[noreturn]] void Fail(const std::string& message) { throw std::runtime_error(message); }

// %a, %d, ... and their complements %A, %D, ...; any other character stands for itself
bool ClassMatches(unsigned char c, unsigned char letter) {
  bool in = false;
  switch (std::tolower(letter)) {
    case 'a':
      in = std::isalpha(c) != 0;
      break;
    case 'c':
      in = std::iscntrl(c) != 0;
      break;
    case 'd':
      in = std::isdigit(c) != 0;
      break;
    case 'g':
      in = std::isgraph(c) != 0;
      break;
    case 'l':
      in = std::islower(c) != 0;
      break;
    case 'p':
      in = std::ispunct(c) != 0;
      break;
    case 's':
      in = std::isspace(c) != 0;
      break;
    case 'u':
      in = std::isupper(c) != 0;
      break;
    case 'w':
      in = std::isalnum(c) != 0;
      break;
    case 'x':
      in = std::isxdigit(c) != 0;
      break;
    default:
      return letter == c;
  }
  return std::isupper(letter) != 0 ? !in : in;
}

}  // namespace

PatternMatcher::PatternMatcher(std::string_view subject, std::string_view pattern,
                               std::function<void(int64_t steps)> charge)
    : subject_(subject), pattern_(pattern), charge_(std::move(charge)) {}

bool PatternMatcher::IsPlain(std::string_view pattern) {
  return pattern.find_first_of("^$*+?.([%-") == kNone;
}

std::optional<size_t> PatternMatcher::FindPlain(std::string_view subject, std::string_view needle,
                                                size_t from,
                                                const std::function<void(int64_t)>& charge) {
  int64_t steps = 0;
  for (size_t s = from; s <= subject.size() && needle.size() <= subject.size() - s; ++s) {
    size_t i = 0;
    while (i < needle.size() && subject[s + i] == needle[i]) ++i;
    steps += static_cast<int64_t>(i) + 1;
    if (steps >= kChargeEvery) {
      charge(steps);
      steps = 0;
    }
    if (i == needle.size()) return s;
  }
  return std::nullopt;
}

void PatternMatcher::Step() {
  if (++uncharged_ < kChargeEvery) return;
  const int64_t steps = uncharged_;
  uncharged_ = 0;
  charge_(steps);
}

std::optional<PatternMatch> PatternMatcher::Find(size_t from, bool anchored, size_t skip_empty_at) {
  for (size_t s = from; s <= subject_.size(); ++s) {
    captures_.clear();
    depth_ = 0;
    const size_t end = Match(s, 0);
    if (end != kNone && !(end == s && s == skip_empty_at)) {
      PatternMatch match{s, end, {}};
      for (const Open& c : captures_) {
        if (c.length == kUnclosed) Fail("unfinished capture");
        match.captures.push_back({c.start,
                                  c.length == kPosition ? 0 : static_cast<size_t>(c.length),
                                  c.length == kPosition});
      }
      return match;
    }
    if (anchored) break;
  }
  return std::nullopt;
}

size_t PatternMatcher::ClassEnd(size_t p) const {
  const size_t n = pattern_.size();
  const char c = pattern_[p++];
  if (c == '%') {
    if (p >= n) Fail("malformed pattern (ends with '%')");
    return p + 1;
  }
  if (c == '[') {
    if (p < n && pattern_[p] == '^') ++p;
    // the first character is in the set even when it is ']'
    do {
      if (p >= n) Fail("malformed pattern (missing ']')");
      if (pattern_[p++] == '%') {
        if (p >= n) Fail("malformed pattern (missing ']')");
        ++p;
      }
    } while (p >= n || pattern_[p] != ']');
    return p + 1;
  }
  return p;
}

bool PatternMatcher::MatchBracketClass(unsigned char c, size_t p, size_t ec) const {
  // p is at '[', ec at its ']'
  bool in = true;
  if (pattern_[++p] == '^') {
    in = false;
    ++p;
  }
  for (; p < ec; ++p) {
    const auto here = static_cast<unsigned char>(pattern_[p]);
    if (here == '%') {
      ++p;
      if (ClassMatches(c, static_cast<unsigned char>(pattern_[p]))) return in;
    } else if (p + 2 < ec && pattern_[p + 1] == '-') {
      if (here <= c && c <= static_cast<unsigned char>(pattern_[p + 2])) return in;
      p += 2;
    } else if (here == c) {
      return in;
    }
  }
  return !in;
}

bool PatternMatcher::SingleMatch(size_t s, size_t p, size_t ep) const {
  if (s >= subject_.size()) return false;
  const auto c = static_cast<unsigned char>(subject_[s]);
  switch (pattern_[p]) {
    case '.':
      return true;
    case '%':
      return ClassMatches(c, static_cast<unsigned char>(pattern_[p + 1]));
    case '[':
      return MatchBracketClass(c, p, ep - 1);
    default:
      return static_cast<unsigned char>(pattern_[p]) == c;
  }
}

size_t PatternMatcher::Match(size_t s, size_t p) {
  if (depth_ >= kMaxDepth) Fail("pattern too complex");
  ++depth_;
  struct Leave {
    int& depth;
    ~Leave() { --depth; }
  } leave{depth_};
  const size_t n = pattern_.size();
  for (;;) {
    Step();
    if (p == n) return s;
    switch (pattern_[p]) {
      case '(':
        if (p + 1 < n && pattern_[p + 1] == ')') return StartCapture(s, p + 2, kPosition);
        return StartCapture(s, p + 1, kUnclosed);
      case ')':
        return EndCapture(s, p + 1);
      case '$':
        if (p + 1 == n) return s == subject_.size() ? s : kNone;
        break;  // a '$' inside the pattern is itself
      case '%':
        if (p + 1 >= n) break;  // ClassEnd reports it
        if (pattern_[p + 1] == 'b') {
          s = MatchBalance(s, p + 2);
          if (s == kNone) return kNone;
          p += 4;
          continue;
        }
        if (pattern_[p + 1] == 'f') {
          p += 2;
          if (p >= n || pattern_[p] != '[') Fail("missing '[' after '%f' in pattern");
          const size_t ep = ClassEnd(p);
          const auto before = static_cast<unsigned char>(s == 0 ? '\0' : subject_[s - 1]);
          const auto at = static_cast<unsigned char>(s < subject_.size() ? subject_[s] : '\0');
          if (MatchBracketClass(before, p, ep - 1) || !MatchBracketClass(at, p, ep - 1)) {
            return kNone;
          }
          p = ep;
          continue;
        }
        if (std::isdigit(static_cast<unsigned char>(pattern_[p + 1])) != 0) {
          s = MatchCapture(s, pattern_[p + 1]);
          if (s == kNone) return kNone;
          p += 2;
          continue;
        }
        break;
      default:
        break;
    }
    // a single-character class, maybe with a repetition after it
    const size_t ep = ClassEnd(p);
    const char suffix = ep < n ? pattern_[ep] : '\0';
    if (ep < n && suffix == '?') {
      if (SingleMatch(s, p, ep)) {
        const size_t end = Match(s + 1, ep + 1);
        if (end != kNone) return end;
      }
      p = ep + 1;
      continue;
    }
    if (ep < n && suffix == '+') return SingleMatch(s, p, ep) ? MaxExpand(s + 1, p, ep) : kNone;
    if (ep < n && suffix == '*') return MaxExpand(s, p, ep);
    if (ep < n && suffix == '-') return MinExpand(s, p, ep);
    if (!SingleMatch(s, p, ep)) return kNone;
    ++s;
    p = ep;
  }
}

size_t PatternMatcher::MaxExpand(size_t s, size_t p, size_t ep) {
  size_t count = 0;
  while (SingleMatch(s + count, p, ep)) {
    Step();
    ++count;
  }
  // the longest run first, then shorter ones
  for (size_t i = count + 1; i-- > 0;) {
    const size_t end = Match(s + i, ep + 1);
    if (end != kNone) return end;
  }
  return kNone;
}

size_t PatternMatcher::MinExpand(size_t s, size_t p, size_t ep) {
  for (;;) {
    const size_t end = Match(s, ep + 1);
    if (end != kNone) return end;
    if (!SingleMatch(s, p, ep)) return kNone;
    ++s;
  }
}

size_t PatternMatcher::StartCapture(size_t s, size_t p, long what) {
  if (captures_.size() >= kMaxCaptures) Fail("too many captures");
  captures_.push_back({s, what});
  const size_t end = Match(s, p);
  if (end == kNone) captures_.pop_back();
  return end;
}

size_t PatternMatcher::EndCapture(size_t s, size_t p) {
  const int open = CaptureToClose();
  captures_[open].length = static_cast<long>(s - captures_[open].start);
  const size_t end = Match(s, p);
  if (end == kNone) captures_[open].length = kUnclosed;
  return end;
}

int PatternMatcher::CaptureToClose() const {
  for (int i = static_cast<int>(captures_.size()) - 1; i >= 0; --i) {
    if (captures_[i].length == kUnclosed) return i;
  }
  Fail("invalid pattern capture");
}

size_t PatternMatcher::MatchBalance(size_t s, size_t p) {
  if (p + 1 >= pattern_.size()) Fail("malformed pattern (missing arguments to '%b')");
  if (s >= subject_.size() || subject_[s] != pattern_[p]) return kNone;
  const char open = pattern_[p], close = pattern_[p + 1];
  int depth = 1;
  for (size_t i = s + 1; i < subject_.size(); ++i) {
    Step();
    if (subject_[i] == close) {
      if (--depth == 0) return i + 1;
    } else if (subject_[i] == open) {
      ++depth;
    }
  }
  return kNone;
}

size_t PatternMatcher::MatchCapture(size_t s, int letter) {
  const int index = letter - '1';
  if (index < 0 || index >= static_cast<int>(captures_.size()) ||
      captures_[index].length == kUnclosed) {
    Fail("invalid capture index %" + std::to_string(index + 1));
  }
  if (captures_[index].length == kPosition) return kNone;
  const auto length = static_cast<size_t>(captures_[index].length);
  uncharged_ += static_cast<int64_t>(length);
  if (subject_.size() - s >= length &&
      subject_.compare(s, length, subject_.substr(captures_[index].start, length)) == 0) {
    return s + length;
  }
  return kNone;
}

}  // namespace unimouse
