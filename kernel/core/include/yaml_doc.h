// SPDX-License-Identifier: GPL-3.0-or-later
// YAML documents as plain trees that remember where every node came from, so that every input
// error can say file:line:col. The only place that sees the YAML library.
#ifndef UNIMOUSE_CORE_YAML_DOC_H_
#define UNIMOUSE_CORE_YAML_DOC_H_

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace unimouse {

/// A place in an input file; line and column count from 1. Line 0: a command-line option,
/// named by `file` ("--link-set failsafe_s=0").
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;

  /// Returns "file:line:col", or just `file` for a command-line option.
  std::string ToString() const;
};

struct YamlEntry;

/// One node of a YAML document.
class YamlNode {
 public:
  enum class Kind { kNull, kScalar, kSequence, kMap };

  Kind kind = Kind::kNull;
  std::string scalar;
  std::vector<YamlNode> items;     ///< sequence items
  std::vector<YamlEntry> entries;  ///< map keys and values, in file order
  SourceLocation location;

  /// Throws InputError "file:line:col: reason".
  [[noreturn]] void Fail(const std::string& reason) const;

  /// Returns the scalar as a finite number, or fails naming what it should be.
  double AsNumber(std::string_view what) const;
  /// Returns the scalar as a whole number.
  int AsInteger(std::string_view what) const;
  /// Returns true/false.
  bool AsBool(std::string_view what) const;
  /// Returns the scalar text.
  const std::string& AsString(std::string_view what) const;
  /// Returns exactly N numbers from a sequence.
  template <size_t N>
  std::array<double, N> AsNumbers(std::string_view what) const {
    if (kind != Kind::kSequence || items.size() != N) {
      Fail(std::string(what) + " must be a list of " + std::to_string(N) + " numbers");
    }
    std::array<double, N> out{};
    for (size_t i = 0; i < N; ++i) {
      out[i] = items[i].AsNumber(what);
    }
    return out;
  }

  bool IsMap() const { return kind == Kind::kMap; }
  bool IsSequence() const { return kind == Kind::kSequence; }
};

/// Most values (scalars, lists and maps) a YAML document may hold once its aliases are
/// expanded: a robot file has a few hundred.
inline constexpr size_t kMaxYamlNodes = 100000;

/// Most levels of values a YAML document may hold, its top value being level 1 (`[[7]]` has
/// three): a robot file has 8. A document deeper, or with an alias inside its own anchor (a
/// cycle), is refused before it is converted further, so that neither the conversion nor any
/// reader after it can run out of stack.
inline constexpr size_t kMaxYamlDepth = 64;

/// A key of a map and its value, named as std::pair names them (a pair of an incomplete type
/// cannot be a member of that type for every compiler).
struct YamlEntry {
  YamlEntry(YamlNode key, YamlNode value) : first(std::move(key)), second(std::move(value)) {}
  YamlNode first;
  YamlNode second;
};

/// Parses a YAML file; a syntax error becomes an InputError with file:line:col.
YamlNode LoadYamlFile(const std::string& path);
/// Parses YAML text; `file` names it in errors.
YamlNode ParseYaml(const std::string& text, const std::string& file);

/// Reads a map strictly: keys outside the known list are refused up front, so a misspelt key is
/// reported as such rather than as a missing one.
class MapReader {
 public:
  /// Fails unless node is a map whose keys are all in `known`; `what` names it in errors
  /// ("robot", "geom").
  MapReader(const YamlNode& node, std::string what, std::vector<std::string> known);

  /// Returns the value of a key that must be present.
  const YamlNode& Required(std::string_view key) const;
  /// Returns the value of a key, or nullptr when absent.
  const YamlNode* Optional(std::string_view key) const;
  std::string String(std::string_view key, const std::string& fallback) const;
  /// Fails if `key` is present: it does not apply here, for the reason given.
  void Forbid(std::string_view key, const std::string& reason) const;

 private:
  const YamlNode& node_;
  std::string what_;
};

/// Returns the candidate closest to `word` by edit distance, or "" if none is close.
std::string NearestWord(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_YAML_DOC_H_
