// SPDX-License-Identifier: GPL-3.0-or-later
// A batch's result files from job records written by hand.
#include "batch_results.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "run_program.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse::batch {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

class BatchResultsTest : public ::testing::Test {
 protected:
  void SetUp() override { out_ = testing::FreshDirectory("results"); }

  // a job directory under out/jobs with this job.json and a picture
  std::string Job(const json& record) {
    const fs::path dir = fs::path(out_) / "jobs" / record["id"].get<std::string>();
    fs::create_directories(dir);
    std::ofstream(dir / "job.json") << record.dump();
    std::ofstream(dir / "final.png") << "png";
    return dir.string();
  }

  std::string out_;
};

json Record(const std::string& id, const std::string& status, const json& scores,
            double sim_time_s) {
  const size_t slash = id.find('/');
  return {{"id", id},
          {"submission", id.substr(0, slash)},
          {"scenario", "micromouse"},
          {"maze", "japan2018"},
          {"seed", 1},
          {"status", status},
          {"reason", status == "passed" ? "ok" : "went \"wrong\", twice"},
          {"scores", scores},
          {"sim_time_s", sim_time_s},
          {"wall_time_s", 0.5},
          {"exit_code", status == "passed" ? 0 : 1},
          {"manifest", "/m.yaml"}};
}

TEST_F(BatchResultsTest, RowsAreSortedByIdWithPathsRelativeToTheOutput) {
  const std::vector<std::string> dirs = {
      Job(Record("bo/micromouse/japan2018/seed-1", "failed", json::object(), 4)),
      Job(Record("amy/micromouse/japan2018/seed-1", "passed", {{"best_run_s", 2}}, 3))};
  const json rows = JobRows(dirs, out_);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0]["id"], "amy/micromouse/japan2018/seed-1");
  EXPECT_EQ(rows[0]["dir"], "jobs/amy/micromouse/japan2018/seed-1");
  EXPECT_EQ(rows[0]["pictures"], json({"jobs/amy/micromouse/japan2018/seed-1/final.png"}));
  EXPECT_EQ(FindJobDirectories(out_).size(), 2u);
  EXPECT_THROW(JobRows({dirs[0], dirs[0]}, out_), InputError);
}

TEST_F(BatchResultsTest, TheSummaryCountsStatusesAndPicksTheFastestPassedRun) {
  const json rows = JobRows({Job(Record("amy/micromouse/a/seed-1", "passed",
                                        {{"best_run_s", 5.0}, {"best_run_path_cost", 20}}, 9)),
                             Job(Record("amy/micromouse/b/seed-1", "passed",
                                        {{"best_run_s", 4.0}, {"best_run_path_cost", 15}}, 9)),
                             Job(Record("amy/micromouse/c/seed-1", "timeout", json::object(), 1))},
                            out_);
  const json summary = Summarize(rows);
  ASSERT_EQ(summary.size(), 1u);
  EXPECT_EQ(summary[0]["jobs"], 3);
  EXPECT_EQ(summary[0]["passed"], 2);
  EXPECT_EQ(summary[0]["timeout"], 1);
  EXPECT_EQ(summary[0]["failed"], 0);
  EXPECT_EQ(summary[0]["best"]["id"], "amy/micromouse/b/seed-1");
  EXPECT_DOUBLE_EQ(summary[0]["mean_path_cost"].get<double>(), 17.5);  // (20 + 15) / 2
}

TEST_F(BatchResultsTest, TheSummaryAggregatesEveryScoreAndRanksByTheDeclaredOne) {
  const json rows = JobRows(
      {Job(Record("amy/micromouse/a/seed-1", "passed", {{"best_run_s", 5.0}, {"laps", 2}}, 9)),
       Job(Record("amy/micromouse/b/seed-1", "passed", {{"best_run_s", 4.0}, {"laps", 3}}, 9)),
       Job(Record("amy/micromouse/c/seed-1", "failed", {{"best_run_s", 9.0}, {"laps", 1}}, 9)),
       Job(Record("bo/micromouse/a/seed-1", "passed", {{"best_run_s", 3.5}, {"laps", 1}}, 9)),
       Job(Record("cy/micromouse/a/seed-1", "failed", {{"laps", 0}}, 9))},
      out_);
  const json summary = Summarize(rows, {"best_run_s", {"laps"}});
  ASSERT_EQ(summary.size(), 3u);
  // ranked by each one's best best_run_s, lower better: bo 3.5, amy 4.0, cy none
  EXPECT_EQ(summary[0]["submission"], "bo");
  EXPECT_EQ(summary[0]["rank"], 1);
  EXPECT_EQ(summary[1]["submission"], "amy");
  EXPECT_EQ(summary[1]["rank"], 2);
  EXPECT_EQ(summary[2]["submission"], "cy");
  EXPECT_TRUE(summary[2]["rank"].is_null());
  // amy's three jobs: best_run_s 5, 4, 9 and laps 2, 3, 1 (laps: higher is better)
  const json& amy = summary[1]["scores"];
  EXPECT_EQ(amy["best_run_s"]["jobs"], 3);
  EXPECT_DOUBLE_EQ(amy["best_run_s"]["mean"].get<double>(), 6.0);
  EXPECT_DOUBLE_EQ(amy["best_run_s"]["best"].get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(amy["best_run_s"]["worst"].get<double>(), 9.0);
  EXPECT_DOUBLE_EQ(amy["laps"]["mean"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(amy["laps"]["best"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(amy["laps"]["worst"].get<double>(), 1.0);
}

// a page is named only when its job.json names one and it is in the job's directory
TEST_F(BatchResultsTest, ARowNamesTheJobsReplayPageOnlyWhenItIsThere) {
  json with_page = Record("amy/micromouse/japan2018/seed-1", "passed", json::object(), 1);
  with_page["replay_page"] = "replay.html";
  const std::string amy = Job(with_page);
  std::ofstream(amy + "/replay.html") << "<!DOCTYPE html>";
  json gone = Record("bo/micromouse/japan2018/seed-1", "passed", json::object(), 1);
  gone["replay_page"] = "replay.html";  // named, but not written
  json outside = Record("cy/micromouse/japan2018/seed-1", "passed", json::object(), 1);
  outside["replay_page"] = "../../../../../results.json";
  std::ofstream(out_ + "/results.json") << "{}";
  const json none = Record("dee/micromouse/japan2018/seed-1", "passed", json::object(), 1);
  const json rows = JobRows({amy, Job(gone), Job(outside), Job(none)}, out_);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0]["replay_page"], "jobs/amy/micromouse/japan2018/seed-1/replay.html");
  EXPECT_TRUE(rows[1]["replay_page"].is_null()) << rows[1];
  EXPECT_TRUE(rows[2]["replay_page"].is_null()) << rows[2];
  EXPECT_TRUE(rows[3]["replay_page"].is_null()) << rows[3];
}

TEST_F(BatchResultsTest, TheFilesSayTheSameAsTheRows) {
  json with_page =
      Record("amy/micromouse/japan2018/seed-1", "passed", {{"best_run_s", 1.4}, {"runs", 1}}, 1.5);
  with_page["replay_page"] = "replay.html";
  const std::string amy = Job(with_page);
  std::ofstream(amy + "/replay.html") << "<!DOCTYPE html>";
  const json rows = JobRows(
      {amy, Job(Record("bo/micromouse/japan2018/seed-1", "failed", {{"runs", 0}}, 4))}, out_);
  WriteResults(out_, rows, "/m.yaml", "9.9.9");
  EXPECT_EQ(ReadTextFile(out_ + "/results.csv"),
            "submission,scenario,maze,seed,status,reason,score.best_run_s,score.runs,sim_time_s,"
            "wall_time_s,exit_code,dir,replay_page\n"
            "amy,micromouse,japan2018,1,passed,ok,1.4,1,1.500,0.500,0,"
            "jobs/amy/micromouse/japan2018/seed-1,jobs/amy/micromouse/japan2018/seed-1/"
            "replay.html\n"
            "bo,micromouse,japan2018,1,failed,\"went \"\"wrong\"\", twice\",,0,4.000,0.500,1,"
            "jobs/bo/micromouse/japan2018/seed-1,\n");
  EXPECT_EQ(ReadTextFile(out_ + "/summary.csv"),
            "submission,jobs,passed,failed,firmware_error,script_error,bad_input,timeout,crashed,"
            "best_job,best_run_s,mean_path_cost\n"
            "amy,1,1,0,0,0,0,0,0,amy/micromouse/japan2018/seed-1,1.400,\n"
            "bo,1,0,1,0,0,0,0,0,,,\n");
  const json results = json::parse(ReadTextFile(out_ + "/results.json"));
  EXPECT_EQ(results["unimouse_version"], "9.9.9");
  EXPECT_EQ(results["manifest"], "/m.yaml");
  EXPECT_EQ(results["jobs"], rows);
  const std::string junit = ReadTextFile(out_ + "/junit.xml");
  EXPECT_NE(junit.find("<testsuites name=\"unimouse batch\" tests=\"2\" failures=\"1\" "
                       "errors=\"0\">"),
            std::string::npos)
      << junit;
  EXPECT_NE(junit.find("<testcase classname=\"amy.micromouse\" name=\"micromouse/japan2018/"
                       "seed-1\" time=\"0.500\"/>"),
            std::string::npos)
      << junit;
  EXPECT_NE(junit.find("<failure type=\"failed\" message=\"went &quot;wrong&quot;, twice\">"),
            std::string::npos)
      << junit;
}

}  // namespace
}  // namespace unimouse::batch
