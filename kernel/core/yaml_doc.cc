// SPDX-License-Identifier: GPL-3.0-or-later
#include "yaml_doc.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>

#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

SourceLocation At(const std::string& file, const YAML::Mark& mark) {
  // yaml-cpp counts from 0
  return {file, mark.line + 1, mark.column + 1};
}

// aliases let a short file name a node many times over: count what the tree would hold; an
// alias inside its own anchor makes a cycle, and a deep tree a deep recursion here and in every
// reader after us: follow at most kMaxYamlDepth levels, and name a cycle as such
struct Budget {
  const std::string& file;
  size_t nodes_left = kMaxYamlNodes;
  std::vector<YAML::Node> open;  // the nodes from the root to the one being converted
};

YamlNode Convert(const YAML::Node& in, Budget& budget);

std::string TooDeep() {
  return "values nested more than " + std::to_string(kMaxYamlDepth) +
         " levels deep; no robot file or manifest nests that deep (docs/limits.md)";
}

YamlNode ConvertChild(const YAML::Node& in, Budget& budget) {
  const std::string& file = budget.file;
  for (const YAML::Node& ancestor : budget.open) {
    if (in.is(ancestor)) {
      throw InputError(At(file, in.Mark()).ToString() +
                       ": this list or map holds an alias of itself (a cycle); a value cannot "
                       "contain itself");
    }
  }
  if (budget.open.size() >= kMaxYamlDepth) {
    throw InputError(At(file, in.Mark()).ToString() + ": " + TooDeep());
  }
  return Convert(in, budget);
}

YamlNode Convert(const YAML::Node& in, Budget& budget) {
  const std::string& file = budget.file;
  if (budget.nodes_left-- == 0) {
    throw InputError(At(file, in.Mark()).ToString() + ": more than " +
                     std::to_string(kMaxYamlNodes) +
                     " values once aliases are expanded; no robot needs that many "
                     "(docs/limits.md)");
  }
  YamlNode out;
  out.location = At(file, in.Mark());
  budget.open.push_back(in);
  switch (in.Type()) {
    case YAML::NodeType::Scalar:
      out.kind = YamlNode::Kind::kScalar;
      out.scalar = in.Scalar();
      break;
    case YAML::NodeType::Sequence:
      out.kind = YamlNode::Kind::kSequence;
      for (const auto& item : in) {
        out.items.push_back(ConvertChild(item, budget));
      }
      break;
    case YAML::NodeType::Map: {
      out.kind = YamlNode::Kind::kMap;
      // key -> its line, so that a map of many keys is checked in n log n
      std::map<std::string, int, std::less<>> lines;
      for (const auto& entry : in) {
        YamlNode key = ConvertChild(entry.first, budget);
        if (key.kind != YamlNode::Kind::kScalar) {
          key.Fail("map keys must be plain words");
        }
        if (const auto [seen, fresh] = lines.emplace(key.scalar, key.location.line); !fresh) {
          key.Fail("duplicate key '" + key.scalar + "' (first given at line " +
                   std::to_string(seen->second) + ")");
        }
        out.entries.emplace_back(std::move(key), ConvertChild(entry.second, budget));
      }
      break;
    }
    default:
      out.kind = YamlNode::Kind::kNull;
  }
  budget.open.pop_back();
  return out;
}

size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string SourceLocation::ToString() const {
  // a value from the command line has no line: its option names it
  if (line == 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

void YamlNode::Fail(const std::string& reason) const {
  throw InputError(location.ToString() + ": " + reason);
}

double YamlNode::AsNumber(std::string_view what) const {
  if (kind != Kind::kScalar) {
    Fail(std::string(what) + " must be a number");
  }
  std::string lower = scalar;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == ".inf" || lower == "+.inf" || lower == "-.inf" || lower == ".nan") {
    Fail(std::string(what) + " must be finite, not '" + scalar + "'");
  }
  double value = 0;
  const char* begin = scalar.data();
  const char* end = begin + scalar.size();
  if (!scalar.empty() && *begin == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr != end) {
    Fail(std::string(what) + " must be a number, not '" + scalar + "'");
  }
  if (!std::isfinite(value)) {
    Fail(std::string(what) + " must be finite, not '" + scalar + "'");
  }
  return value;
}

int YamlNode::AsInteger(std::string_view what) const {
  const double value = AsNumber(what);
  if (value != std::floor(value) || std::fabs(value) > 2e9) {
    Fail(std::string(what) + " must be a whole number, not '" + scalar + "'");
  }
  return static_cast<int>(value);
}

bool YamlNode::AsBool(std::string_view what) const {
  if (kind == Kind::kScalar && (scalar == "true" || scalar == "false")) {
    return scalar == "true";
  }
  Fail(std::string(what) + " must be true or false");
}

const std::string& YamlNode::AsString(std::string_view what) const {
  if (kind != Kind::kScalar) {
    Fail(std::string(what) + " must be a word or text");
  }
  return scalar;
}

YamlNode ParseYaml(const std::string& text, const std::string& file) {
  try {
    Budget budget{file, kMaxYamlNodes, {}};
    YamlNode root = Convert(YAML::Load(text), budget);
    if (root.kind == YamlNode::Kind::kNull) {
      root.location = {file, 1, 1};
    }
    return root;
  } catch (const YAML::DeepRecursion& e) {
    // the parser's own bound, far beyond ours, is met before the conversion sees the tree; its
    // message says only "bad file"
    throw InputError(At(file, e.mark).ToString() + ": " + TooDeep());
  } catch (const YAML::Exception& e) {
    throw InputError(At(file, e.mark).ToString() + ": " + e.msg);
  }
}

YamlNode LoadYamlFile(const std::string& path) { return ParseYaml(ReadTextFile(path), path); }

std::string NearestWord(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_distance = std::max<size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    // a name without its unit suffix ("torque" for "torque_nm") is the likeliest slip
    const bool missing_unit =
        c.size() > word.size() + 1 && c.compare(0, word.size(), word) == 0 && c[word.size()] == '_';
    const size_t d = missing_unit ? 1 : EditDistance(word, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

MapReader::MapReader(const YamlNode& node, std::string what, std::vector<std::string> known)
    : node_(node), what_(std::move(what)) {
  if (!node.IsMap()) {
    node.Fail(what_ + " must be a map of key: value lines");
  }
  for (const auto& [k, v] : node.entries) {
    if (std::find(known.begin(), known.end(), k.scalar) == known.end()) {
      const std::string near = NearestWord(k.scalar, known);
      k.Fail(what_ + ": unknown key '" + k.scalar + "'" +
             (near.empty() ? "" : " (did you mean '" + near + "'?)"));
    }
  }
}

const YamlNode* MapReader::Optional(std::string_view key) const {
  for (const auto& [k, v] : node_.entries) {
    if (k.scalar == key) return &v;
  }
  return nullptr;
}

const YamlNode& MapReader::Required(std::string_view key) const {
  const YamlNode* value = Optional(key);
  if (value == nullptr) node_.Fail(what_ + ": missing key '" + std::string(key) + "'");
  return *value;
}

std::string MapReader::String(std::string_view key, const std::string& fallback) const {
  const YamlNode* value = Optional(key);
  return value ? value->AsString(key) : fallback;
}

void MapReader::Forbid(std::string_view key, const std::string& reason) const {
  for (const auto& [k, v] : node_.entries) {
    if (k.scalar == key) k.Fail(what_ + ": '" + k.scalar + "' " + reason);
  }
}

}  // namespace unimouse
