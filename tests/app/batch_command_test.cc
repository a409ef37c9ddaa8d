// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse batch` as a teacher runs it: a class of submissions, one correct, one that fails the
// challenge, one that crashes and one that hangs, on two mazes with two seeds; the same results
// again on a second run, through GNU parallel and through the Slurm array script; untrusted
// submissions kept to their own jobs; Ctrl-C and resume.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "run_program.h"
#include "text_file.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using unimouse::ReadTextFile;
using unimouse::testing::FreshDirectory;
using unimouse::testing::Outcome;
using unimouse::testing::Unimouse;

const std::string kSource = UNIMOUSE_SOURCE_DIR;

// the class: four submissions in a contest of 3 s that ends at the first run to the goal
std::string ClassManifest() {
  return std::string(R"(
submissions:
  - name: good
    controller: )") +
         kSource + R"(/tests/batch/walking_mouse.lua
  - name: lost
    controller: )" +
         kSource + R"(/tests/scenarios/wandering_mouse.lua
  - name: segfault
    link: inproc:)" +
         UNIMOUSE_TEST_BINARY_DIR + R"(/null_pointer_firmware.so
  - name: stuck
    link: native:)" +
         UNIMOUSE_TEST_FIRMWARE + R"( --hang-at 50
    link_set: {lockstep_timeout_s: 60}
    limits: {wall_time_s: 2}
scenarios:
  - scenario: micromouse
    set: {contest_s: 3, max_runs: 1}
mazes: [japan2018, japan2019]
seeds: [1, 2]
limits: {wall_time_s: 60}
)";
}

std::string WriteFile(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// the CSV's lines with one column left out (by header name)
std::vector<std::string> CsvWithout(const std::string& file, const std::string& column) {
  std::istringstream in(ReadTextFile(file));
  std::vector<std::string> lines;
  int skip = -1;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::string field;
    bool quoted = false;
    for (char c : line) {
      if (c == '"') quoted = !quoted;
      if (c == ',' && !quoted) {
        fields.push_back(field);
        field.clear();
      } else {
        field += c;
      }
    }
    fields.push_back(field);
    if (skip < 0) {
      for (size_t i = 0; i < fields.size(); ++i) {
        if (fields[i] == column) skip = static_cast<int>(i);
      }
    }
    std::string kept;
    for (size_t i = 0; i < fields.size(); ++i) {
      if (static_cast<int>(i) != skip) kept += fields[i] + ",";
    }
    lines.push_back(kept);
  }
  return lines;
}

json Results(const std::string& out) { return json::parse(ReadTextFile(out + "/results.json")); }

std::map<std::string, fs::file_time_type> JobRecordTimes(const std::string& out) {
  std::map<std::string, fs::file_time_type> times;
  for (const auto& e : fs::recursive_directory_iterator(out + "/jobs")) {
    if (e.path().filename() == "job.json") times[e.path().string()] = fs::last_write_time(e);
  }
  return times;
}

TEST(BatchCommandTest, AClassGetsTheRightStatusForEveryJobTheSameOnResumeAndThroughParallel) {
  const std::string dir = FreshDirectory("batch_class");
  const std::string manifest = WriteFile(dir, "class.yaml", ClassManifest());
  const std::string out = dir + "/out";
  const Outcome run = Unimouse("batch run " + manifest + " -j 2 --out " + out);
  ASSERT_EQ(run.exit_code, 1) << run.output;  // not every job passed

  const json results = Results(out);
  ASSERT_EQ(results["jobs"].size(), 16u) << results.dump(1);
  const std::map<std::string, std::string> expected = {
      {"good", "passed"}, {"lost", "failed"}, {"segfault", "crashed"}, {"stuck", "timeout"}};
  for (const auto& job : results["jobs"]) {
    const std::string submission = job["submission"];
    EXPECT_EQ(job["status"], expected.at(submission)) << job.dump();
    EXPECT_TRUE(fs::exists(out + "/" + job["dir"].get<std::string>() + "/job.json"));
    if (submission == "good") {
      // walking_mouse.lua's path by hand: 7 cells north, a quarter turn, 7 cells east
      EXPECT_EQ(job["scores"]["best_run_path_cost"], 15) << job.dump();
      EXPECT_EQ(job["pictures"].size(), 1u) << job.dump();  // final.png
    }
    if (submission == "lost") {
      EXPECT_EQ(
          job["reason"],
          "no run reached the goal in 3.0 s (0 wall contacts); the time ran out during run 1");
    }
    if (submission == "segfault") {
      EXPECT_NE(job["reason"].get<std::string>().find("SIGSEGV"), std::string::npos);
    }
    if (submission == "stuck") {
      EXPECT_EQ(job["reason"], "still running after the wall-time limit of 2 s");
      EXPECT_LT(job["wall_time_s"].get<double>(), 10);
    }
  }
  EXPECT_EQ(results["jobs"][0]["id"], "good/micromouse/japan2018/seed-1");
  EXPECT_EQ(results["summary"][0]["passed"], 4);
  EXPECT_DOUBLE_EQ(results["summary"][0]["mean_path_cost"].get<double>(), 15);
  EXPECT_EQ(results["summary"][3]["timeout"], 4);
  const std::string csv = ReadTextFile(out + "/results.csv");
  // the teacher's page has every job (its rendering: tests/report)
  const std::string page = ReadTextFile(out + "/report.html");
  for (const auto& job : results["jobs"]) {
    EXPECT_NE(page.find(job["id"].get<std::string>()), std::string::npos) << job["id"];
  }

  // a second run keeps every job: no job.json is written again, and the CSV is the same
  const auto times = JobRecordTimes(out);
  const Outcome again = Unimouse("batch run " + manifest + " -j 2 --out " + out);
  EXPECT_EQ(again.exit_code, 1) << again.output;
  EXPECT_NE(again.output.find("16 jobs, 0 to run"), std::string::npos) << again.output;
  EXPECT_EQ(JobRecordTimes(out), times);
  EXPECT_EQ(ReadTextFile(out + "/results.csv"), csv);

  // the plan's lines through GNU parallel, then collect: the same CSV but for wall time
  const std::string planned = dir + "/planned";
  const Outcome plan = Unimouse("batch plan " + manifest + " --out " + planned);
  ASSERT_EQ(plan.exit_code, 0) << plan.output;
  const std::string jobs_txt = ReadTextFile(planned + "/jobs.txt");
  EXPECT_EQ(std::count(jobs_txt.begin(), jobs_txt.end(), '\n'), 16);
  EXPECT_EQ(jobs_txt.substr(0, jobs_txt.find('\n')),
            std::string(UNIMOUSE_BINARY) + " batch job " + manifest +
                " good/micromouse/japan2018/seed-1 --out " + planned);
  if (std::system("parallel --version >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "GNU parallel is not installed (setup.sh installs it)";
  }
  EXPECT_EQ(std::system(("parallel -j 2 < " + planned + "/jobs.txt >/dev/null 2>&1").c_str()) >> 8,
            12);  // parallel's exit code: how many lines failed
  const Outcome collect = Unimouse("batch collect " + planned);
  EXPECT_EQ(collect.exit_code, 1) << collect.output;
  EXPECT_EQ(CsvWithout(planned + "/results.csv", "wall_time_s"),
            CsvWithout(out + "/results.csv", "wall_time_s"));
}

// an algorithm written for mms scored over mazes as each of its own `unimouse mms` runs scores
// docs/batch.md: a job is kept only while the SHA-256 of every file it reads is unchanged
TEST(BatchCommandTest, AResubmittedControllerOrAChangedScenarioIsGradedAgainOnResume) {
  const std::string dir = FreshDirectory("batch_regrade");
  const std::string controller =
      WriteFile(dir, "student.lua", ReadTextFile(kSource + "/tests/batch/walking_mouse.lua"));
  const std::string scenario =
      WriteFile(dir, "contest.lua", ReadTextFile(kSource + "/scenarios/micromouse.lua"));
  const std::string manifest = WriteFile(dir, "class.yaml", R"(
submissions:
  - name: student
    controller: student.lua
scenarios:
  - scenario: contest.lua
    set: {contest_s: 3, max_runs: 1}
mazes: [japan2018]
)");
  const std::string out = dir + "/out";
  const std::string batch = "batch run " + manifest + " -j 1 --out " + out;
  auto graded = [&](const std::string& role) {
    const json results = Results(out);
    for (const auto& input : results["jobs"][0]["inputs"]) {
      if (input["role"] == role) return input["sha256"].get<std::string>();
    }
    return std::string("none");
  };
  auto sha256sum = [](const std::string& file) {
    return unimouse::testing::Shell("sha256sum " + file).output.substr(0, 64);
  };

  Outcome o = Unimouse(batch);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("1 jobs, 1 to run"), std::string::npos) << o.output;
  EXPECT_EQ(graded("submission"), sha256sum(controller));
  EXPECT_EQ(graded("scenario"), sha256sum(scenario));
  EXPECT_EQ(graded("maze"), sha256sum(kSource + "/mazes/japan2018.txt"));
  EXPECT_EQ(graded("robot"), sha256sum(kSource + "/robots/unimouse.yaml"));
  o = Unimouse(batch);
  EXPECT_NE(o.output.find("1 jobs, 0 to run"), std::string::npos) << o.output;

  // the student resubmits: the same command line, another file
  std::ofstream(controller, std::ios::app) << "-- resubmitted\n";
  o = Unimouse(batch);
  EXPECT_NE(o.output.find("1 jobs, 1 to run"), std::string::npos) << o.output;
  EXPECT_EQ(graded("submission"), sha256sum(controller));

  // the teacher changes the scenario
  std::ofstream(scenario, std::ios::app) << "-- the rules, amended\n";
  o = Unimouse(batch);
  EXPECT_NE(o.output.find("1 jobs, 1 to run"), std::string::npos) << o.output;
  EXPECT_EQ(graded("scenario"), sha256sum(scenario));
}

TEST(BatchCommandTest, ForceForgetsEveryEarlierRecordOfTheManifestsJobs) {
  const std::string dir = FreshDirectory("batch_force");
  const std::string manifest = WriteFile(dir, "class.yaml", R"(
submissions:
  - name: student
    controller: )" + kSource + R"(/tests/batch/walking_mouse.lua
scenarios:
  - scenario: micromouse
    set: {contest_s: 3, max_runs: 1}
mazes: [japan2018, japan2019]
)");
  const std::string out = dir + "/out";
  ASSERT_EQ(Unimouse("batch run " + manifest + " -j 1 --out " + out).exit_code, 0);
  // a record of the earlier grading in each job's directory
  for (const auto& e : fs::recursive_directory_iterator(out + "/jobs")) {
    if (e.path().filename() == "job.json") {
      std::ofstream(e.path().parent_path() / "earlier.txt") << "old\n";
    }
  }
  // RunBatch removes each job's directory before the first job starts, so that an interrupted
  // --force cannot leave earlier records beside new ones
  const Outcome o = Unimouse("batch run " + manifest + " -j 1 --force --out " + out);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("2 jobs, 2 to run"), std::string::npos) << o.output;
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    EXPECT_NE(e.path().filename(), "earlier.txt") << e.path();
  }
}

// docs/batch.md: `robot:` at the top for every job, and per submission for its own jobs
TEST(BatchCommandTest, ASubmissionCanBringItsOwnRobotFile) {
  const std::string dir = FreshDirectory("batch_own_robot");
  const std::string robot =
      WriteFile(dir, "erin.yaml", ReadTextFile(kSource + "/robots/unimouse.yaml"));
  const std::string manifest = WriteFile(dir, "class.yaml", R"(
robot: unimouse
submissions:
  - name: dan
    controller: )" + kSource + R"(/tests/batch/walking_mouse.lua
  - name: erin
    controller: )" + kSource + R"(/tests/batch/walking_mouse.lua
    robot: erin.yaml
scenarios:
  - scenario: micromouse
    set: {contest_s: 3, max_runs: 1}
mazes: [japan2018]
)");
  const std::string out = dir + "/out";
  const Outcome o = Unimouse("batch run " + manifest + " -j 1 --out " + out);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  std::map<std::string, std::string> robots;
  const json results = Results(out);
  for (const auto& job : results["jobs"]) {
    const json result =
        json::parse(ReadTextFile(out + "/" + job["dir"].get<std::string>() + "/result.json"));
    robots[job["submission"].get<std::string>()] = result["robot"].get<std::string>();
  }
  EXPECT_EQ(robots["erin"], robot);
  EXPECT_EQ(fs::path(robots["dan"]).filename(), "unimouse.yaml");
  EXPECT_NE(robots["dan"], robot);
}

TEST(BatchCommandTest, ARaceJobPutsSeveralSubmissionsInOneWorldEachARobotOfItsName) {
  // the jumping controller reaches the goal at 1.4 s from the opposite corner; a controller
  // that does nothing never does, and the race ends at its time limit
  const std::string dir = FreshDirectory("batch_race");
  WriteFile(dir, "stand.lua", "return function(time_s) end\n");
  const std::string manifest = WriteFile(dir, "race.yaml", R"(
submissions:
  - {name: dan, controller: stand.lua}
  - {name: erin, controller: )" + kSource + R"(/tests/scenarios/race_jumping_controller.lua}
scenarios:
  - scenario: race
    set: {time_limit_s: 3}
jobs:
  - {submissions: [dan, erin], scenario: race}
)");
  const std::string out = dir + "/out";
  const Outcome o = Unimouse("batch run " + manifest + " -j 1 --out " + out);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const json results = Results(out);
  ASSERT_EQ(results["jobs"].size(), 1u);
  const json& job = results["jobs"][0];
  EXPECT_EQ(job["id"], "dan+erin/race/japan2018/seed-1");
  EXPECT_EQ(job["submission"], "dan+erin");
  EXPECT_EQ(job["status"], "passed") << job;
  const json result =
      json::parse(ReadTextFile(out + "/" + job["dir"].get<std::string>() + "/result.json"));
  ASSERT_EQ(result["robots"].size(), 2u);
  EXPECT_EQ(result["robots"][0]["name"], "dan");
  EXPECT_EQ(result["robots"][1]["name"], "erin");
  EXPECT_EQ(result["scenario"]["reason"].get<std::string>().rfind("erin wins in 1.4", 0), 0u)
      << result["scenario"]["reason"];
}

// docs/limits.md's limit per call, named in a reason that names the file as the manifest does
TEST(BatchCommandTest, AControllerThatNeverReturnsIsAScriptErrorNamingItsFileAndTheLimitPerCall) {
  const std::string dir = FreshDirectory("batch_endless");
  WriteFile(dir, "loop.lua", "return function(time_s)\n  while true do end\nend\n");
  const std::string manifest = WriteFile(dir, "class.yaml", R"(
submissions:
  - {name: frank, controller: loop.lua}
scenarios:
  - scenario: micromouse
    set: {contest_s: 3, max_runs: 1}
mazes: [japan2018]
)");
  const std::string out = dir + "/out";
  const Outcome o = Unimouse("batch run " + manifest + " -j 1 --out " + out);
  EXPECT_EQ(o.exit_code, 1) << o.output;
  const json job = Results(out)["jobs"][0];
  EXPECT_EQ(job["status"], "script_error") << job.dump();
  const std::string reason = job["reason"];
  EXPECT_EQ(reason.rfind("loop.lua:2: instruction budget exhausted: more than 20 million "
                         "instructions in one call into the script, its limit per call",
                         0),
            0u)
      << reason;
  EXPECT_EQ(reason.find(dir), std::string::npos) << reason;
}

// docs/batch.md "Traces": none unless the manifest asks
TEST(BatchCommandTest, JobsWriteATraceOnlyWhenTheManifestAsksForOne) {
  const std::string dir = FreshDirectory("batch_trace");
  const std::string jobs = R"(
submissions:
  - name: student
    controller: )" + kSource +
                           R"(/tests/batch/walking_mouse.lua
scenarios:
  - scenario: micromouse
    set: {contest_s: 3, max_runs: 1}
mazes: [japan2018]
)";
  auto traces = [&](const std::string& out) {
    std::vector<std::string> found;
    for (const auto& e : fs::recursive_directory_iterator(out + "/jobs")) {
      if (e.path().filename() == "trace.csv") found.push_back(ReadTextFile(e.path().string()));
    }
    return found;
  };
  const std::string plain = WriteFile(dir, "plain.yaml", jobs);
  ASSERT_EQ(Unimouse("batch run " + plain + " -j 1 --out " + dir + "/plain").exit_code, 0);
  EXPECT_TRUE(traces(dir + "/plain").empty());

  const std::string asked =
      WriteFile(dir, "asked.yaml", "trace: {period_s: 0.5, signals: tof.front_m}\n" + jobs);
  ASSERT_EQ(Unimouse("batch run " + asked + " -j 1 --out " + dir + "/asked").exit_code, 0);
  const std::vector<std::string> found = traces(dir + "/asked");
  ASSERT_EQ(found.size(), 1u);
  const std::string header = found[0].substr(0, found[0].find('\n'));
  EXPECT_NE(header.find("tof.front_m"), std::string::npos) << header;
  EXPECT_EQ(header.find("left.command"), std::string::npos) << header;
}

// docs/batch.md "The summary": what the teacher scored, ranked by the manifest's score
TEST(BatchCommandTest, TheSummaryAggregatesTheScoresRanksByTheManifestsScoreAndNamesThePage) {
  const std::string dir = FreshDirectory("batch_rank");
  const std::string manifest = WriteFile(dir, "class.yaml", R"(
rank: best_run_path_cost
submissions:
  - name: lost
    controller: )" + kSource + R"(/tests/scenarios/wandering_mouse.lua
  - name: good
    controller: )" + kSource + R"(/tests/batch/walking_mouse.lua
scenarios:
  - scenario: micromouse
    set: {contest_s: 3, max_runs: 1}
mazes: [japan2018]
seeds: [1, 2]
)");
  const std::string out = dir + "/out";
  const Outcome o = Unimouse("batch run " + manifest + " -j 2 --out " + out);
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("report: " + out + "/report.html"), std::string::npos) << o.output;
  const json results = Results(out);
  EXPECT_EQ(results["rank"]["score"], "best_run_path_cost");
  const json& first = results["summary"][0];
  EXPECT_EQ(first["submission"], "good") << results["summary"].dump(1);
  EXPECT_EQ(first["rank"], 1);
  // walking_mouse.lua's path by hand: 7 cells north, a quarter turn, 7 cells east
  const json& cost = first["scores"]["best_run_path_cost"];
  EXPECT_EQ(cost["jobs"], 2);
  EXPECT_DOUBLE_EQ(cost["mean"].get<double>(), 15);
  EXPECT_DOUBLE_EQ(cost["best"].get<double>(), 15);
  EXPECT_DOUBLE_EQ(cost["worst"].get<double>(), 15);
  EXPECT_TRUE(results["summary"][1]["rank"].is_null());
  const std::string page = ReadTextFile(out + "/report.html");
  EXPECT_NE(page.find("data-key=\"scores.best_run_path_cost.mean\""), std::string::npos);
}

TEST(BatchCommandTest, MmsProgramsAreScoredOverTheMazesAsTheirOwnRunsScoreThem) {
  const std::string dir = FreshDirectory("batch_mms");
  const std::string manifest = WriteFile(dir, "mms.yaml",
                                         std::string(R"(
submissions:
  - {name: flood, mms: )") + UNIMOUSE_MMS_FLOODFILL +
                                             R"(}
  - {name: wall, mms: python3 left_wall.py, dir: )" +
                                             kSource + R"(/tests/mms/clients}
  - {name: quits, mms: "false"}
mazes: [japan2018, japan2019]
)");
  const std::string out = dir + "/out";
  const Outcome run = Unimouse("batch run " + manifest + " -j 2 --out " + out);
  ASSERT_EQ(run.exit_code, 1) << run.output;
  const json results = Results(out);
  ASSERT_EQ(results["jobs"].size(), 6u) << results.dump(1);
  for (const auto& job : results["jobs"]) {
    EXPECT_EQ(job["scenario"], "mms");
    const std::string submission = job["submission"];
    if (submission == "flood") {
      // the same program run by hand in the same maze
      const std::string own = dir + "/own";
      const Outcome direct = Unimouse("mms --maze " + job["maze"].get<std::string>() + " --out " +
                                      own + " -- " + UNIMOUSE_MMS_FLOODFILL);
      ASSERT_EQ(direct.exit_code, 0) << direct.output;
      const json result = json::parse(ReadTextFile(own + "/result.json"));
      EXPECT_EQ(job["status"], "passed") << job.dump();
      EXPECT_EQ(job["scores"]["score"], result["score"]) << job.dump();
      EXPECT_EQ(job["scores"]["moves"], result["moves"]) << job.dump();
      EXPECT_EQ(job["sim_time_s"], result["contest_time_s"]) << job.dump();
      // what the program displayed, one click away in the report
      ASSERT_EQ(job["pictures"].size(), 1u) << job.dump();
      EXPECT_TRUE(job["pictures"][0].get<std::string>().ends_with("/maze.png")) << job.dump();
    }
    if (submission == "wall") {
      // a left-hand wall follower never reaches a centre goal: 1200 moves of 0.5 s, and out
      EXPECT_EQ(job["status"], "failed") << job.dump();
      EXPECT_EQ(job["scores"]["score"], 2000) << job.dump();
    }
    if (submission == "quits") {
      EXPECT_EQ(job["status"], "firmware_error") << job.dump();
      EXPECT_NE(job["reason"].get<std::string>().find("exit"), std::string::npos) << job.dump();
    }
  }
}

// docs/batch.md "Replay pages": a job whose run left a recording has that run's page, which the
// results name and the report links by its path relative to the batch's folder
TEST(BatchCommandTest, EachRecordedJobHasItsReplayPageWhichTheResultsNameAndTheReportLinks) {
  const std::string dir = FreshDirectory("batch_replay");
  const std::string manifest = WriteFile(dir, "class.yaml",
                                         std::string(R"(
submissions:
  - name: good
    controller: )") + kSource + R"(/tests/batch/walking_mouse.lua
  - name: lost
    controller: )" + kSource + R"(/tests/scenarios/wandering_mouse.lua
  - {name: flood, mms: )" + UNIMOUSE_MMS_FLOODFILL +
                                             R"(}
scenarios:
  - scenario: micromouse
    set: {contest_s: 3, max_runs: 1}
mazes: [japan2018]
)");
  const std::string out = dir + "/out";
  const Outcome run = Unimouse("batch run " + manifest + " -j 2 --out " + out);
  ASSERT_EQ(run.exit_code, 1) << run.output;  // lost fails
  const json results = Results(out);
  ASSERT_EQ(results["jobs"].size(), 3u) << results.dump(1);
  const std::string report = ReadTextFile(out + "/report.html");
  const std::string csv = ReadTextFile(out + "/results.csv");
  EXPECT_NE(csv.find(",dir,replay_page\n"), std::string::npos) << csv;
  for (const auto& job : results["jobs"]) {
    const std::string job_dir = job["dir"];
    if (job["submission"] == "flood") {
      // `unimouse mms` without --physical records nothing: no page, no link
      EXPECT_FALSE(fs::exists(out + "/" + job_dir + "/run.mcap"));
      EXPECT_FALSE(fs::exists(out + "/" + job_dir + "/replay.html"));
      EXPECT_TRUE(job["replay_page"].is_null()) << job.dump();
      EXPECT_NE(csv.find("," + job_dir + ",\n"), std::string::npos) << csv;
      continue;
    }
    // passed or failed, the run's own page: the same as replay makes of its folder by hand
    EXPECT_EQ(job["replay_page"], job_dir + "/replay.html") << job.dump();
    const std::string page = out + "/" + job_dir + "/replay.html";
    ASSERT_TRUE(fs::exists(page)) << job.dump();
    const std::string by_hand = dir + "/" + job["submission"].get<std::string>() + ".html";
    const Outcome replay = Unimouse("replay " + out + "/" + job_dir + " --html " + by_hand);
    ASSERT_EQ(replay.exit_code, 0) << replay.output;
    EXPECT_TRUE(ReadTextFile(page) == ReadTextFile(by_hand)) << page;
    EXPECT_NE(csv.find("," + job_dir + "," + job_dir + "/replay.html\n"), std::string::npos) << csv;
    EXPECT_NE(report.find("<a class=\"replay\" href=\"" + job_dir + "/replay.html\">replay</a>"),
              std::string::npos)
        << job_dir;
  }
  size_t links = 0;
  for (size_t at = report.find(">replay</a>"); at != std::string::npos;
       at = report.find(">replay</a>", at + 1)) {
    ++links;
  }
  EXPECT_EQ(links, 2u);

  // a resumed batch keeps each job and its page
  const std::string good_page = out + "/jobs/good/micromouse/japan2018/seed-1/replay.html";
  const auto written = fs::last_write_time(good_page);
  const Outcome again = Unimouse("batch run " + manifest + " -j 2 --out " + out);
  EXPECT_NE(again.output.find("3 jobs, 0 to run"), std::string::npos) << again.output;
  EXPECT_EQ(fs::last_write_time(good_page), written);
  EXPECT_EQ(Results(out)["jobs"], results["jobs"]);
}

TEST(BatchCommandTest, TheSlurmArrayScriptRunsTheLinesOfThePlan) {
  const std::string dir = FreshDirectory("batch_slurm");
  const std::string manifest = WriteFile(dir, "class.yaml", ClassManifest());
  const std::string planned = dir + "/planned";
  ASSERT_EQ(Unimouse("batch plan " + manifest + " --out " + planned).exit_code, 0);
  const std::string script = planned + "/slurm-array.sh";
  EXPECT_EQ(std::system(("bash -n " + script).c_str()), 0);
  const std::string text = ReadTextFile(script);
  EXPECT_NE(text.find("\n#SBATCH --array=1-16\n"), std::string::npos) << text;

  // task 16 is the last line, the stuck submission's seed 2 in japan2019: it runs that job
  ASSERT_EQ(
      std::system(("SLURM_ARRAY_TASK_ID=16 bash " + script + " >/dev/null 2>&1").c_str()) >> 8, 1);
  const json job =
      json::parse(ReadTextFile(planned + "/jobs/stuck/micromouse/japan2019/seed-2/job.json"));
  EXPECT_EQ(job["status"], "timeout");
  EXPECT_EQ(std::system(("SLURM_ARRAY_TASK_ID=17 bash " + script + " 2>/dev/null").c_str()) >> 8,
            2);

  // the whole array on a real Slurm of one node, then collect: every job's status
  const int slurm = std::system((UNIMOUSE_SOURCE_DIR "/tests/support/slurm_one_node.sh " + script +
                                 " " + planned + " > " + planned + "/slurm.log 2>&1")
                                    .c_str()) >>
                    8;
  if (slurm == 77)
    GTEST_SKIP() << "no one-node Slurm here: " << ReadTextFile(planned + "/slurm.log");
  EXPECT_EQ(slurm, 1) << ReadTextFile(planned + "/slurm.log");  // the highest task's exit code
  EXPECT_EQ(Unimouse("batch collect " + planned).exit_code, 1);
  const std::map<std::string, std::string> expected = {
      {"good", "passed"}, {"lost", "failed"}, {"segfault", "crashed"}, {"stuck", "timeout"}};
  const json results = Results(planned);
  ASSERT_EQ(results["jobs"].size(), 16u);
  for (const auto& row : results["jobs"]) {
    EXPECT_EQ(row["status"], expected.at(row["submission"].get<std::string>())) << row.dump();
  }
}

TEST(BatchCommandTest, AManifestWithAMistakeIsBadInputWithFileLineAndColumn) {
  const std::string dir = FreshDirectory("batch_bad");
  const std::string manifest = WriteFile(dir, "bad.yaml", R"(submissions:
  - name: amy
    controler: amy.lua
scenarios: [micromouse]
)");
  for (const std::string command : {"run", "plan"}) {
    const Outcome o = Unimouse("batch " + command + " " + manifest + " --out " + dir + "/out");
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_NE(o.output.find(manifest + ":3:5: submission: unknown key 'controler' (did you mean "
                                       "'controller'?)"),
              std::string::npos)
        << o.output;
  }
  EXPECT_FALSE(fs::exists(dir + "/out/jobs"));
}

TEST(BatchCommandTest, AManifestWhoseAliasHoldsItselfIsBadInputWithFileLineAndColumn) {
  const std::string dir = FreshDirectory("batch_cycle");
  const std::string head =
      "submissions: [{name: amy, controller: amy.lua}]\n"
      "scenarios: [micromouse]\n";
  for (const std::string key : {"seeds", "jobs"}) {
    const std::string manifest = WriteFile(dir, key + ".yaml", head + key + ": {a: &b [*b]}\n");
    for (const std::string command : {"run", "plan"}) {
      const Outcome o = Unimouse("batch " + command + " " + manifest + " --out " + dir + "/out");
      EXPECT_EQ(o.exit_code, 2) << key << " " << command << ": " << o.output;
      EXPECT_NE(o.output.find(manifest + ":3:" + std::to_string(key.size() + 7) +
                              ": this list or map holds an alias of itself (a cycle)"),
                std::string::npos)
          << o.output;
    }
  }
  EXPECT_FALSE(fs::exists(dir + "/out/jobs"));
}

// whether any process's command line holds this text
bool ProcessWith(const std::string& text) {
  for (const auto& e : fs::directory_iterator("/proc")) {
    std::ifstream in(e.path() / "cmdline");
    const std::string cmdline((std::istreambuf_iterator<char>(in)), {});
    if (cmdline.find(text) != std::string::npos) return true;
  }
  return false;
}

// the flood reaches the file-size limit through the trace, which logs every line (the run's log
// stops showing them after 1 MiB)
TEST(BatchCommandTest, ASubmissionThatForksOrFloodsHarmsNoOtherJob) {
  for (const std::string sandbox : {"none", "auto"}) {
    const std::string dir = FreshDirectory("batch_untrusted_" + sandbox);
    const std::string marker = dir + "/left-behind";
    const std::string manifest = WriteFile(dir, "m.yaml",
                                           R"(
submissions:
  - name: good
    controller: )" + kSource + R"(/tests/batch/walking_mouse.lua
  - name: forker
    link: native:)" + UNIMOUSE_TEST_FIRMWARE + " --leave-behind " +
                                               marker + R"(
  - name: flooder
    controller: )" + kSource + R"(/tests/batch/chatty_controller.lua
scenarios:
  - scenario: micromouse
    set: {contest_s: 3, max_runs: 1}
trace: {period_s: 0.01}
limits: {wall_time_s: 60, file_size_mb: 1, sandbox: )" +
                                               sandbox + "}\n");
    const std::string out = dir + "/out";
    const Outcome o = Unimouse("batch run " + manifest + " -j 3 --out " + out);
    EXPECT_EQ(o.exit_code, 1) << o.output;
    const json jobs = Results(out)["jobs"];
    ASSERT_EQ(jobs.size(), 3u) << o.output;
    EXPECT_EQ(jobs[0]["submission"], "flooder");
    EXPECT_EQ(jobs[0]["status"], "crashed") << jobs[0].dump();
    EXPECT_EQ(jobs[0]["signal"], "SIGXFSZ");
    EXPECT_EQ(jobs[1]["submission"], "forker");
    EXPECT_EQ(jobs[1]["status"], "failed") << jobs[1].dump();  // it never reaches the goal
    EXPECT_EQ(jobs[2]["submission"], "good");
    EXPECT_EQ(jobs[2]["status"], "passed") << jobs[2].dump();
    // the process the forker left behind is gone with its job
    EXPECT_FALSE(ProcessWith(marker)) << sandbox;
    const bool sandboxed = jobs[1].contains("dir") &&
                           json::parse(ReadTextFile(out + "/" + jobs[1]["dir"].get<std::string>() +
                                                    "/job.json"))["sandbox"] == "bwrap";
    // in the sandbox nothing is written outside the job's directory
    if (sandboxed) {
      EXPECT_FALSE(fs::exists(marker));
    }
    for (const auto& e : fs::recursive_directory_iterator(out)) {
      if (e.is_regular_file()) {
        EXPECT_LE(e.file_size(), 1u << 20) << e.path();
      }
    }
  }
}

// bubblewrap installed but unable to make its sandbox (in a chroot: "Failed to make / slave"), as
// a stand-in that fails so: with sandbox auto the jobs run without it and job.json says why; with
// sandbox bwrap no job runs, and the batch's log says why in one line
TEST(BatchCommandTest, ABubblewrapThatCannotMakeItsSandboxIsSaidSoNotBlamedOnTheSubmission) {
  const std::string dir = FreshDirectory("batch_broken_bwrap");
  fs::create_directories(dir + "/bin");
  const std::string complaint = "bwrap: Failed to make / slave: Invalid argument";
  WriteFile(dir + "/bin", "bwrap", "#!/bin/sh\necho '" + complaint + "' >&2\nexit 1\n");
  fs::permissions(dir + "/bin/bwrap", fs::perms::owner_all);
  for (const std::string sandbox : {"auto", "bwrap"}) {
    const std::string manifest = WriteFile(dir, sandbox + ".yaml", R"(
submissions:
  - name: good
    controller: )" + kSource + R"(/tests/batch/walking_mouse.lua
scenarios:
  - scenario: micromouse
    set: {contest_s: 3, max_runs: 1}
limits: {sandbox: )" + sandbox + "}\n");
    const std::string out = dir + "/out-" + sandbox;
    const Outcome o =
        unimouse::testing::Shell("PATH=" + dir + "/bin:$PATH " + UNIMOUSE_BINARY + " batch run " +
                                 manifest + " -j 1 --out " + out + " 2>&1");
    if (sandbox == "auto") {
      ASSERT_EQ(o.exit_code, 0) << o.output;
      const json jobs = Results(out)["jobs"];
      ASSERT_EQ(jobs.size(), 1u);
      EXPECT_EQ(jobs[0]["status"], "passed") << jobs[0].dump();
      const json record =
          json::parse(ReadTextFile(out + "/" + jobs[0]["dir"].get<std::string>() + "/job.json"));
      EXPECT_EQ(record["sandbox"], "none");
      EXPECT_EQ(record["sandbox_problem"], complaint);
    } else {
      // as when bwrap is not installed: the job writes no record, and the batch's log says why
      EXPECT_EQ(o.exit_code, 3) << o.output;
      EXPECT_NE(o.output.find("no record (batch job exit code 2, see batch.log)"),
                std::string::npos)
          << o.output;
      EXPECT_NE(ReadTextFile(out + "/batch.log")
                    .find("submission 'good': sandbox: bwrap, but bwrap cannot make its sandbox "
                          "here: " +
                          complaint),
                std::string::npos);
    }
  }
}

TEST(BatchCommandTest, AnInterruptedBatchWritesWhatItHasAndAResumeFinishesIt) {
  const std::string dir = FreshDirectory("batch_interrupt");
  const std::string manifest = WriteFile(dir, "m.yaml", R"(
submissions:
  - name: good
    controller: )" + kSource + R"(/tests/batch/walking_mouse.lua
scenarios:
  - scenario: micromouse
    set: {contest_s: 3, max_runs: 1}
mazes: [japan2018, japan2019]
seeds: [1, 2, 3]
)");
  const std::string out = dir + "/out";
  const std::string log = dir + "/batch.txt";
  const std::vector<std::string> words = {UNIMOUSE_BINARY, "batch", "run", manifest, "-j", "1",
                                          "--out",         out};
  std::vector<char*> argv;
  for (const auto& w : words) argv.push_back(const_cast<char*>(w.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  // Ctrl-C once the first job is done
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(out + "/jobs/good/micromouse/japan2018/seed-1/job.json") &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << ReadTextFile(log);
  EXPECT_EQ(WEXITSTATUS(status), 3) << ReadTextFile(log);
  const size_t done = Results(out)["jobs"].size();
  EXPECT_GE(done, 1u);
  EXPECT_LT(done, 6u);
  EXPECT_EQ(JobRecordTimes(out).size(), done);  // the stopped job left no record

  const auto times = JobRecordTimes(out);
  const Outcome resumed = Unimouse("batch run " + manifest + " -j 1 --out " + out);
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find(std::to_string(done) + " already done"), std::string::npos)
      << resumed.output;
  EXPECT_EQ(Results(out)["jobs"].size(), 6u);
  for (const auto& [file, time] : times) EXPECT_EQ(fs::last_write_time(file), time) << file;
}

}  // namespace
