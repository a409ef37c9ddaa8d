// SPDX-License-Identifier: GPL-3.0-or-later
#include "batch_results.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "batch_report.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse::batch {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// a CSV field, quoted when it must be
std::string Csv(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

// a number as CSV shows it: fixed decimals for times, enough digits for scores
std::string Number(const json& value, const char* format) {
  if (!value.is_number()) return "";
  char text[64];
  std::snprintf(text, sizeof(text), format, value.get<double>());
  return text;
}

std::string Text(const json& value) {
  return value.is_string() ? value.get<std::string>() : value.is_null() ? "" : value.dump();
}

}  // namespace

std::vector<std::string> FindJobDirectories(const std::string& root) {
  std::vector<std::string> dirs;
  UNIMOUSE_THROW_UNLESS(IsDirectory(root), root + ": no such directory");
  if (PathExists(fs::path(root) / "job.json")) dirs.push_back(root);
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (e.is_directory() && PathExists(e.path() / "job.json")) dirs.push_back(e.path().string());
  }
  std::sort(dirs.begin(), dirs.end());
  return dirs;
}

json JobRows(const std::vector<std::string>& job_dirs, const std::string& out_dir) {
  std::map<std::string, json> rows;  // by id, so sorted
  std::map<std::string, std::string> where;
  const fs::path out = fs::absolute(out_dir);
  for (const auto& d : job_dirs) {
    const fs::path dir = fs::absolute(d);
    json job;
    try {
      job = json::parse(ReadTextFile((dir / "job.json").string()));
    } catch (const json::exception& e) {
      throw InputError((dir / "job.json").string() + ": not a job record: " + e.what());
    }
    const std::string id = job.value("id", "");
    UNIMOUSE_THROW_UNLESS(!id.empty(), (dir / "job.json").string() + ": no job id");
    UNIMOUSE_THROW_UNLESS(!where.contains(id), "job " + id + " is in both " + where[id] + " and " +
                                                   dir.string() + ": collect one");
    where[id] = dir.string();
    const std::string relative = dir.lexically_relative(out).generic_string();
    std::vector<std::string> pictures;
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.path().extension() == ".png") {
        pictures.push_back((fs::path(relative) / e.path().filename()).generic_string());
      }
    }
    std::sort(pictures.begin(), pictures.end());
    json row;
    for (const char* key : {"id", "submission", "scenario", "maze", "seed", "status", "reason",
                            "scores", "sim_time_s", "wall_time_s", "exit_code", "signal"}) {
      row[key] = job.contains(key) ? job[key] : json(nullptr);
    }
    if (!row["scores"].is_object()) row["scores"] = json::object();
    row["dir"] = relative;
    row["pictures"] = pictures;
    // the job's replay page, where its job.json names one in its directory that is there
    const json page = job.contains("replay_page") ? job["replay_page"] : json(nullptr);
    const fs::path name = page.is_string() ? fs::path(page.get<std::string>()) : fs::path();
    row["replay_page"] = !name.empty() && !name.has_parent_path() && name != ".." &&
                                 IsRegularFile((dir / name).string())
                             ? json((fs::path(relative) / name).generic_string())
                             : json(nullptr);
    // what the job graded: each input file with its SHA-256
    row["inputs"] = job.contains("command") && job["command"].contains("inputs")
                        ? job["command"]["inputs"]
                        : json::array();
    rows[id] = std::move(row);
  }
  json list = json::array();
  for (auto& [id, row] : rows) list.push_back(std::move(row));
  return list;
}

json Summarize(const json& rows, const ScoreRanking& ranking) {
  auto higher_better = [&](const std::string& name) {
    return std::find(ranking.higher_is_better.begin(), ranking.higher_is_better.end(), name) !=
           ranking.higher_is_better.end();
  };
  // each submission's numeric values of each score, over its jobs
  std::map<std::string, std::map<std::string, std::vector<double>>> values;
  for (const auto& row : rows) {
    for (const auto& [name, value] : row["scores"].items()) {
      if (value.is_number()) values[Text(row["submission"])][name].push_back(value.get<double>());
    }
  }
  std::map<std::string, json> by_submission;
  for (const auto& row : rows) {
    json& s = by_submission[Text(row["submission"])];
    if (s.is_null()) {
      s = {{"submission", row["submission"]}, {"jobs", 0}};
      for (const auto& status : kStatuses) s[status] = 0;
      s["best"] = nullptr;
      s["path_costs"] = json::array();
    }
    s["jobs"] = s["jobs"].get<int>() + 1;
    const std::string status = Text(row["status"]);
    if (s.contains(status)) s[status] = s[status].get<int>() + 1;
    const json& scores = row["scores"];
    if (scores.contains("best_run_path_cost") && scores["best_run_path_cost"].is_number()) {
      s["path_costs"].push_back(scores["best_run_path_cost"]);
    }
    if (status != "passed") continue;
    // the best passed job: its fastest run where the scenario times runs, else its sim time
    const auto key = [](const json& r) {
      const json& sc = r["scores"];
      const bool timed = sc.contains("best_run_s") && sc["best_run_s"].is_number();
      return std::make_pair(timed ? sc["best_run_s"].get<double>() : 1e300,
                            r["sim_time_s"].is_number() ? r["sim_time_s"].get<double>() : 1e300);
    };
    if (s["best"].is_null() || key(row) < key(s["best"])) {
      s["best"] = {{"id", row["id"]},
                   {"maze", row["maze"]},
                   {"seed", row["seed"]},
                   {"scores", row["scores"]},
                   {"sim_time_s", row["sim_time_s"]}};
    }
  }
  json summary = json::array();
  for (auto& [name, s] : by_submission) {
    const json& costs = s["path_costs"];
    double sum = 0;
    for (const auto& c : costs) sum += c.get<double>();
    s["mean_path_cost"] =
        costs.empty() ? json(nullptr) : json(sum / static_cast<double>(costs.size()));
    s.erase("path_costs");
    s["scores"] = json::object();
    for (const auto& [score, list] : values[name]) {
      double total = 0;
      for (double v : list) total += v;
      const auto [low, high] = std::minmax_element(list.begin(), list.end());
      const bool higher = higher_better(score);
      s["scores"][score] = {{"jobs", list.size()},
                            {"mean", total / static_cast<double>(list.size())},
                            {"best", higher ? *high : *low},
                            {"worst", higher ? *low : *high}};
    }
    summary.push_back(std::move(s));
  }
  if (ranking.score.empty()) return summary;
  // ranked by each submission's best value of the score; those without one last, unranked
  const bool higher = higher_better(ranking.score);
  auto best_of = [&](const json& s) -> std::optional<double> {
    const json& scores = s["scores"];
    if (!scores.contains(ranking.score)) return std::nullopt;
    return scores[ranking.score]["best"].get<double>();
  };
  std::stable_sort(summary.begin(), summary.end(), [&](const json& a, const json& b) {
    const auto va = best_of(a), vb = best_of(b);
    if (!va || !vb) return va.has_value() && !vb.has_value();
    return higher ? *va > *vb : *va < *vb;
  });
  int position = 0;
  for (auto& s : summary) s["rank"] = best_of(s) ? json(++position) : json(nullptr);
  return summary;
}

void WriteResults(const std::string& out_dir, const json& rows, const std::string& manifest,
                  const std::string& version, const ScoreRanking& ranking) {
  const fs::path out(out_dir);
  fs::create_directories(out);
  const json summary = Summarize(rows, ranking);
  json results = {
      {"unimouse_version", version}, {"manifest", manifest}, {"jobs", rows}, {"summary", summary}};
  results["rank"] = ranking.score.empty()
                        ? json(nullptr)
                        : json{{"score", ranking.score},
                               {"better", std::find(ranking.higher_is_better.begin(),
                                                    ranking.higher_is_better.end(),
                                                    ranking.score) != ranking.higher_is_better.end()
                                              ? "higher"
                                              : "lower"}};
  WriteTextFile((out / "results.json").string(),
                results.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
  WriteBatchReport(results, out / "report.html");

  // scores flattened: a column for every score any job reports, by name
  std::set<std::string> score_names;
  for (const auto& row : rows) {
    for (const auto& [name, value] : row["scores"].items()) score_names.insert(name);
  }
  std::ostringstream csv;
  csv << "submission,scenario,maze,seed,status,reason";
  for (const auto& name : score_names) csv << "," << Csv("score." + name);
  csv << ",sim_time_s,wall_time_s,exit_code,dir,replay_page\n";
  for (const auto& row : rows) {
    csv << Csv(Text(row["submission"])) << "," << Csv(Text(row["scenario"])) << ","
        << Csv(Text(row["maze"])) << "," << Text(row["seed"]) << "," << Csv(Text(row["status"]))
        << "," << Csv(Text(row["reason"]));
    for (const auto& name : score_names) {
      csv << "," << (row["scores"].contains(name) ? Number(row["scores"][name], "%.10g") : "");
    }
    csv << "," << Number(row["sim_time_s"], "%.3f") << "," << Number(row["wall_time_s"], "%.3f")
        << "," << Text(row["exit_code"]) << "," << Csv(Text(row["dir"])) << ","
        << Csv(Text(row["replay_page"])) << "\n";
  }
  WriteTextFile((out / "results.csv").string(), csv.str());

  std::ostringstream sum;
  sum << "submission,jobs";
  for (const auto& status : kStatuses) sum << "," << status;
  sum << ",best_job,best_run_s,mean_path_cost\n";
  for (const auto& s : summary) {
    sum << Csv(Text(s["submission"])) << "," << s["jobs"].get<int>();
    for (const auto& status : kStatuses) sum << "," << s[status].get<int>();
    const json& best = s["best"];
    const bool timed = !best.is_null() && best["scores"].contains("best_run_s");
    sum << "," << (best.is_null() ? "" : Csv(Text(best["id"]))) << ","
        << (timed ? Number(best["scores"]["best_run_s"], "%.3f") : "") << ","
        << Number(s["mean_path_cost"], "%.10g") << "\n";
  }
  WriteTextFile((out / "summary.csv").string(), sum.str());

  // JUnit: failed is a failure, every other status but passed an error
  std::ostringstream xml;
  int failures = 0, errors = 0;
  for (const auto& row : rows) {
    const std::string status = Text(row["status"]);
    failures += status == "failed";
    errors += status != "failed" && status != "passed";
  }
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"unimouse batch\" tests=\""
      << rows.size() << "\" failures=\"" << failures << "\" errors=\"" << errors << "\">\n";
  for (const auto& s : summary) {
    const std::string name = Text(s["submission"]);
    double time_s = 0;
    for (const auto& row : rows) {
      if (Text(row["submission"]) == name && row["wall_time_s"].is_number()) {
        time_s += row["wall_time_s"].get<double>();
      }
    }
    const int not_failed_errors =
        s["jobs"].get<int>() - s["passed"].get<int>() - s["failed"].get<int>();
    xml << "  <testsuite name=\"" << XmlEscaped(name) << "\" tests=\"" << s["jobs"].get<int>()
        << "\" failures=\"" << s["failed"].get<int>() << "\" errors=\"" << not_failed_errors
        << "\" time=\"" << Number(time_s, "%.3f") << "\">\n";
    for (const auto& row : rows) {
      if (Text(row["submission"]) != name) continue;
      const std::string id = Text(row["id"]);
      const std::string status = Text(row["status"]);
      xml << "    <testcase classname=\"" << XmlEscaped(name + "." + Text(row["scenario"]))
          << "\" name=\"" << XmlEscaped(id.substr(id.find('/') + 1)) << "\" time=\""
          << Number(row["wall_time_s"], "%.3f") << "\"";
      if (status == "passed") {
        xml << "/>\n";
        continue;
      }
      const char* element = status == "failed" ? "failure" : "error";
      xml << ">\n      <" << element << " type=\"" << XmlEscaped(status) << "\" message=\""
          << XmlEscaped(Text(row["reason"])) << "\">" << XmlEscaped(Text(row["dir"])) << "</"
          << element << ">\n    </testcase>\n";
    }
    xml << "  </testsuite>\n";
  }
  xml << "</testsuites>\n";
  WriteTextFile((out / "junit.xml").string(), xml.str());
}

}  // namespace unimouse::batch
