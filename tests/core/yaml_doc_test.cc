// SPDX-License-Identifier: GPL-3.0-or-later
// YAML documents become plain trees with their places; a document whose aliases would expand
// beyond the node limit is refused quickly instead of being expanded.
#include "yaml_doc.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "unimouse/errors.h"

namespace unimouse {
namespace {

TEST(YamlDocTest, AliasesThatWouldExpandToABillionNodesAreRefusedFast) {
  // each line names the previous one ten times: 10^9 leaves at the last line
  std::string text = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i <= 8; ++i) {
    const std::string prev = "*a" + std::to_string(i - 1);
    text += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [";
    for (int k = 0; k < 10; ++k) text += (k ? ", " : "") + prev;
    text += "]\n";
  }
  const auto start = std::chrono::steady_clock::now();
  try {
    ParseYaml(text, "bomb.yaml");
    FAIL() << "expanded";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("bomb.yaml:", 0), 0u) << what;
    EXPECT_NE(what.find("more than 100000 values once aliases are expanded"), std::string::npos)
        << what;
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

TEST(YamlDocTest, AliasesWithinTheLimitAreExpanded) {
  const YamlNode root = ParseYaml("a: &w [1, 2]\nb: *w\n", "small.yaml");
  ASSERT_EQ(root.entries.size(), 2u);
  ASSERT_EQ(root.entries[1].second.items.size(), 2u);
  EXPECT_EQ(root.entries[1].second.items[1].scalar, "2");
}

// the message of the InputError that parsing `text` throws, or ""
std::string ErrorOf(const std::string& text, const std::string& file) {
  try {
    ParseYaml(text, file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(YamlDocTest, AListThatHoldsAnAliasOfItselfIsRefusedAtTheList) {
  EXPECT_EQ(ErrorOf("a: &b [*b]\n", "cycle.yaml"),
            "cycle.yaml:1:4: this list or map holds an alias of itself (a cycle); a value cannot "
            "contain itself");
}

TEST(YamlDocTest, ACycleThroughAMapAndAListFurtherDownIsRefusedAtItsAnchor) {
  EXPECT_EQ(ErrorOf("robot:\n  parts: &p\n    left: [1, {more: *p}]\n", "deep_cycle.yaml"),
            "deep_cycle.yaml:2:10: this list or map holds an alias of itself (a cycle); a value "
            "cannot contain itself");
}

TEST(YamlDocTest, AMapKeyThatIsAnAliasOfItsOwnMapIsRefused) {
  EXPECT_EQ(ErrorOf("a: &m {x: 1, ? *m : 2}\n", "key.yaml")
                .rfind("key.yaml:1:4: this list or "
                       "map holds an alias of itself",
                       0),
            0u);
}

TEST(YamlDocTest, AnAliasUsedTwiceSideBySideIsNoCycle) {
  const YamlNode root = ParseYaml("a: &w [1]\nb: [*w, *w, [*w]]\n", "twice.yaml");
  ASSERT_EQ(root.entries[1].second.items.size(), 3u);
  EXPECT_EQ(root.entries[1].second.items[2].items[0].items[0].scalar, "1");
}

// `lists` lists, one inside the other, around one number: the number is value `lists` + 1 deep
std::string NestedLists(size_t lists) {
  return std::string(lists, '[') + "7" + std::string(lists, ']') + "\n";
}

TEST(YamlDocTest, ValuesNestedToTheBoundAreReadAndOneLevelMoreIsRefused) {
  ASSERT_EQ(kMaxYamlDepth, 64u);
  const YamlNode root = ParseYaml(NestedLists(63), "deep.yaml");
  const YamlNode* node = &root;
  for (int level = 1; level < 64; ++level) {
    ASSERT_EQ(node->items.size(), 1u) << level;
    node = &node->items[0];
  }
  EXPECT_EQ(node->scalar, "7");
  // the number, 65th value down, stands in column 65
  EXPECT_EQ(ErrorOf(NestedLists(64), "deeper.yaml"),
            "deeper.yaml:1:65: values nested more than 64 levels deep; no robot file or manifest "
            "nests that deep (docs/limits.md)");
}

TEST(YamlDocTest, NestingFarBeyondTheBoundIsRefusedWithoutRunningOutOfStack) {
  // beyond about 2000 lists the YAML parser meets its own bound before the conversion runs
  for (const size_t lists : {1000, 1990, 5000, 100000}) {
    const std::string what = ErrorOf(NestedLists(lists), "abyss.yaml");
    EXPECT_EQ(what.rfind("abyss.yaml:", 0), 0u) << lists << ": " << what;
    EXPECT_NE(what.find(": values nested more than 64 levels deep"), std::string::npos)
        << lists << ": " << what;
  }
}

TEST(YamlDocTest, AMapOfManyKeysIsReadInTimeAndADuplicateNamed) {
  std::string text;
  for (int i = 0; i < 40000; ++i) text += "k" + std::to_string(i) + ": 1\n";
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(ParseYaml(text, "wide.yaml").entries.size(), 40000u);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
  try {
    ParseYaml(text + "k7: 2\n", "wide.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "wide.yaml:40001:1: duplicate key 'k7' (first given at line 8)");
  }
}

TEST(YamlDocTest, AHugeValueIsCutInTheMessageThatEchoesIt) {
  const YamlNode root = ParseYaml("mass_kg: " + std::string(100000, '9') + "x\n", "huge.yaml");
  try {
    root.entries[0].second.AsNumber("mass_kg");
    FAIL();
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("huge.yaml:1:10: mass_kg must be a number, not '999", 0), 0u);
    EXPECT_EQ(what.size(), kMaxErrorMessage_bytes + std::string("... (100049 bytes in all)").size())
        << what.substr(kMaxErrorMessage_bytes);
  }
}

}  // namespace
}  // namespace unimouse
