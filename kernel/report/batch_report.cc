// SPDX-License-Identifier: GPL-3.0-or-later
#include "batch_report.h"

#include <array>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "text_file.h"

namespace unimouse {
namespace {

using nlohmann::json;

// the statuses a job can have, in the order the page lists them
constexpr std::array<const char*, 7> kStatuses = {
    "passed", "failed", "firmware_error", "script_error", "bad_input", "timeout", "crashed"};

// style, behaviour and policy are constants: nothing from the results is ever put inside them
constexpr std::string_view kHead = R"(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; img-src 'self' file: data:; style-src 'unsafe-inline'; script-src 'unsafe-inline'; base-uri 'none'; form-action 'none'">
<style>
body { font-family: system-ui, sans-serif; margin: 1.5em; color: #1b1b1b; background: #fff; }
h1 { font-size: 1.4em; margin: 0 0 0.3em; }
h2 { font-size: 1.15em; margin: 1.4em 0 0.4em; }
table { border-collapse: collapse; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.5em; text-align: left; vertical-align: top; }
th { background: #eee; position: sticky; top: 0; white-space: nowrap; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.reason { max-width: 28em; white-space: pre-wrap; overflow-wrap: anywhere; }
.wide { max-width: 100%; overflow-x: auto; }
tbody tr:nth-child(even) { background: #f7f7f7; }
tbody tr:target { outline: 2px solid #1565c0; }
.js th[data-key] { cursor: pointer; }
.js th[data-key]:hover { background: #ddd; }
th[aria-sort=ascending]::after { content: " \25B2"; }
th[aria-sort=descending]::after { content: " \25BC"; }
.status { display: inline-block; padding: 0 0.45em; border-radius: 0.6em; color: #fff; white-space: nowrap; }
.status-passed { background: #2e7d32; }
.status-failed { background: #c62828; }
.status-firmware_error, .status-script_error { background: #6a1b9a; }
.status-bad_input { background: #616161; }
.status-timeout { background: #ef6c00; }
.status-crashed { background: #4e342e; }
.status-other { background: #37474f; }
#controls { margin: 0.5em 0; }
#controls label { margin-right: 1em; }
details a { display: inline-block; vertical-align: top; margin: 0.3em 0.5em 0 0; }
details img { display: block; max-width: 240px; border: 1px solid #ccc; }
code { overflow-wrap: anywhere; }
</style>
)";

constexpr std::string_view kScript = R"(<script>
(function () {
  'use strict';
  document.documentElement.classList.add('js');
  var jobs = document.getElementById('jobs');
  var statusFilter = document.getElementById('status-filter');
  var textFilter = document.getElementById('text-filter');
  var shown = document.getElementById('shown');

  // numeric columns compare the data-value of their cells as numbers, empty cells last
  function sortTable(table, th, descending) {
    var index = th.cellIndex;
    var numeric = th.getAttribute('data-type') === 'number';
    var body = table.tBodies[0];
    var rows = Array.prototype.slice.call(body.rows);
    function key(row) {
      var cell = row.cells[index];
      var value = cell.hasAttribute('data-value') ? cell.getAttribute('data-value') : cell.textContent;
      if (!numeric) return value;
      return value === '' ? NaN : Number(value);
    }
    rows.sort(function (a, b) {
      var x = key(a), y = key(b), order;
      if (numeric) {
        if (isNaN(x) || isNaN(y)) return isNaN(x) - isNaN(y);
        order = x - y;
      } else {
        order = x.localeCompare(y, undefined, {numeric: true, sensitivity: 'base'});
      }
      return descending ? -order : order;
    });
    rows.forEach(function (row) { body.appendChild(row); });
    Array.prototype.forEach.call(table.tHead.rows[0].cells, function (cell) {
      cell.removeAttribute('aria-sort');
    });
    th.setAttribute('aria-sort', descending ? 'descending' : 'ascending');
  }

  function filterJobs() {
    var status = statusFilter.value;
    var text = textFilter.value.trim().toLowerCase();
    var count = 0;
    Array.prototype.forEach.call(jobs.tBodies[0].rows, function (row) {
      var visible = (status === '' || row.getAttribute('data-status') === status) &&
          (text === '' || row.textContent.toLowerCase().indexOf(text) >= 0);
      row.hidden = !visible;
      if (visible) count++;
    });
    shown.textContent = count + ' of ' + jobs.tBodies[0].rows.length + ' jobs shown';
  }

  Array.prototype.forEach.call(document.querySelectorAll('table.sortable'), function (table) {
    Array.prototype.forEach.call(table.tHead.rows[0].cells, function (th) {
      if (!th.hasAttribute('data-key')) return;
      th.addEventListener('click', function () {
        sortTable(table, th, th.getAttribute('aria-sort') === 'ascending');
      });
    });
  });
  statusFilter.addEventListener('change', filterJobs);
  textFilter.addEventListener('input', filterJobs);
  document.getElementById('controls').hidden = false;

  // the address's fragment opens the page sorted and filtered (#sort=-wall_time_s&status=failed);
  // sorting clicks the column's header, once for ascending, twice for descending
  // and summary=KEY sorts the submissions' table (#summary=scores.best_run_s.best)
  var options = new URLSearchParams(location.hash.slice(1));
  function sortFromAddress(table, sort) {
    var descending = sort.charAt(0) === '-';
    var name = descending ? sort.slice(1) : sort;
    Array.prototype.forEach.call(table.tHead.rows[0].cells, function (th) {
      if (name === '' || th.getAttribute('data-key') !== name) return;
      th.click();
      if (descending) th.click();
    });
  }
  sortFromAddress(jobs, options.get('sort') || '');
  sortFromAddress(document.getElementById('summary'), options.get('summary') || '');
  if (options.has('status')) statusFilter.value = options.get('status');
  if (options.has('text')) textFilter.value = options.get('text');
  filterJobs();
})();
</script>
)";

const json& Field(const json& object, const char* key) {
  static const json kNull;
  if (!object.is_object()) return kNull;
  const auto found = object.find(key);
  return found == object.end() ? kNull : *found;
}

// a relative path as an address: every byte but letters, digits, "-._~" and "/" is
// percent-encoded, so a name with '#', '?', ':' or a space stays one file name
std::string PathAddress(std::string_view path) {
  std::string out;
  for (const char c : path) {
    const unsigned char byte = static_cast<unsigned char>(c);
    if ((byte >= 'a' && byte <= 'z') || (byte >= 'A' && byte <= 'Z') ||
        (byte >= '0' && byte <= '9') || std::string_view("-._~/").find(c) != std::string::npos) {
      out += c;
    } else {
      char encoded[4];
      std::snprintf(encoded, sizeof(encoded), "%%%02X", byte);
      out += encoded;
    }
  }
  return out;
}

// a value as the page writes it: text as it is, whole numbers whole, others to 6 digits
std::string Shown(const json& value) {
  if (value.is_null()) return "";
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number_float()) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.6g", value.get<double>());
    return text;
  }
  return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

// seconds as a stopwatch shows them
std::string Seconds(const json& value) {
  if (!value.is_number()) return Shown(value);
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f", value.get<double>());
  return text;
}

// a cell that sorts by its number in full precision; empty when the value is not a number
std::string NumberCell(const json& value, const std::string& shown) {
  const std::string sort_value = value.is_number() ? value.dump() : "";
  return "<td class=\"num\" data-value=\"" + sort_value + "\">" + XmlEscaped(shown) + "</td>";
}

std::string TextCell(const std::string& text, const char* css_class = nullptr) {
  const std::string attribute =
      css_class == nullptr ? "" : std::string(" class=\"") + css_class + "\"";
  return "<td" + attribute + ">" + XmlEscaped(text) + "</td>";
}

// the class of a status comes from the known list only, never from the text itself
std::string StatusBadge(const json& status) {
  const std::string text = Shown(status);
  std::string css_class = "status-other";
  for (const char* known : kStatuses) {
    if (text == known) css_class = std::string("status-") + known;
  }
  return "<span class=\"status " + css_class + "\">" + XmlEscaped(text) + "</span>";
}

struct Column {
  std::string key;  // the fragment's sort=KEY; empty for a column that does not sort
  std::string title;
  bool numeric = false;
};

std::string HeaderRow(const std::vector<Column>& columns) {
  std::string out = "<thead><tr>";
  for (const auto& c : columns) {
    out += "<th";
    if (!c.key.empty()) {
      out += " data-key=\"" + XmlEscaped(c.key) + "\"";
      if (c.numeric) out += " data-type=\"number\"";
      out += " title=\"sort by " + XmlEscaped(c.title) + "\"";
    }
    out += ">" + XmlEscaped(c.title) + "</th>";
  }
  return out + "</tr></thead>\n";
}

// every score name any job reports, in name order, and whether all its values are numbers
std::map<std::string, bool> ScoreNames(const json& jobs) {
  std::map<std::string, bool> numeric_by_name;
  for (const auto& job : jobs) {
    const json& scores = Field(job, "scores");
    if (!scores.is_object()) continue;
    for (const auto& [name, value] : scores.items()) {
      const auto [entry, added] = numeric_by_name.emplace(name, true);
      entry->second = entry->second && (value.is_number() || value.is_null());
    }
  }
  return numeric_by_name;
}

std::string PicturesCell(const json& job) {
  std::string out = "<td>";
  const json& pictures = Field(job, "pictures");
  if (pictures.is_array() && !pictures.empty()) {
    out += "<details><summary>" + std::to_string(pictures.size()) +
           (pictures.size() == 1 ? " picture" : " pictures") + "</summary>";
    for (const auto& picture : pictures) {
      const std::string path = Shown(picture);
      const std::string address = XmlEscaped(PathAddress(path));
      const std::string name = XmlEscaped(path.substr(path.find_last_of('/') + 1));
      out += "<a href=\"" + address + "\"><img src=\"" + address + "\" alt=\"" + name +
             "\" loading=\"lazy\">" + name + "</a>";
    }
    out += "</details>";
  }
  // the run played again, a page of its own beside the job's other files
  const std::string replay = Shown(Field(job, "replay_page"));
  if (!replay.empty()) {
    out += "<a class=\"replay\" href=\"" + XmlEscaped(PathAddress(replay)) + "\">replay</a> ";
  }
  const std::string dir = Shown(Field(job, "dir"));
  if (!dir.empty()) out += "<a href=\"" + XmlEscaped(PathAddress(dir)) + "/\">job folder</a>";
  return out + "</td>";
}

std::string JobTable(const json& jobs) {
  const auto score_names = ScoreNames(jobs);
  std::vector<Column> columns = {
      {"submission", "Submission"}, {"scenario", "Scenario"}, {"maze", "Maze"},
      {"seed", "Seed", true},       {"status", "Status"},     {"reason", "Reason"}};
  for (const auto& [name, numeric] : score_names)
    columns.push_back({"scores." + name, name, numeric});
  columns.push_back({"sim_time_s", "Sim time (s)", true});
  columns.push_back({"wall_time_s", "Wall time (s)", true});
  columns.push_back({"", "Pictures"});

  std::string out = "<div class=\"wide\"><table id=\"jobs\" class=\"sortable\">\n" +
                    HeaderRow(columns) + "<tbody>\n";
  size_t index = 0;
  for (const auto& job : jobs) {
    out += "<tr id=\"job-" + std::to_string(index++) + "\" data-job=\"" +
           XmlEscaped(Shown(Field(job, "id"))) + "\" data-status=\"" +
           XmlEscaped(Shown(Field(job, "status"))) + "\">";
    out += TextCell(Shown(Field(job, "submission")));
    out += TextCell(Shown(Field(job, "scenario")));
    out += TextCell(Shown(Field(job, "maze")));
    out += NumberCell(Field(job, "seed"), Shown(Field(job, "seed")));
    out += "<td>" + StatusBadge(Field(job, "status")) + "</td>";
    out += TextCell(Shown(Field(job, "reason")), "reason");
    const json& scores = Field(job, "scores");
    for (const auto& [name, numeric] : score_names) {
      const json& score = Field(scores, name.c_str());
      out += numeric ? NumberCell(score, Shown(score)) : TextCell(Shown(score));
    }
    out += NumberCell(Field(job, "sim_time_s"), Seconds(Field(job, "sim_time_s")));
    out += NumberCell(Field(job, "wall_time_s"), Seconds(Field(job, "wall_time_s")));
    out += PicturesCell(job) + "</tr>\n";
  }
  return out + "</tbody>\n</table></div>\n";
}

// the best run: its job's id, linked to the job's row when the page has it, then its other members
std::string BestCell(const json& best, const json& jobs) {
  if (!best.is_object()) return TextCell(Shown(best));
  std::vector<std::string> parts;
  const std::string id = Shown(Field(best, "id"));
  if (!id.empty()) {
    parts.push_back(XmlEscaped(id));
    for (size_t i = 0; i < jobs.size(); ++i) {
      if (Shown(Field(jobs[i], "id")) != id) continue;
      parts.back() = "<a href=\"#job-" + std::to_string(i) + "\">" + parts.back() + "</a>";
      break;
    }
  }
  // its scores one by one, as numbers, not as the JSON they are kept in
  for (const auto& [name, value] : best.items()) {
    if (name == "id") continue;
    if (!value.is_object()) {
      parts.push_back(XmlEscaped(name) + " " + XmlEscaped(Shown(value)));
      continue;
    }
    for (const auto& [inner, number] : value.items()) {
      parts.push_back(XmlEscaped(inner) + " " + XmlEscaped(Shown(number)));
    }
  }
  std::string out = "<td>";
  for (size_t i = 0; i < parts.size(); ++i) out += (i == 0 ? "" : "; ") + parts[i];
  return out + "</td>";
}

// every score name any submission's summary has
std::set<std::string> SummaryScoreNames(const json& summary) {
  std::set<std::string> names;
  for (const auto& row : summary) {
    const json& scores = Field(row, "scores");
    if (!scores.is_object()) continue;
    for (const auto& [name, value] : scores.items()) names.insert(name);
  }
  return names;
}

std::string SummaryTable(const json& summary, const json& jobs, const json& rank) {
  const bool ranked = rank.is_object();
  std::vector<Column> columns;
  if (ranked) columns.push_back({"rank", "Rank", true});
  columns.push_back({"submission", "Submission"});
  columns.push_back({"jobs", "Jobs", true});
  for (const char* status : kStatuses) columns.push_back({status, status, true});
  columns.push_back({"best", "Best run"});
  columns.push_back({"mean_path_cost", "Mean path cost", true});
  // each score the jobs report: its mean, best and worst over the submission's jobs
  const std::set<std::string> score_names = SummaryScoreNames(summary);
  for (const auto& name : score_names) {
    for (const char* what : {"mean", "best", "worst"}) {
      columns.push_back({"scores." + name + "." + what, name + " " + what, true});
    }
  }
  std::string out = "<div class=\"wide\"><table id=\"summary\" class=\"sortable\">\n" +
                    HeaderRow(columns) + "<tbody>\n";
  for (const auto& row : summary) {
    out += "<tr>";
    if (ranked) out += NumberCell(Field(row, "rank"), Shown(Field(row, "rank")));
    out += TextCell(Shown(Field(row, "submission")));
    out += NumberCell(Field(row, "jobs"), Shown(Field(row, "jobs")));
    for (const char* status : kStatuses) {
      out += NumberCell(Field(row, status), Shown(Field(row, status)));
    }
    out += BestCell(Field(row, "best"), jobs);
    out += NumberCell(Field(row, "mean_path_cost"), Shown(Field(row, "mean_path_cost")));
    for (const auto& name : score_names) {
      const json& score = Field(Field(row, "scores"), name.c_str());
      for (const char* what : {"mean", "best", "worst"}) {
        out += NumberCell(Field(score, what), Shown(Field(score, what)));
      }
    }
    out += "</tr>\n";
  }
  return out + "</tbody>\n</table></div>\n";
}

// "12 jobs: 9 passed, 2 failed, 1 timeout"
std::string JobCounts(const json& jobs) {
  std::string out = std::to_string(jobs.size()) + (jobs.size() == 1 ? " job" : " jobs");
  const char* separator = ": ";
  for (const char* status : kStatuses) {
    size_t count = 0;
    for (const auto& job : jobs) count += Shown(Field(job, "status")) == status ? 1 : 0;
    if (count == 0) continue;
    out += separator + std::to_string(count) + " " + status;
    separator = ", ";
  }
  return out;
}

}  // namespace

std::string BatchReportHtml(const nlohmann::json& results) {
  static const json kEmpty = json::array();
  const json& jobs = Field(results, "jobs").is_array() ? Field(results, "jobs") : kEmpty;
  const json& summary = Field(results, "summary").is_array() ? Field(results, "summary") : kEmpty;
  const std::string manifest = Shown(Field(results, "manifest"));

  std::string out(kHead);
  out += "<title>Batch report: " + XmlEscaped(manifest) + "</title>\n</head>\n<body>\n";
  out += "<h1>Batch report</h1>\n<p>Manifest <code>" + XmlEscaped(manifest) + "</code>, unimouse " +
         XmlEscaped(Shown(Field(results, "unimouse_version"))) + ". " +
         XmlEscaped(JobCounts(jobs)) + ".</p>\n";
  const json& rank = Field(results, "rank");
  std::string ranking;
  if (rank.is_object()) {
    ranking = " Ranked by the best " + XmlEscaped(Shown(Field(rank, "score"))) + " (" +
              XmlEscaped(Shown(Field(rank, "better"))) + " is better).";
  }
  out += "<h2>Submissions</h2>\n<p>Each score's mean, best and worst over the submission's jobs." +
         ranking + "</p>\n" + SummaryTable(summary, jobs, rank);
  out +=
      "<h2>Jobs</h2>\n<div id=\"controls\" hidden><label>Status <select id=\"status-filter\">"
      "<option value=\"\">all</option>";
  for (const char* status : kStatuses) out += std::string("<option>") + status + "</option>";
  out +=
      "</select></label><label>Text <input id=\"text-filter\" type=\"search\"></label>"
      "<span id=\"shown\"></span></div>\n";
  out += JobTable(jobs);
  out += kScript;
  return out + "</body>\n</html>\n";
}

void WriteBatchReport(const nlohmann::json& results, const std::filesystem::path& html) {
  WriteTextFile(html.string(), BatchReportHtml(results));
}

}  // namespace unimouse
