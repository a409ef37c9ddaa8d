// SPDX-License-Identifier: GPL-3.0-or-later
// How a job's ending becomes its status: what the job saw of the run process, the run's exit
// code and its result.json; and how its replay page is made without touching that status.
#include "job_runner.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "manifest.h"
#include "run_program.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse::batch {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

ProcessEnd Exited(int code) { return {false, code, 0}; }

TEST(ClassifyJobTest, ExitCodesAndTheScenarioGiveStatusAndReason) {
  const JobLimits limits;
  const json passed = {{"exit_code", 0}, {"scenario", {{"reason", "1 run, best 1.4 s"}}}};
  EXPECT_EQ(ClassifyJob(Exited(0), passed, limits).status, "passed");
  const json failed = {{"exit_code", 1}, {"scenario", {{"reason", "no run reached the goal"}}}};
  const JobOutcome f = ClassifyJob(Exited(1), failed, limits);
  EXPECT_EQ(f.status, "failed");
  EXPECT_EQ(f.reason, "no run reached the goal");
  const JobOutcome bad = ClassifyJob(Exited(2), {{"error", "fw: no such program"}}, limits);
  EXPECT_EQ(bad.status, "bad_input");
  EXPECT_EQ(bad.reason, "fw: no such program");
}

TEST(ClassifyJobTest, AFaultIsTheFirmwaresWhenAComponentFailedElseTheScripts) {
  const JobLimits limits;
  EXPECT_EQ(ClassifyJob(Exited(3),
                        {{"error",
                          "component 'link' failed at t=0 s: the firmware did not ask "
                          "for lock-step"}},
                        limits)
                .status,
            "firmware_error");
  EXPECT_EQ(
      ClassifyJob(Exited(3), {{"error", "x.lua:12: attempt to index a nil value"}}, limits).status,
      "script_error");
  const JobOutcome crash = ClassifyJob(
      Exited(3), {{"error", "component 'link' failed at t=0.2 s: the firmware crashed: SIGSEGV"}},
      limits);
  EXPECT_EQ(crash.status, "crashed");
  // killed from outside the batch: not the script's fault
  const JobOutcome stopped = ClassifyJob(
      Exited(3), {{"status", "interrupted"}, {"error", "interrupted by SIGTERM at 3.200 s"}},
      limits);
  EXPECT_EQ(stopped.status, "crashed");
  EXPECT_EQ(stopped.reason, "interrupted by SIGTERM at 3.200 s");
}

// `unimouse mms` writes its reason and status at the top (docs/mms.md)
TEST(ClassifyJobTest, AnMmsRunIsClassifiedFromItsOwnStatusAndReason) {
  const JobLimits limits;
  const auto mms = [](const std::string& status) {
    return json{{"command", "mms"}, {"status", status}, {"reason", "why: " + status}};
  };
  const JobOutcome goal = ClassifyJob(Exited(0), mms("goal_reached"), limits);
  EXPECT_EQ(goal.status, "passed");
  EXPECT_EQ(goal.reason, "why: goal_reached");
  EXPECT_EQ(ClassifyJob(Exited(1), mms("time_out"), limits).status, "failed");
  EXPECT_EQ(ClassifyJob(Exited(2), mms("error"), limits).reason, "why: error");
  EXPECT_EQ(ClassifyJob(Exited(3), mms("program_crashed"), limits).status, "crashed");
  EXPECT_EQ(ClassifyJob(Exited(3), mms("interrupted"), limits).status, "crashed");
  EXPECT_EQ(ClassifyJob(Exited(3), mms("program_hang"), limits).status, "firmware_error");
  EXPECT_EQ(ClassifyJob(Exited(3), mms("program_exited"), limits).status, "firmware_error");
}

TEST(ClassifyJobTest, WhatTheJobSawWinsOverAnyResult) {
  JobLimits limits;
  limits.wall_time_s = 2;
  limits.file_size_mb = 1;
  const json passed = {{"exit_code", 0}};
  const JobOutcome timeout = ClassifyJob({true, -1, SIGKILL}, passed, limits);
  EXPECT_EQ(timeout.status, "timeout");
  EXPECT_EQ(timeout.reason, "still running after the wall-time limit of 2 s");
  const JobOutcome segv = ClassifyJob({false, -1, SIGSEGV}, nullptr, limits);
  EXPECT_EQ(segv.status, "crashed");
  EXPECT_EQ(segv.reason, "killed by SIGSEGV");
  EXPECT_EQ(ClassifyJob({false, -1, SIGXFSZ}, nullptr, limits).reason,
            "killed by SIGXFSZ (wrote past the file size limit of 1 MB)");
  EXPECT_EQ(ClassifyJob(Exited(0), nullptr, limits).reason,
            "the run ended with exit code 0 and wrote no result.json");
}

TEST(ClassifyJobTest, SignalsAreNamedAsInC) {
  EXPECT_EQ(SignalName(SIGSEGV), "SIGSEGV");
  EXPECT_EQ(SignalName(SIGXCPU), "SIGXCPU");
}

// A job run by RunJob with a stand-in for unimouse: a shell script whose `run` passes and
// leaves a recording or none, and whose `replay` does what the test says.
class JobReplayTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::FreshDirectory("job_replay");
    manifest_ = dir_ + "/class.yaml";
    std::ofstream(manifest_) << "submissions:\n  - name: amy\n    controller: " UNIMOUSE_SOURCE_DIR
                                "/tests/batch/walking_mouse.lua\n"
                                "scenarios: [micromouse]\n"
                                "mazes: [japan2018]\n"
                                "limits: {wall_time_s: 2, sandbox: none}\n";
  }

  // the stand-in's result.json is not unimouse's: kept out of the result records the suite
  // checks against the schema (result_records.h)
  void TearDown() override {
    std::error_code ignored;
    fs::remove(JobDir() + "/result.json", ignored);
  }

  // runs the one job with a program whose `run` leaves a run.mcap when asked and whose
  // `replay` runs this shell text; returns RunJob's exit code and the job's job.json
  json Job(bool recording, const std::string& replay, int* exit_code = nullptr) {
    const std::string program = dir_ + "/unimouse";
    // run: `run --out DIR ...`; replay: `replay DIR --html PAGE`
    std::ofstream(program) << "#!/bin/sh\n"
                              "if [ \"$1\" = run ]; then\n"
                              "  echo '{\"exit_code\": 0, \"scenario\": {\"reason\": \"ok\"}}' "
                              "> \"$3/result.json\"\n"
                           << (recording ? "  echo recorded > \"$3/run.mcap\"\n" : "")
                           << "  exit 0\nfi\n"
                           << replay << "\n";
    ::chmod(program.c_str(), 0755);
    const Manifest m = LoadManifest(manifest_);
    // in a child: RunJob makes its process the subreaper of the run and catches SIGTERM
    const pid_t pid = ::fork();
    if (pid == 0) {
      int code = 100;
      try {
        code = RunJob(m, m.jobs.front(), dir_ + "/out", program, "9.9.9");
      } catch (...) {
      }
      ::_exit(code);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (exit_code != nullptr) *exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return json::parse(ReadTextFile(JobDir() + "/job.json"));
  }

  std::string JobDir() { return dir_ + "/out/jobs/amy/micromouse/japan2018/seed-1"; }

  std::string dir_, manifest_;
};

TEST_F(JobReplayTest, ARecordingBecomesTheJobsReplayPageNamedInItsRecord) {
  int exit_code = -1;
  const json job =
      Job(true, "[ \"$1 $2 $3\" = \"replay $(dirname \"$4\") --html\" ] && echo page > \"$4\"",
          &exit_code);
  EXPECT_EQ(exit_code, kExitPassed);
  EXPECT_EQ(job["status"], "passed") << job;
  EXPECT_EQ(job["replay_page"], "replay.html") << job;
  EXPECT_TRUE(job["replay_error"].is_null()) << job;
  EXPECT_EQ(ReadTextFile(JobDir() + "/replay.html"), "page\n");
}

TEST_F(JobReplayTest, AReplayThatFailsIsNotedAndLeavesTheJobsStatus) {
  int exit_code = -1;
  json job = Job(true, "echo half > \"$4\"; echo 'not a recording' >&2; exit 2", &exit_code);
  EXPECT_EQ(exit_code, kExitPassed);
  EXPECT_EQ(job["status"], "passed") << job;
  EXPECT_TRUE(job["replay_page"].is_null()) << job;
  EXPECT_EQ(job["replay_error"], "ended with exit code 2 (see replay.log)") << job;
  EXPECT_FALSE(fs::exists(JobDir() + "/replay.html"));
  EXPECT_EQ(ReadTextFile(JobDir() + "/replay.log"), "not a recording\n");

  // one that never ends is stopped at the job's wall-time limit, here under the replay's own
  job = Job(true, "exec sleep 60", &exit_code);
  EXPECT_EQ(exit_code, kExitPassed);
  EXPECT_EQ(job["status"], "passed") << job;
  EXPECT_TRUE(job["replay_page"].is_null()) << job;
  EXPECT_EQ(job["replay_error"], "still running after the replay's wall-time limit of 2 s") << job;
  EXPECT_LT(job["wall_time_s"].get<double>(), 2);  // the run's time alone
}

TEST_F(JobReplayTest, ARunWithoutARecordingHasNoPageNotEvenAnEarlierOne) {
  // an earlier run's recording and page in the job's directory
  fs::create_directories(JobDir());
  std::ofstream(JobDir() + "/run.mcap") << "earlier";
  std::ofstream(JobDir() + "/replay.html") << "earlier";
  const json job = Job(false, "echo page > \"$4\"");
  EXPECT_EQ(job["status"], "passed") << job;
  EXPECT_TRUE(job["replay_page"].is_null()) << job;
  EXPECT_TRUE(job["replay_error"].is_null()) << job;
  EXPECT_FALSE(fs::exists(JobDir() + "/replay.html"));
  EXPECT_FALSE(fs::exists(JobDir() + "/replay.log"));
}

}  // namespace
}  // namespace unimouse::batch
