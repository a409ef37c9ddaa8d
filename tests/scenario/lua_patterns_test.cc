// SPDX-License-Identifier: GPL-3.0-or-later
// Lua's patterns matched with their work counted: the matches the Lua 5.4 manual describes,
// worked out by hand, Lua's own words for malformed patterns, and a search that backtracks
// without end stopped by its counter.
#include "lua_patterns.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace unimouse {
namespace {

// the whole match and its captures as text ("()" captures as their 1-based position), or
// "none"
std::vector<std::string> Find(const std::string& subject, const std::string& pattern,
                              size_t from = 0) {
  const bool anchored = !pattern.empty() && pattern[0] == '^';
  const std::string body = anchored ? pattern.substr(1) : pattern;  // the matcher keeps a view
  PatternMatcher matcher(subject, body, [](int64_t) {});
  const auto m = matcher.Find(from, anchored);
  if (!m) return {"none"};
  std::vector<std::string> out = {subject.substr(m->start, m->end - m->start)};
  for (const PatternCapture& c : m->captures) {
    out.push_back(c.position ? std::to_string(c.start + 1) : subject.substr(c.start, c.length));
  }
  return out;
}

using Texts = std::vector<std::string>;

TEST(PatternMatcherTest, ClassesSetsAndRepetitionsMatchAsTheManualSays) {
  EXPECT_EQ(Find("hello world", "o w"), Texts{"o w"});
  EXPECT_EQ(Find("hello", "l+"), Texts{"ll"});
  EXPECT_EQ(Find("hello", "l*"), Texts{""});  // empty, at the first position
  EXPECT_EQ(Find("<a><b>", "<.->"), Texts{"<a>"});
  EXPECT_EQ(Find("<a><b>", "<.*>"), Texts{"<a><b>"});
  EXPECT_EQ(Find("color colour", "colou?r", 1), Texts{"colour"});
  EXPECT_EQ(Find("x = 42;", "%d+"), Texts{"42"});
  EXPECT_EQ(Find("x = 42;", "%D+"), Texts{"x = "});
  EXPECT_EQ(Find("a1_b2", "[%a_]+"), Texts{"a"});
  EXPECT_EQ(Find("2026-11-23", "[0-9]+%-[0-9]+"), Texts{"2026-11"});
  EXPECT_EQ(Find("abc]d", "[]a-c]+"), Texts{"abc]"});
  EXPECT_EQ(Find("abc", "[^a]"), Texts{"b"});
  EXPECT_EQ(Find("a.b", "%."), Texts{"."});
  EXPECT_EQ(Find("ab$", "b$"), Texts{"none"});
  EXPECT_EQ(Find("ab$", "b%$$"), Texts{"b$"});
  EXPECT_EQ(Find("xab", "^ab"), Texts{"none"});
}

TEST(PatternMatcherTest, CapturesBalancesFrontiersAndBackReferences) {
  EXPECT_EQ(Find("key = value", "(%w+)%s*=%s*(%w+)"), (Texts{"key = value", "key", "value"}));
  EXPECT_EQ(Find("hello", "()ll()"), (Texts{"ll", "3", "5"}));
  EXPECT_EQ(Find("f(a(b)c)d", "%b()"), Texts{"(a(b)c)"});
  EXPECT_EQ(Find("THE (quick) fox", "%f[%a]%a+", 4), Texts{"quick"});
  EXPECT_EQ(Find("say 'hi' \"x\"", "([\"'])(.-)%1"), (Texts{"'hi'", "'", "hi"}));
  EXPECT_EQ(Find("  trim me  ", "^%s*(.-)%s*$"), (Texts{"  trim me  ", "trim me"}));
}

TEST(PatternMatcherTest, MalformedPatternsAreRefusedInLuasWords) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[a", "malformed pattern (missing ']')"},
      {"a%", "malformed pattern (ends with '%')"},
      {"%b(", "malformed pattern (missing arguments to '%b')"},
      {"%fa", "missing '[' after '%f' in pattern"},
      {"(a", "unfinished capture"},
      {"a)", "invalid pattern capture"},
      {"(a)%2", "invalid capture index %2"},
  };
  for (const auto& [pattern, message] : cases) {
    PatternMatcher matcher("aaa", pattern, [](int64_t) {});
    try {
      matcher.Find(0, false);
      ADD_FAILURE() << pattern << ": no error";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(e.what(), message) << pattern;
    }
  }
}

TEST(PatternMatcherTest, EveryStepIsChargedSoABacktrackingSearchCanBeStopped) {
  // each start position tries every split of the a's between five lazy items: far too many
  // steps to finish, so the counter stops it after a million
  const std::string subject(100'000, 'a');
  int64_t charged = 0;
  PatternMatcher matcher(subject, ".-.-.-.-.-b", [&](int64_t steps) {
    charged += steps;
    if (charged > 1'000'000) throw std::runtime_error("budget spent");
  });
  EXPECT_THROW(matcher.Find(0, false), std::runtime_error);
  EXPECT_GT(charged, 1'000'000);
  EXPECT_LT(charged, 1'002'000);
}

TEST(PatternMatcherTest, PlainSearchesAreChargedByTheComparisonsTheyMake) {
  int64_t charged = 0;
  const auto charge = [&](int64_t steps) { charged += steps; };
  EXPECT_EQ(PatternMatcher::FindPlain("a.b.c", ".c", 0, charge), 3u);
  EXPECT_EQ(PatternMatcher::FindPlain("abc", "d", 0, charge), std::nullopt);
  EXPECT_EQ(PatternMatcher::FindPlain("abc", "", 3, charge), 3u);
  // 2000 'a's and a needle of 1000 'a's then 'b': every position compares about 1000 bytes
  const std::string subject(2000, 'a');
  const std::string needle = std::string(1000, 'a') + "b";
  charged = 0;
  EXPECT_EQ(PatternMatcher::FindPlain(subject, needle, 0, charge), std::nullopt);
  EXPECT_GT(charged, 900'000);
  EXPECT_TRUE(PatternMatcher::IsPlain("a b, c"));
  EXPECT_FALSE(PatternMatcher::IsPlain("a.b"));
}

}  // namespace
}  // namespace unimouse
