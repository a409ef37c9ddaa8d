// SPDX-License-Identifier: GPL-3.0-or-later
// The loader accepts a matching plugin library and refuses each kind of mismatch with one
// sentence naming the library.
#include "plugin_registry.h"

#include <gtest/gtest.h>

#include <string>

#include "inline_assets.h"
#include "kernel.h"
#include "probe_components.h"
#include "robot_spec.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

std::string FakeLibrary(const std::string& name) {
  return std::string(FAKE_PLUGIN_DIR) + "/" + name + "/libunimouse_fake_" + name + ".so";
}

std::string LoadError(const std::string& path) {
  try {
    LoadPluginLibrary(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PluginLoaderTest, LoadsAGoodLibraryAndItsTypes) {
  PluginRegistry registry;
  registry.AddLibrary(FakeLibrary("good"));
  const PluginRegistry::Entry* widget = registry.Find("fake.widget");
  ASSERT_NE(widget, nullptr);
  EXPECT_EQ(widget->library, FakeLibrary("good"));
  EXPECT_EQ(widget->type->nparam, 1);
  EXPECT_STREQ(widget->type->params[0].name, "speed_m_per_s");
}

TEST(PluginLoaderTest, RefusesAWrongAbiVersion) {
  const std::string e = LoadError(FakeLibrary("wrong_abi"));
  EXPECT_NE(e.find("built for plugin ABI version 2, but this unimouse uses version 1"),
            std::string::npos)
      << e;
  EXPECT_EQ(e.find('\n'), std::string::npos);
}

TEST(PluginLoaderTest, RefusesAWrongStructSize) {
  const std::string e = LoadError(FakeLibrary("wrong_size"));
  EXPECT_NE(e.find("built with an older plugin header"), std::string::npos) << e;
  EXPECT_NE(e.find(FakeLibrary("wrong_size")), std::string::npos) << e;
}

TEST(PluginLoaderTest, AcceptsAPluginBuiltAgainstAnOlderShorterHeaderAndReadsNothingBeyond) {
  PluginRegistry registry;
  registry.AddLibrary(FakeLibrary("old_header"));
  const PluginRegistry::Entry* widget = registry.Find("fake.widget");
  ASSERT_NE(widget, nullptr);
  EXPECT_EQ(widget->type->size, sizeof(unimouse_component_type));
  EXPECT_EQ(widget->type->start, nullptr);  // beyond its table: a hook it does not have
  EXPECT_NE(widget->original->start, nullptr);
  // and a run uses it: a start read from beyond its table would fail the kernel's creation
  const RobotSpec robot =
      ParseRobotSpec(testing::TinyRobotWith("  - { type: fake.widget, name: w }\n"), "robot.yaml");
  auto kernel = Kernel::Create(robot, nullptr, registry, 1);
  kernel->Step();
  EXPECT_EQ(kernel->state().step(), 1);
}

TEST(PluginLoaderTest, RefusesATypeTableShorterThanTheFirstPublishedOne) {
  const std::string e = LoadError(FakeLibrary("too_short"));
  EXPECT_NE(e.find("built with an older plugin header"), std::string::npos) << e;
}

TEST(PluginLoaderTest, RefusesAWrongMujocoVersion) {
  const std::string e = LoadError(FakeLibrary("wrong_mujoco"));
  EXPECT_NE(e.find("built against MuJoCo 3.1.2, but this unimouse runs MuJoCo 2.2.2"),
            std::string::npos)
      << e;
}

TEST(PluginLoaderTest, RefusesALibraryWithoutTheEntrySymbol) {
  const std::string e = LoadError(FakeLibrary("no_symbol"));
  EXPECT_NE(e.find("is not a unimouse plugin: it does not export unimouse_plugin_v1"),
            std::string::npos)
      << e;
}

TEST(PluginLoaderTest, RefusesAFileThatIsNotALibrary) {
  const std::string e = LoadError(std::string(UNIMOUSE_SOURCE_DIR) + "/robots/unimouse.yaml");
  EXPECT_NE(e.find("cannot load plugin library"), std::string::npos) << e;
}

TEST(PluginRegistryTest, ScansSearchPathDirectoriesAndSkipsMissingOnes) {
  PluginRegistry registry;
  registry.AddSearchPath({"/nonexistent/dir", std::string(FAKE_PLUGIN_DIR) + "/good"});
  EXPECT_NE(registry.Find("fake.widget"), nullptr);
}

TEST(PluginRegistryTest, EarlierDirectoryShadowsALibraryOfTheSameName) {
  PluginRegistry registry;
  const std::string good = std::string(FAKE_PLUGIN_DIR) + "/good";
  registry.AddSearchPath({good, good});
  EXPECT_EQ(registry.entries().size(), 1u);
}

TEST(PluginRegistryTest, StaticAndLoadedTypesMeetInOneTable) {
  PluginRegistry registry;
  registry.AddStatic(ComponentType<testing::Probe>());
  registry.AddStatic(ComponentType<testing::Probe>());  // the same type again is harmless
  registry.AddLibrary(FakeLibrary("good"));
  EXPECT_EQ(registry.Find("test.probe")->library, "built-in");
  EXPECT_EQ(registry.entries().size(), 2u);
}

TEST(PluginRegistryTest, DescribesTypesWithTheirParameterTables) {
  PluginRegistry registry;
  registry.AddStatic(ComponentType<testing::Probe>());
  const std::string text = DescribePlugins(registry);
  EXPECT_NE(text.find("test.probe  (built-in)"), std::string::npos) << text;
  EXPECT_NE(text.find("- tag (string), required: name written into the event log"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("- count (integer), default 1, [1, 10]"), std::string::npos) << text;
  EXPECT_NE(text.find("- mode (string), default `a`, one of a|b"), std::string::npos) << text;
}

}  // namespace
}  // namespace unimouse
