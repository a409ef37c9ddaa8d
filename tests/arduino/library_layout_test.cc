// SPDX-License-Identifier: GPL-3.0-or-later
// arduino-lib/ is an installable Arduino library: library.properties has every field the
// library format (1.5) requires, names a header that exists, agrees with library.json, and each
// example folder holds a sketch of its own name.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "text_file.h"

namespace unimouse {
namespace {

const std::filesystem::path kLibrary = UNIMOUSE_SOURCE_DIR "/arduino-lib";

TEST(ArduinoLibraryLayoutTest, PropertiesJsonHeaderAndExamplesAgree) {
  std::map<std::string, std::string> properties;
  std::istringstream lines(ReadTextFile((kLibrary / "library.properties").string()));
  for (std::string line; std::getline(lines, line);) {
    const size_t eq = line.find('=');
    if (eq != std::string::npos) properties[line.substr(0, eq)] = line.substr(eq + 1);
  }
  for (const char* key : {"name", "version", "author", "maintainer", "sentence", "paragraph",
                          "category", "url", "architectures"}) {
    EXPECT_EQ(properties.count(key), 1u) << key;
  }
  EXPECT_EQ(properties["name"], "UnimouseSim");
  EXPECT_TRUE(std::filesystem::exists(kLibrary / "src" / properties["includes"]));

  const auto json = nlohmann::json::parse(ReadTextFile((kLibrary / "library.json").string()));
  EXPECT_EQ(json["name"], properties["name"]);
  EXPECT_EQ(json["version"], properties["version"]);
  EXPECT_EQ(json["license"], "MIT");

  int examples = 0;
  for (const auto& dir : std::filesystem::directory_iterator(kLibrary / "examples")) {
    const std::string name = dir.path().filename().string();
    EXPECT_TRUE(std::filesystem::exists(dir.path() / (name + ".ino"))) << name;
    ++examples;
  }
  EXPECT_EQ(examples, 7);
}

}  // namespace
}  // namespace unimouse
