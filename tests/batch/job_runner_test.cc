// SPDX-License-Identifier: GPL-3.0-or-later
// How a job's ending becomes its status: what the job saw of the run process, the run's exit
// code and its result.json.
#include "job_runner.h"

#include <gtest/gtest.h>

#include <csignal>

namespace unimouse::batch {
namespace {

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

}  // namespace
}  // namespace unimouse::batch
