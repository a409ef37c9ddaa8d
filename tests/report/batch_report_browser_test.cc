// SPDX-License-Identifier: GPL-3.0-or-later
// The batch report as a teacher sees it: loaded from a file into headless Chromium (Debian's
// `chromium`), its scripts run, and the rendered DOM read back with --dump-dom.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "batch_report.h"
#include "headless_chromium.h"
#include "run_program.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// one job per status, in id order; their wall times sort one way as numbers and another as text,
// and one has none; two have a replay page, one of them in a folder whose name is markup
const json kResults = json::parse(R"({
  "unimouse_version": "0.9.0", "manifest": "class.yaml",
  "jobs": [
    {"id": "a/seed-1", "submission": "a", "seed": 1, "status": "passed", "wall_time_s": 9.5,
     "dir": "jobs/a/seed-1", "replay_page": "jobs/a/seed-1/replay.html"},
    {"id": "b/seed-1", "submission": "b", "seed": 1, "status": "failed", "wall_time_s": 100,
     "reason": "</td></tr></table><script>document.title='owned'</script><img src=x onerror=\"document.title='owned'\">"},
    {"id": "c/seed-1", "submission": "c", "seed": 1, "status": "firmware_error", "wall_time_s": 2,
     "replay_page": "jobs/c\"><b>x</b>/replay.html"},
    {"id": "d/seed-1", "submission": "d", "seed": 1, "status": "script_error", "wall_time_s": null},
    {"id": "e/seed-1", "submission": "e", "seed": 1, "status": "bad_input", "wall_time_s": 10.25},
    {"id": "f/seed-1", "submission": "f", "seed": 1, "status": "timeout", "wall_time_s": 30},
    {"id": "g/seed-1", "submission": "g", "seed": 1, "status": "crashed", "wall_time_s": 0.5}
  ],
  "summary": []
})");

class BatchReportBrowserTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string program = testing::FindProgram("chromium");
    if (program.empty()) GTEST_SKIP() << "no chromium on PATH (Debian: apt-get install chromium)";
    dir_ = testing::FreshDirectory("report");
    chromium_.emplace(program, dir_ / "chromium-profile");
    WriteBatchReport(kResults, dir_ / "report.html");
  }

  // the page's DOM after its scripts ran, opened at `fragment`
  std::string RenderedDom(const std::string& fragment) {
    return chromium_->Dom("file://" + (dir_ / "report.html").string() + "#" + fragment);
  }

  std::optional<testing::HeadlessChromium> chromium_;
  fs::path dir_;
};

// the ids of the job rows in the order the DOM has them
std::vector<std::string> RowOrder(const std::string& dom) {
  std::vector<std::string> ids;
  const std::string marker = "data-job=\"";
  for (size_t at = dom.find(marker); at != std::string::npos; at = dom.find(marker, at + 1)) {
    const size_t start = at + marker.size();
    ids.push_back(dom.substr(start, dom.find('"', start) - start));
  }
  return ids;
}

TEST_F(BatchReportBrowserTest, ShowsEveryJobsRowWithItsStatus) {
  const std::string dom = RenderedDom("");
  EXPECT_EQ(RowOrder(dom), (std::vector<std::string>{"a/seed-1", "b/seed-1", "c/seed-1", "d/seed-1",
                                                     "e/seed-1", "f/seed-1", "g/seed-1"}));
  for (const char* status :
       {"passed", "failed", "firmware_error", "script_error", "bad_input", "timeout", "crashed"}) {
    EXPECT_NE(
        dom.find(std::string("<span class=\"status status-") + status + "\">" + status + "</span>"),
        std::string::npos)
        << status;
  }

  // its script ran: the controls show, and count the rows
  EXPECT_NE(dom.find("<div id=\"controls\">"), std::string::npos);
  EXPECT_NE(dom.find("<span id=\"shown\">7 of 7 jobs shown</span>"), std::string::npos);
}

TEST_F(BatchReportBrowserTest, ShowsAReasonWithMarkupAsText) {
  const std::string dom = RenderedDom("");
  EXPECT_NE(dom.find("<td class=\"reason\">&lt;/td&gt;&lt;/tr&gt;&lt;/table&gt;&lt;script&gt;"
                     "document.title='owned'&lt;/script&gt;&lt;img src=x onerror=\""
                     "document.title='owned'\"&gt;</td>"),
            std::string::npos);
  EXPECT_NE(dom.find("<title>Batch report: class.yaml</title>"), std::string::npos);
  EXPECT_EQ(dom.find("<img src=\"x\""), std::string::npos);
}

TEST_F(BatchReportBrowserTest, SortsByAColumnsNumbersWhenItsHeaderIsClicked) {
  const std::string dom = RenderedDom("sort=wall_time_s");
  EXPECT_EQ(RowOrder(dom), (std::vector<std::string>{"g/seed-1", "c/seed-1", "a/seed-1", "e/seed-1",
                                                     "f/seed-1", "b/seed-1", "d/seed-1"}));
  EXPECT_NE(dom.find("data-key=\"wall_time_s\" data-type=\"number\" title=\"sort by Wall time "
                     "(s)\" aria-sort=\"ascending\""),
            std::string::npos);
}

TEST_F(BatchReportBrowserTest, SortsDescendingWhenItsHeaderIsClickedTwice) {
  const std::string dom = RenderedDom("sort=-wall_time_s");

  // a job without a wall time comes last either way
  EXPECT_EQ(RowOrder(dom), (std::vector<std::string>{"b/seed-1", "f/seed-1", "e/seed-1", "a/seed-1",
                                                     "c/seed-1", "g/seed-1", "d/seed-1"}));
  EXPECT_NE(dom.find("aria-sort=\"descending\""), std::string::npos);
}

TEST_F(BatchReportBrowserTest, SortsTheSubmissionsByAScoreFromTheAddress) {
  json results = kResults;
  results["summary"] = json::parse(R"([
    {"submission": "a", "jobs": 1, "scores": {"best_run_s": {"jobs": 1, "mean": 9, "best": 9, "worst": 9}}},
    {"submission": "b", "jobs": 1, "scores": {"best_run_s": {"jobs": 1, "mean": 10, "best": 10, "worst": 10}}},
    {"submission": "c", "jobs": 1, "scores": {"best_run_s": {"jobs": 1, "mean": 2, "best": 2, "worst": 2}}}])");
  WriteBatchReport(results, dir_ / "report.html");
  const std::string dom = RenderedDom("summary=-scores.best_run_s.best");
  const size_t summary = dom.find("id=\"summary\"");
  ASSERT_NE(summary, std::string::npos);
  const size_t b = dom.find("<td>b</td>", summary), a = dom.find("<td>a</td>", summary),
               c = dom.find("<td>c</td>", summary);
  EXPECT_LT(b, a);
  EXPECT_LT(a, c);
}

// a page in a 1280 px wide window, measured by a page beside it that holds it in a frame
TEST_F(BatchReportBrowserTest, FitsAWindow1280PixelsWideWhateverItsColumns) {
  json results = kResults;
  for (auto& job : results["jobs"]) {
    for (int i = 0; i < 12; ++i) job["scores"]["a_long_score_name_number_" + std::to_string(i)] = i;
    job["reason"] = std::string(300, 'x');
  }
  WriteBatchReport(results, dir_ / "report.html");
  std::ofstream(dir_ / "measure.html")
      << "<!DOCTYPE html><html><body style=\"margin:0\"><iframe id=\"page\" src=\"report.html\" "
         "style=\"width:1280px;height:800px;border:0\"></iframe><script>"
         "document.getElementById('page').onload = function () {"
         "  var d = this.contentDocument.documentElement;"
         "  document.body.setAttribute('data-width', String(d.scrollWidth));"
         "};</script></body></html>";
  const testing::Outcome chromium =
      chromium_->Run("--allow-file-access-from-files --virtual-time-budget=5000 --dump-dom",
                     "file://" + (dir_ / "measure.html").string());
  const std::string marker = "data-width=\"";
  const size_t at = chromium.output.find(marker);
  ASSERT_NE(at, std::string::npos) << chromium.output;
  EXPECT_LE(std::stoi(chromium.output.substr(at + marker.size())), 1280) << chromium.output;
}

// the job row of this id as the DOM has it, from its <tr> to its </tr>
std::string Row(const std::string& dom, const std::string& id) {
  const size_t start = dom.find("data-job=\"" + id + "\"");
  if (start == std::string::npos) return "";
  return dom.substr(start, dom.find("</tr>", start) - start);
}

TEST_F(BatchReportBrowserTest, LinksAJobsReplayPageByItsRelativePathAndNothingWithoutOne) {
  const std::string dom = RenderedDom("");
  EXPECT_NE(Row(dom, "a/seed-1")
                .find("<a class=\"replay\" href=\"jobs/a/seed-1/replay.html\">replay</a>"),
            std::string::npos)
      << Row(dom, "a/seed-1");
  // a folder's name is an address, never markup
  EXPECT_NE(Row(dom, "c/seed-1")
                .find("<a class=\"replay\" href=\"jobs/c%22%3E%3Cb%3Ex%3C/b%3E/replay.html\">"
                      "replay</a>"),
            std::string::npos)
      << Row(dom, "c/seed-1");
  EXPECT_EQ(dom.find("<b>x</b>"), std::string::npos);
  for (const char* id : {"b/seed-1", "d/seed-1", "e/seed-1", "f/seed-1", "g/seed-1"}) {
    ASSERT_FALSE(Row(dom, id).empty()) << id;
    EXPECT_EQ(Row(dom, id).find(">replay</a>"), std::string::npos) << Row(dom, id);
  }
}

// the page's Content-Security-Policy lets a click on the link open the replay page: a page
// beside it holds the report in a frame, clicks the link and reads the title of what it shows
TEST_F(BatchReportBrowserTest, AClickOnAReplayLinkOpensThatPage) {
  fs::create_directories(dir_ / "jobs/a/seed-1");
  std::ofstream(dir_ / "jobs/a/seed-1/replay.html")
      << "<!DOCTYPE html><html><head><title>the replay of a</title></head></html>";
  std::ofstream(dir_ / "click.html")
      << "<!DOCTYPE html><html><body><iframe id=\"page\" src=\"report.html\"></iframe><script>"
         "document.getElementById('page').onload = function () {"
         "  var d = this.contentDocument;"
         "  var link = d.querySelector('tr[data-job=\"a/seed-1\"] a.replay');"
         "  if (link) { link.click(); return; }"
         "  document.body.setAttribute('data-shown', d.title);"
         "};</script></body></html>";
  const testing::Outcome chromium =
      chromium_->Run("--allow-file-access-from-files --virtual-time-budget=5000 --dump-dom",
                     "file://" + (dir_ / "click.html").string());
  EXPECT_NE(chromium.output.find("data-shown=\"the replay of a\""), std::string::npos)
      << chromium.output;
}

TEST_F(BatchReportBrowserTest, HidesTheJobsOfOtherStatusesWhenFiltered) {
  const std::string dom = RenderedDom("status=failed");
  EXPECT_NE(dom.find("data-job=\"b/seed-1\" data-status=\"failed\">"), std::string::npos);
  EXPECT_NE(dom.find("data-job=\"a/seed-1\" data-status=\"passed\" hidden=\"\">"),
            std::string::npos);
  EXPECT_NE(dom.find("<span id=\"shown\">1 of 7 jobs shown</span>"), std::string::npos);
}

}  // namespace
}  // namespace unimouse
