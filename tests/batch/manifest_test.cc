// SPDX-License-Identifier: GPL-3.0-or-later
// Batch manifests: what they expand to, and every mistake refused with file:line:col.
#include "manifest.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "run_program.h"
#include "unimouse/errors.h"

namespace unimouse::batch {
namespace {

namespace fs = std::filesystem;

class ManifestTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::FreshDirectory("manifest"); }

  std::string Write(const std::string& name, const std::string& text) {
    const fs::path path = fs::path(dir_) / name;
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
    return path.string();
  }

  // the message of the InputError that loading the manifest text throws, or ""
  std::string ErrorOf(const std::string& text) {
    const std::string file = Write("manifest.yaml", text);
    try {
      LoadManifest(file);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  std::string dir_;
};

TEST_F(ManifestTest, TheBatchIsTheProductOfSubmissionsScenariosMazesAndSeedsSortedById) {
  Write("fw/amy", "");
  const Manifest m = LoadManifest(Write("m.yaml", R"(
submissions:
  - name: zed
    controller: z.lua
  - name: amy
    link: native:fw/amy --fast
scenarios:
  - micromouse
mazes: [japan2019, japan2018]
seeds: [2, 1]
)"));
  ASSERT_EQ(m.jobs.size(), 8u);  // 2 x 1 x 2 x 2
  EXPECT_EQ(m.jobs.front().id, "amy/micromouse/japan2018/seed-1");
  EXPECT_EQ(m.jobs[1].id, "amy/micromouse/japan2018/seed-2");
  EXPECT_EQ(m.jobs.back().id, "zed/micromouse/japan2019/seed-2");
  // paths are the manifest's directory's, and a native program keeps its arguments
  EXPECT_EQ(m.submissions[0].controller, dir_ + "/z.lua");
  EXPECT_EQ(m.submissions[1].link, "native:" + dir_ + "/fw/amy --fast");
  EXPECT_EQ(m.jobs.front().submission, 1);
  EXPECT_TRUE(m.jobs.front().maze_file.ends_with("mazes/japan2018.txt"));
}

TEST_F(ManifestTest, AJobIsTheRunCommandOfItsSubmissionScenarioMazeAndSeed) {
  Write("amy.elf", "");
  const Manifest m = LoadManifest(Write("m.yaml", R"(
submissions:
  - name: amy
    link: avr:amy.elf
    link_set: {lockstep_timeout_s: 20}
    firmware_profile: unimousesim-0.1
scenarios:
  - scenario: micromouse
    set: {contest_s: 30}
mazes: [japan2018]
seeds: [7]
)"));
  ASSERT_EQ(m.jobs.size(), 1u);
  const std::vector<std::string> args = RunArguments(m, m.jobs[0], "/out/j");
  const std::vector<std::string> expected = {"run",
                                             "--out",
                                             "/out/j",
                                             "--seed",
                                             "7",
                                             "--robot",
                                             "unimouse",
                                             "--scenario",
                                             m.scenarios[0].file,
                                             "--trace-period",
                                             "0",
                                             "--set",
                                             "contest_s=30",
                                             "--maze",
                                             m.jobs[0].maze_file,
                                             "--link",
                                             "avr:" + dir_ + "/amy.elf",
                                             "--link-set",
                                             "lockstep_timeout_s=20",
                                             "--firmware-profile",
                                             "unimousesim-0.1"};
  EXPECT_EQ(args, expected);
}

// an algorithm written for mms scored over mazes: its jobs run `unimouse mms`, not a scenario
TEST_F(ManifestTest, AnMmsProgramRunsInEveryMazeWithoutTheScenarios) {
  fs::create_directories(dir_ + "/bob");
  const Manifest m = LoadManifest(Write("m.yaml", R"(
submissions:
  - {name: amy, controller: a.lua}
  - name: bob
    mms: python3  main.py --fast
    dir: bob
    mms_options: [--end-on-crash]
scenarios: [micromouse]
mazes: [japan2018, japan2019]
)"));
  ASSERT_EQ(m.jobs.size(), 4u);  // amy: 1 scenario x 2 mazes; bob: 2 mazes
  EXPECT_EQ(m.jobs[2].id, "bob/mms/japan2018/seed-1");
  EXPECT_EQ(m.jobs[3].id, "bob/mms/japan2019/seed-1");
  EXPECT_EQ(ScenarioName(m, m.jobs[2]), "mms");
  const std::vector<std::string> expected = {
      "mms",         "--out",          "/out/j", "--maze",  m.jobs[2].maze_file, "--program-dir",
      dir_ + "/bob", "--end-on-crash", "--",     "python3", "main.py",           "--fast"};
  EXPECT_EQ(RunArguments(m, m.jobs[2], "/out/j"), expected);
  // without dir: the manifest's directory, as mms runs a program in its own directory
  const Manifest only = LoadManifest(Write("only.yaml", R"(
submissions: [{name: bob, mms: ./solver}]
jobs: [{submission: bob, maze: japan2019, seed: 3}]
)"));
  ASSERT_EQ(only.jobs.size(), 1u);
  EXPECT_EQ(only.jobs[0].id, "bob/mms/japan2019/seed-3");
  EXPECT_EQ(only.submissions[0].program_dir, dir_);
}

TEST_F(ManifestTest, AnMmsProgramsMistakesAreRefusedWithFileLineAndColumn) {
  const std::string file = dir_ + "/manifest.yaml";
  const std::string mazes = "mazes: [japan2018]\n";
  EXPECT_EQ(ErrorOf("submissions: [{name: bob, mms: ' '}]\n" + mazes),
            file + ":1:32: mms must name a program");
  EXPECT_EQ(ErrorOf("submissions: [{name: bob, mms: x, dir: nowhere}]\n" + mazes),
            file + ":1:40: " + dir_ + "/nowhere: no such directory");
  EXPECT_EQ(ErrorOf("submissions: [{name: bob, mms: x, link_set: {a: 1}}]\n" + mazes),
            file + ":1:45: link_set goes with link");
  EXPECT_EQ(ErrorOf("submissions: [{name: bob, controller: c.lua, dir: .}]\n"
                    "scenarios: [micromouse]\n"),
            file + ":1:51: dir is where an mms program runs; it goes with mms");
  EXPECT_EQ(ErrorOf("submissions: [{name: bob, mms: x}]\n"),
            file + ":1:1: submission 'bob' (" + file +
                ":1:15) is an mms program, which runs in mazes: give them (mazes: [...])");
  EXPECT_EQ(
      ErrorOf("submissions: [{name: bob, mms: x}]\n"
              "jobs: [{submission: bob, scenario: micromouse, maze: japan2018}]\n"),
      file + ":2:26: job: 'scenario' does not apply to an mms program: it runs in its maze alone");
}

TEST_F(ManifestTest, AFirmwareNotBesideTheManifestIsNamedAsGiven) {
  // the link finds it then: a bundled firmware's name, or an error of that one job
  const Manifest m = LoadManifest(Write("m.yaml", R"(
submissions: [{name: amy, link: "native:micromouse --fast"}, {name: bo, link: pty}]
scenarios: [micromouse]
)"));
  EXPECT_EQ(m.submissions[0].link, "native:micromouse --fast");
  EXPECT_EQ(m.submissions[1].link, "pty");
}

TEST_F(ManifestTest, ADirectoryOfMazesIsEveryMazeFileInItSorted) {
  const std::string maze = "o---o\n| S |\no---o\n";
  Write("contest/b.txt", maze);
  Write("contest/a.txt", maze);
  Write("contest/notes.md", "not a maze");
  const Manifest m = LoadManifest(Write("m.yaml", R"(
submissions: [{name: amy, controller: a.lua}]
scenarios: [micromouse]
mazes: [contest]
)"));
  ASSERT_EQ(m.jobs.size(), 2u);
  EXPECT_EQ(m.jobs[0].id, "amy/micromouse/a/seed-1");
  EXPECT_EQ(m.jobs[0].maze_file, dir_ + "/contest/a.txt");
  EXPECT_EQ(m.jobs[1].maze_file, dir_ + "/contest/b.txt");
}

TEST_F(ManifestTest, AnExplicitJobListReplacesTheProduct) {
  const Manifest m = LoadManifest(Write("m.yaml", R"(
submissions: [{name: amy, controller: a.lua}, {name: bo, controller: b.lua}]
scenarios: [micromouse, speed_control]
jobs:
  - {submission: bo, scenario: speed_control, seed: 3}
  - {submission: amy, scenario: micromouse, maze: japan2019}
)"));
  ASSERT_EQ(m.jobs.size(), 2u);
  EXPECT_EQ(m.jobs[0].id, "amy/micromouse/japan2019/seed-1");
  EXPECT_EQ(m.jobs[1].id, "bo/speed_control/no-maze/seed-3");
}

TEST_F(ManifestTest, NamesAreMadeSafeForDirectories) {
  EXPECT_EQ(SanitizeName("Ann Lee/v2"), "Ann_Lee_v2");
  EXPECT_EQ(SanitizeName(".."), "_");
  EXPECT_EQ(SanitizeName("a.b-c_d"), "a.b-c_d");
  const Manifest m = LoadManifest(Write("m.yaml", R"(
submissions: [{name: "Ann Lee", controller: a.lua}]
scenarios: [micromouse]
)"));
  EXPECT_EQ(m.jobs[0].id, "Ann_Lee/micromouse/japan2018/seed-1");
}

TEST_F(ManifestTest, MistakesAreRefusedWithFileLineAndColumn) {
  const std::string head = "submissions: [{name: amy, controller: a.lua}]\n";
  const std::string file = dir_ + "/manifest.yaml";
  EXPECT_EQ(ErrorOf(head + "scenarios: [micromouse]\nseed: [1]\n"),
            file + ":3:1: manifest: unknown key 'seed' (did you mean 'seeds'?)");
  EXPECT_EQ(ErrorOf(head + "scenarios: [micromouse]\nseeds: [one]\n"),
            file + ":3:9: seed must be a number, not 'one'");
  EXPECT_EQ(ErrorOf(head + "scenarios: [speed_control]\nmazes: [japan2018]\n"),
            file + ":3:8: scenario 'speed_control' (" + file +
                ":2:13) has no maze parameter: mazes go with scenarios that run in a maze");
  EXPECT_EQ(ErrorOf("submissions:\n  - {name: amy, controller: a.lua}\n  - {name: amy, link: "
                    "pty}\nscenarios: [micromouse]\n"),
            file +
                ":3:5: a second submission named 'amy' (names must differ, also once made "
                "safe for a directory)");
  EXPECT_EQ(ErrorOf("submissions: [{name: amy, controller: a.lua, link: pty}]\n"
                    "scenarios: [micromouse]\n"),
            file + ":1:15: submission 'amy': give exactly one of link, controller or mms");
  EXPECT_EQ(ErrorOf(head + "scenarios: [{scenario: micromouse, set: {contest: 5}}]\n"),
            file +
                ":2:42: scenario 'micromouse' has no parameter 'contest' (did you mean "
                "'contest_s'?)");
  EXPECT_EQ(ErrorOf(head + "scenarios: [micromouse]\nlimits: {memory_mb: 10}\n"),
            file + ":3:21: memory_mb must be from 256 to 262144, not 10");
  EXPECT_EQ(ErrorOf(head + "scenarios: [micromouse]\njobs: [{submission: amu, scenario: "
                           "micromouse}]\n"),
            file + ":3:21: no submission named 'amu' (did you mean 'amy'?)");
  EXPECT_NE(ErrorOf(head + "scenarios: [no_such_scenario]\n").find(file + ":2:13: "),
            std::string::npos);
}

TEST_F(ManifestTest, ANameTheSystemCannotLookUpIsAMistakeAtItsNodeNotACrash) {
  // 300 characters is longer than a file name may be (NAME_MAX 255): looking it up fails with
  // ENAMETOOLONG, which is the same answer as no such file, for every kind of name a manifest has
  const std::string head = "submissions: [{name: amy, controller: a.lua}]\n";
  const std::string file = dir_ + "/manifest.yaml";
  const std::string long_name(300, 'x');
  EXPECT_EQ(ErrorOf(head + "scenarios: [" + long_name + "]\n").rfind(file + ":2:13: ", 0), 0u);
  EXPECT_EQ(ErrorOf(head + "scenarios: [micromouse]\nmazes: [" + long_name + "]\n")
                .rfind(file + ":3:9: ", 0),
            0u);
  EXPECT_EQ(ErrorOf("submissions: [{name: amy, controller: a.lua, robot: " + long_name +
                    "}]\nscenarios: [micromouse]\n")
                .rfind(file + ":1:", 0),
            0u);
  const Manifest m =
      LoadManifest(Write("m.yaml", "submissions: [{name: amy, link: \"native:" + long_name +
                                       "\"}]\nscenarios: [micromouse]\n"));
  EXPECT_EQ(m.submissions[0].link, "native:" + long_name);
}

}  // namespace
}  // namespace unimouse::batch
