// SPDX-License-Identifier: GPL-3.0-or-later
// Each plugin's README lists exactly the parameters the plugin declares, with their kinds and
// defaults, so the documentation cannot drift from the code.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "bundled_plugins.h"
#include "plugin_registry.h"

namespace unimouse {
namespace {

struct Row {
  std::string kind;
  std::string default_text;
};

// rows of the parameter table: | `name` | kind | default | meaning |
std::map<std::string, Row> ReadmeTable(const std::string& folder) {
  std::ifstream in(std::string(UNIMOUSE_SOURCE_DIR) + "/plugins/" + folder + "/README.md");
  EXPECT_TRUE(in.good()) << folder << "/README.md is missing";
  std::map<std::string, Row> rows;
  bool in_table = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("| parameter |", 0) == 0) in_table = true;
    if (line.rfind("|", 0) != 0) in_table = false;
    if (!in_table || line.rfind("| `", 0) != 0) continue;
    std::vector<std::string> cells;
    std::stringstream cells_in(line.substr(1));
    for (std::string cell; std::getline(cells_in, cell, '|');) {
      cell.erase(0, cell.find_first_not_of(' '));
      cell.erase(cell.find_last_not_of(' ') + 1);
      cells.push_back(cell);
    }
    if (cells.size() < 4) continue;
    rows[cells[0].substr(1, cells[0].size() - 2)] = {cells[1], cells[2]};
  }
  return rows;
}

void ExpectReadmeMatches(const std::string& folder, const unimouse_component_type* type) {
  const std::map<std::string, Row> rows = ReadmeTable(folder);
  EXPECT_EQ(rows.size(), static_cast<size_t>(type->nparam)) << folder;
  for (int i = 0; i < type->nparam; ++i) {
    const unimouse_param& p = type->params[i];
    const auto it = rows.find(p.name);
    if (it == rows.end()) {
      ADD_FAILURE() << folder << "/README.md does not list " << p.name;
      continue;
    }
    EXPECT_EQ(it->second.kind, ParamKindName(p.kind)) << folder << ": " << p.name;
    EXPECT_EQ(it->second.default_text, ParamDefaultText(p)) << folder << ": " << p.name;
  }
}

TEST(ReadmeSchemaTest, EveryPluginReadmeListsItsParameters) {
  std::set<std::string> checked;
#define UNIMOUSE_CHECK_README(folder, type)            \
  ExpectReadmeMatches(#folder, ComponentType<type>()); \
  checked.insert(#folder);
  UNIMOUSE_BUNDLED_PLUGINS(UNIMOUSE_CHECK_README)
#undef UNIMOUSE_CHECK_README

  // the list is every plugin folder of the source tree
  std::set<std::string> folders;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(UNIMOUSE_SOURCE_DIR) + "/plugins")) {
    if (std::filesystem::exists(entry.path() / "plugin.cc")) {
      folders.insert(entry.path().filename().string());
    }
  }
  EXPECT_EQ(checked, folders);
}

}  // namespace
}  // namespace unimouse
