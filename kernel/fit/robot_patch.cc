// SPDX-License-Identifier: GPL-3.0-or-later
#include "robot_patch.h"

#include <algorithm>
#include <cstdio>
#include <map>

#include "unimouse/errors.h"

namespace unimouse::fit {
namespace {

std::string Number(double v) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.6g", v);
  return text;
}

// an edit of one line: replace [column, column + length) by `text` (length 0: insert)
struct Edit {
  size_t column;  // 0-based
  size_t length;
  std::string text;
};

}  // namespace

std::string PatchRobotText(const std::string& text, const RobotSpec& robot,
                           const std::vector<FittedParameter>& parameters,
                           const std::string& provenance) {
  std::vector<std::string> lines;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t end = text.find('\n', start);
    lines.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  std::map<int, std::vector<Edit>> edits;         // by 1-based line
  std::map<int, std::vector<std::string>> above;  // comment lines before a 1-based line

  std::map<std::string, std::string> notes;  // component -> what changed
  for (const FittedParameter& p : parameters) {
    if (!p.identified) continue;
    const ComponentSpec* component = nullptr;
    for (const ComponentSpec& c : robot.components) {
      if (c.name == p.ref.component) component = &c;
    }
    if (component == nullptr || !component->params.IsMap()) {
      throw InputError(robot.file + ": no component '" + p.ref.component + "' with params");
    }
    const std::string value = Number(p.value);
    const YamlEntry* given = nullptr;
    for (const YamlEntry& e : component->params.entries) {
      if (e.first.scalar == p.ref.key) given = &e;
    }
    if (given != nullptr) {
      const SourceLocation& at = given->second.location;
      const std::string& line = lines.at(static_cast<size_t>(at.line - 1));
      const size_t from = static_cast<size_t>(at.column - 1);
      size_t to = from;
      while (to < line.size() && line[to] != ',' && line[to] != '}' && line[to] != ' ' &&
             line[to] != '#') {
        ++to;
      }
      edits[at.line].push_back({from, to - from, value});
    } else {
      const SourceLocation& at = component->params.location;
      const std::string& line = lines.at(static_cast<size_t>(at.line - 1));
      const size_t from = static_cast<size_t>(at.column - 1);
      if (from < line.size() && line[from] == '{') {
        edits[at.line].push_back({from + 1, 0, " " + p.ref.key + ": " + value + ","});
      } else {
        // a block map: a line of its own, indented as the map's first key
        above[at.line].push_back(std::string(from, ' ') + p.ref.key + ": " + value);
      }
    }
    const std::string was = ParameterDrawn(robot, p.ref) ? "drawn" : Number(p.file_value);
    notes[p.ref.component] += (notes[p.ref.component].empty() ? "" : ", ") + p.ref.key + " " +
                              value + " (was " + was + ")";
  }
  for (const auto& [name, note] : notes) {
    for (const ComponentSpec& c : robot.components) {
      if (c.name != name) continue;
      // above the component's first line ("- type: ..."), indented as its keys
      const std::string indent(static_cast<size_t>(std::max(c.location.column - 1, 0)), ' ');
      above[c.location.line].insert(above[c.location.line].begin(),
                                    indent + "# " + provenance + ": " + note);
    }
  }

  std::string out;
  for (size_t i = 0; i < lines.size(); ++i) {
    const int number = static_cast<int>(i) + 1;
    std::string line = lines[i];
    if (auto it = edits.find(number); it != edits.end()) {
      // right to left, so that earlier columns stay where they were
      std::vector<Edit> es = it->second;
      std::sort(es.begin(), es.end(),
                [](const Edit& a, const Edit& b) { return a.column > b.column; });
      for (const Edit& e : es) line.replace(e.column, e.length, e.text);
    }
    if (auto it = above.find(number); it != above.end()) {
      for (const std::string& a : it->second) out += a + "\n";
    }
    out += line;
    if (i + 1 < lines.size()) out += "\n";
  }
  return out;
}

}  // namespace unimouse::fit
