// SPDX-License-Identifier: GPL-3.0-or-later
#include "batch_report.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "run_program.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

using nlohmann::json;

// a batch of three jobs, two submissions
const json kResults = json::parse(R"({
  "unimouse_version": "0.9.0",
  "manifest": "class.yaml",
  "jobs": [
    {"id": "alice/micromouse/japan2018/seed-1", "submission": "alice", "scenario": "micromouse",
     "maze": "japan2018", "seed": 1, "status": "passed", "reason": "reached the goal",
     "scores": {"runs": 3, "time_used_s": 61.25}, "sim_time_s": 75.5, "wall_time_s": 12.5,
     "exit_code": 0, "dir": "jobs/alice/micromouse/japan2018/seed-1",
     "pictures": ["jobs/alice/micromouse/japan2018/seed-1/final.png",
                  "jobs/alice/micromouse/japan2018/seed-1/maze.png"]},
    {"id": "alice/micromouse/japan2018/seed-2", "submission": "alice", "scenario": "micromouse",
     "maze": "japan2018", "seed": 2, "status": "failed", "reason": "touched a wall at 3.2 s",
     "scores": {"runs": 0}, "sim_time_s": 3.2, "wall_time_s": 0.75, "exit_code": 1,
     "dir": "jobs/alice/micromouse/japan2018/seed-2", "pictures": []},
    {"id": "bob/micromouse/japan2018/seed-1", "submission": "bob", "scenario": "micromouse",
     "maze": "japan2018", "seed": 1, "status": "timeout", "reason": "no answer for 30 s",
     "scores": {}, "sim_time_s": null, "wall_time_s": 30.0, "exit_code": null,
     "dir": "jobs/bob/micromouse/japan2018/seed-1", "pictures": []}
  ],
  "summary": [
    {"submission": "alice", "jobs": 2, "passed": 1, "failed": 1,
     "best": {"id": "alice/micromouse/japan2018/seed-1", "time_used_s": 61.25},
     "mean_path_cost": 42.5},
    {"submission": "bob", "jobs": 1, "passed": 0, "timeout": 1, "best": null,
     "mean_path_cost": null}
  ]
})");

// the results with one job's reason replaced
json WithReason(const std::string& reason) {
  json results = kResults;
  results["jobs"][1]["reason"] = reason;
  return results;
}

size_t Occurrences(const std::string& text, const std::string& part) {
  size_t count = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) {
    ++count;
  }
  return count;
}

TEST(BatchReportTest, WritesOneRowPerJobWithItsIdAndStatus) {
  const std::string html = BatchReportHtml(kResults);
  EXPECT_EQ(Occurrences(html, "<tr id=\"job-"), 3u);
  EXPECT_NE(html.find("<tr id=\"job-0\" data-job=\"alice/micromouse/japan2018/seed-1\" "
                      "data-status=\"passed\">"),
            std::string::npos);
  EXPECT_NE(html.find("<span class=\"status status-timeout\">timeout</span>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"reason\">touched a wall at 3.2 s</td>"), std::string::npos);
}

TEST(BatchReportTest, SaysHowManyJobsEndedEachWay) {
  EXPECT_NE(BatchReportHtml(kResults).find("3 jobs: 1 passed, 1 failed, 1 timeout."),
            std::string::npos);
}

TEST(BatchReportTest, ShowsAReasonWithMarkupAsTextNotAsMarkup) {
  const std::string html = BatchReportHtml(
      WithReason("</td></tr><script>alert(\"x\")</script><img src=x onerror='y'>&"));
  EXPECT_NE(html.find("&lt;/td&gt;&lt;/tr&gt;&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt;"
                      "&lt;img src=x onerror=&#39;y&#39;&gt;&amp;</td>"),
            std::string::npos);

  // the page's own script is the only one, and the first job's two pictures the only images
  EXPECT_EQ(Occurrences(html, "<script"), 1u);
  EXPECT_EQ(Occurrences(html, "</script"), 1u);
  EXPECT_EQ(Occurrences(html, "<img"), 2u);
}

TEST(BatchReportTest, EscapesEveryTextTheResultsCarry) {
  const std::string hostile = "\" onmouseover=\"x\"'><script>y</script>";
  json results = kResults;
  results["manifest"] = results["unimouse_version"] = hostile;
  for (auto& job : results["jobs"]) {
    for (const char* key : {"id", "submission", "scenario", "maze", "status", "reason", "dir"}) {
      job[key] = hostile;
    }
    job["seed"] = hostile;
    job["scores"] = {{hostile, hostile}};
    job["pictures"] = {hostile};
  }
  results["summary"][0]["submission"] = hostile;
  results["summary"][0]["best"] = {{"id", hostile}, {hostile, hostile}};
  const std::string html = BatchReportHtml(results);
  EXPECT_EQ(Occurrences(html, "<script"), 1u);
  EXPECT_EQ(Occurrences(html, "onmouseover=\""), 0u);
  EXPECT_EQ(Occurrences(html, "'>"), 0u);
}

TEST(BatchReportTest, KeepsTheReplacementCharactersOfInvalidUtf8) {
  // upstream replaces bytes that are not UTF-8 with U+FFFD (EF BF BD)
  EXPECT_NE(BatchReportHtml(WithReason("sent \xEF\xBF\xBD\xEF\xBF\xBD then stopped"))
                .find("<td class=\"reason\">sent \xEF\xBF\xBD\xEF\xBF\xBD then stopped</td>"),
            std::string::npos);
}

TEST(BatchReportTest, GivesNumericCellsTheirNumberToSortBy) {
  const std::string html = BatchReportHtml(kResults);
  EXPECT_NE(html.find("<th data-key=\"wall_time_s\" data-type=\"number\""), std::string::npos);
  EXPECT_NE(html.find("<th data-key=\"seed\" data-type=\"number\""), std::string::npos);
  EXPECT_NE(html.find("<th data-key=\"reason\" title="), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\" data-value=\"12.5\">12.500</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\" data-value=\"0.75\">0.750</td>"), std::string::npos);

  // a missing number is an empty cell, which sorts after every number
  EXPECT_NE(html.find("<td class=\"num\" data-value=\"\"></td>"), std::string::npos);
}

TEST(BatchReportTest, GivesEachScoreNameAColumn) {
  const std::string html = BatchReportHtml(kResults);
  EXPECT_NE(html.find("<th data-key=\"scores.runs\" data-type=\"number\" title=\"sort by runs\">"
                      "runs</th><th data-key=\"scores.time_used_s\""),
            std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\" data-value=\"3\">3</td>"
                      "<td class=\"num\" data-value=\"61.25\">61.25</td>"),
            std::string::npos);
}

TEST(BatchReportTest, LinksEachJobsPicturesByTheirRelativePaths) {
  const std::string html = BatchReportHtml(kResults);
  EXPECT_NE(html.find("<details><summary>2 pictures</summary>"
                      "<a href=\"jobs/alice/micromouse/japan2018/seed-1/final.png\">"
                      "<img src=\"jobs/alice/micromouse/japan2018/seed-1/final.png\" "
                      "alt=\"final.png\" loading=\"lazy\">final.png</a>"),
            std::string::npos);
  EXPECT_NE(html.find("<a href=\"jobs/bob/micromouse/japan2018/seed-1/\">job folder</a>"),
            std::string::npos);
}

TEST(BatchReportTest, EncodesCharactersOfAPictureNameThatWouldEndItsPath) {
  json results = kResults;
  results["jobs"][1]["pictures"] = {"jobs/a b#1?:/final.png"};
  EXPECT_NE(BatchReportHtml(results).find("<a href=\"jobs/a%20b%231%3F%3A/final.png\">"),
            std::string::npos);
}

TEST(BatchReportTest, SummarisesEachSubmissionAndLinksItsBestRun) {
  const std::string html = BatchReportHtml(kResults);
  EXPECT_NE(html.find("<tr><td>alice</td><td class=\"num\" data-value=\"2\">2</td>"
                      "<td class=\"num\" data-value=\"1\">1</td>"
                      "<td class=\"num\" data-value=\"1\">1</td>"),
            std::string::npos);
  EXPECT_NE(html.find("<td><a href=\"#job-0\">alice/micromouse/japan2018/seed-1</a>; "
                      "time_used_s 61.25</td><td class=\"num\" data-value=\"42.5\">42.5</td>"),
            std::string::npos);
}

TEST(BatchReportTest, ShowsEachScoresMeanBestAndWorstAsNumbersAndTheRank) {
  const json results = json::parse(R"({
    "manifest": "class.yaml", "rank": {"score": "best_run_s", "better": "lower"},
    "jobs": [{"id": "amy/a/seed-1", "submission": "amy", "status": "passed",
              "scores": {"best_run_s": 4.25}}],
    "summary": [{"submission": "amy", "jobs": 1, "passed": 1, "rank": 1,
                 "best": {"id": "amy/a/seed-1", "scores": {"best_run_s": 4.25}},
                 "scores": {"best_run_s": {"jobs": 1, "mean": 4.25, "best": 4.25,
                                           "worst": 4.25}}}]})");
  const std::string page = BatchReportHtml(results);
  for (const char* what : {"mean", "best", "worst"}) {
    EXPECT_NE(page.find(std::string("data-key=\"scores.best_run_s.") + what + "\""),
              std::string::npos)
        << what;
  }
  EXPECT_NE(page.find("<td class=\"num\" data-value=\"4.25\">4.25</td>"), std::string::npos);
  EXPECT_NE(page.find("data-key=\"rank\""), std::string::npos);
  EXPECT_NE(page.find("Ranked by the best best_run_s (lower is better)"), std::string::npos);
  // the best run's scores as numbers, not as the JSON they are kept in
  EXPECT_NE(page.find("best_run_s 4.25</td>"), std::string::npos) << page;
  EXPECT_EQ(page.find("{&quot;"), std::string::npos);
  EXPECT_EQ(page.find("{\""), std::string::npos);
}

TEST(BatchReportTest, ShowsMissingFieldsAsEmptyCells) {
  const std::string html = BatchReportHtml(json::parse(R"({"jobs": [{"id": "x"}]})"));
  EXPECT_EQ(Occurrences(html, "<tr id=\"job-"), 1u);
  EXPECT_NE(html.find("<span class=\"status status-other\"></span>"), std::string::npos);
}

TEST(BatchReportTest, KeepsItsFilterControlsHiddenUntilItsScriptRuns) {
  EXPECT_NE(BatchReportHtml(kResults).find("<div id=\"controls\" hidden>"), std::string::npos);
}

TEST(BatchReportTest, WritesTheWholePageAndNoOtherFile) {
  const std::filesystem::path dir = testing::FreshDirectory("report");
  WriteTextFile((dir / "report.html").string(), "an older report");
  WriteBatchReport(kResults, dir / "report.html");
  EXPECT_EQ(ReadTextFile((dir / "report.html").string()), BatchReportHtml(kResults));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(BatchReportTest, ThrowsInputErrorWhenThePageCannotBeWritten) {
  const std::filesystem::path dir = testing::FreshDirectory("report");
  EXPECT_THROW(WriteBatchReport(kResults, dir / "missing" / "report.html"), InputError);
}

}  // namespace
}  // namespace unimouse
