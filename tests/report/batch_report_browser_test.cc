// SPDX-License-Identifier: GPL-3.0-or-later
// The batch report as a teacher sees it: loaded from a file into headless Chromium (Debian's
// `chromium`), its scripts run, and the rendered DOM read back with --dump-dom.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "batch_report.h"
#include "run_program.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// one job per status, in id order; their wall times sort one way as numbers and another as text,
// and one has none
const json kResults = json::parse(R"({
  "unimouse_version": "0.9.0", "manifest": "class.yaml",
  "jobs": [
    {"id": "a/seed-1", "submission": "a", "seed": 1, "status": "passed", "wall_time_s": 9.5},
    {"id": "b/seed-1", "submission": "b", "seed": 1, "status": "failed", "wall_time_s": 100,
     "reason": "</td></tr></table><script>document.title='owned'</script><img src=x onerror=\"document.title='owned'\">"},
    {"id": "c/seed-1", "submission": "c", "seed": 1, "status": "firmware_error", "wall_time_s": 2},
    {"id": "d/seed-1", "submission": "d", "seed": 1, "status": "script_error", "wall_time_s": null},
    {"id": "e/seed-1", "submission": "e", "seed": 1, "status": "bad_input", "wall_time_s": 10.25},
    {"id": "f/seed-1", "submission": "f", "seed": 1, "status": "timeout", "wall_time_s": 30},
    {"id": "g/seed-1", "submission": "g", "seed": 1, "status": "crashed", "wall_time_s": 0.5}
  ],
  "summary": []
})");

// the directory of PATH that holds `program`, or "" when none does
std::string FindProgram(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path == nullptr ? "" : path);
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (!dir.empty() && ::access((dir + "/" + program).c_str(), X_OK) == 0) {
      return dir + "/" + program;
    }
  }
  return "";
}

class BatchReportBrowserTest : public ::testing::Test {
 protected:
  void SetUp() override {
    chromium_ = FindProgram("chromium");
    if (chromium_.empty()) GTEST_SKIP() << "no chromium on PATH (Debian: apt-get install chromium)";
    dir_ = testing::FreshDirectory("report");
    WriteBatchReport(kResults, dir_ / "report.html");
  }

  // the page's DOM after its scripts ran, opened at `fragment`
  std::string RenderedDom(const std::string& fragment) {
    // --no-sandbox: the sandbox cannot start as root, and this page is our own file; the
    // profile and its caches stay in this test's directory
    const fs::path profile = dir_ / "chromium-profile";
    const testing::Outcome chromium = testing::Shell(
        "XDG_CONFIG_HOME=" + profile.string() + " XDG_CACHE_HOME=" + profile.string() + " " +
        chromium_ + " --headless --no-sandbox --disable-gpu --no-first-run --user-data-dir=" +
        profile.string() + " --dump-dom 'file://" + (dir_ / "report.html").string() + "#" +
        fragment + "' 2>/dev/null");
    EXPECT_EQ(chromium.exit_code, 0);
    return chromium.output;
  }

  std::string chromium_;
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

TEST_F(BatchReportBrowserTest, HidesTheJobsOfOtherStatusesWhenFiltered) {
  const std::string dom = RenderedDom("status=failed");
  EXPECT_NE(dom.find("data-job=\"b/seed-1\" data-status=\"failed\">"), std::string::npos);
  EXPECT_NE(dom.find("data-job=\"a/seed-1\" data-status=\"passed\" hidden=\"\">"),
            std::string::npos);
  EXPECT_NE(dom.find("<span id=\"shown\">1 of 7 jobs shown</span>"), std::string::npos);
}

}  // namespace
}  // namespace unimouse
