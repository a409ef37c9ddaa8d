// SPDX-License-Identifier: GPL-3.0-or-later
#include "manifest.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <set>

#include "install_paths.h"
#include "maze.h"
#include "scenario.h"
#include "text_file.h"
#include "transport_spec.h"
#include "unimouse/errors.h"

namespace unimouse::batch {
namespace {

namespace fs = std::filesystem;

// a path as the manifest gives it: relative to the manifest's directory
std::string FromManifest(const fs::path& dir, const std::string& path) {
  if (path.empty() || fs::path(path).is_absolute()) return path;
  return (dir / path).lexically_normal().string();
}

// a bundled name or a file beside the manifest; errors at the node that named it
std::string DataFile(const YamlNode& node, const fs::path& dir, const std::string& folder,
                     const std::string& extension) {
  const std::string& name = node.AsString(folder.substr(0, folder.size() - 2));
  const std::string beside = FromManifest(dir, name);
  if (PathExists(beside)) return beside;
  try {
    return fs::absolute(ResolveDataFile(name, folder, extension)).string();
  } catch (const InputError& e) {
    node.Fail(e.what());
  }
}

double Bounded(const YamlNode& node, const std::string& what, double low, double high) {
  const double value = node.AsNumber(what);
  if (value < low || value > high) {
    char range[96];
    std::snprintf(range, sizeof(range), " must be from %g to %g, not %s", low, high,
                  node.scalar.c_str());
    node.Fail(what + range);
  }
  return value;
}

JobLimits ReadLimits(const YamlNode& node, JobLimits limits) {
  const MapReader r(node, "limits",
                    {"wall_time_s", "cpu_time_s", "memory_mb", "file_size_mb", "sandbox"});
  const bool cpu_follows = limits.cpu_time_s == limits.wall_time_s;
  if (const YamlNode* v = r.Optional("wall_time_s")) {
    limits.wall_time_s = Bounded(*v, "wall_time_s", 1, 86400);
    // the CPU limit follows the wall-time limit unless given
    if (cpu_follows) limits.cpu_time_s = limits.wall_time_s;
  }
  if (const YamlNode* v = r.Optional("cpu_time_s")) {
    limits.cpu_time_s = Bounded(*v, "cpu_time_s", 1, 86400);
  }
  if (const YamlNode* v = r.Optional("memory_mb")) {
    limits.memory_mb = static_cast<int>(Bounded(*v, "memory_mb", 256, 262144));
    if (limits.memory_mb != v->AsNumber("memory_mb")) v->Fail("memory_mb must be whole");
  }
  if (const YamlNode* v = r.Optional("file_size_mb")) {
    limits.file_size_mb = static_cast<int>(Bounded(*v, "file_size_mb", 1, 65536));
    if (limits.file_size_mb != v->AsNumber("file_size_mb")) v->Fail("file_size_mb must be whole");
  }
  if (const YamlNode* v = r.Optional("sandbox")) {
    limits.sandbox = v->AsString("sandbox");
    if (limits.sandbox != "auto" && limits.sandbox != "bwrap" && limits.sandbox != "none") {
      v->Fail("sandbox must be auto, bwrap or none, not '" + limits.sandbox + "'");
    }
  }
  return limits;
}

const YamlNode& ListOf(const YamlNode& node, const std::string& what) {
  if (!node.IsSequence() || node.items.empty()) node.Fail(what + " must be a list of one or more");
  return node;
}

// a link spec with its firmware's file (a program, module or image) found beside the manifest;
// transports without a file as given
std::string LinkSpec(const YamlNode& node, const fs::path& dir) {
  const std::string& text = node.AsString("link");
  link::TransportSpec spec;
  try {
    spec = link::ParseTransportSpec(text);
  } catch (const InputError& e) {
    node.Fail(std::string("link: ") + e.what());
  }
  if (spec.kind->firmware == link::FirmwareHost::kBoard) return text;
  if (spec.firmware.empty())
    node.Fail("link " + text + ": name the file, like " + spec.kind->usage);
  // a file beside the manifest, else as given (a bundled firmware's name)
  const std::string beside = FromManifest(dir, spec.firmware);
  return PathExists(beside) ? spec.WithFirmware(beside) : text;
}

// "python3 main.py" as words; no shell in between, as for a native link
std::vector<std::string> Words(const YamlNode& node, const std::string& what) {
  const std::string& text = node.AsString(what);
  std::vector<std::string> words;
  for (size_t at = 0; at < text.size();) {
    const size_t end = std::min(text.find(' ', at), text.size());
    if (end > at) words.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  if (words.empty()) node.Fail(what + " must name a program");
  return words;
}

Submission ReadSubmission(const YamlNode& node, const fs::path& dir, const JobLimits& limits) {
  const MapReader r(node, "submission",
                    {"name", "link", "controller", "mms", "dir", "mms_options", "link_set",
                     "firmware_profile", "robot", "limits"});
  Submission s;
  s.location = node.location;
  s.name = r.Required("name").AsString("name");
  if (s.name.empty()) r.Required("name").Fail("a submission's name must not be empty");
  const YamlNode* link = r.Optional("link");
  const YamlNode* controller = r.Optional("controller");
  const YamlNode* mms = r.Optional("mms");
  if ((link != nullptr) + (controller != nullptr) + (mms != nullptr) != 1) {
    node.Fail("submission '" + s.name + "': give exactly one of link, controller or mms");
  }
  if (link != nullptr) s.link = LinkSpec(*link, dir);
  if (controller != nullptr) s.controller = FromManifest(dir, controller->AsString("controller"));
  if (mms != nullptr) {
    s.mms = Words(*mms, "mms");
    s.program_dir = dir.string();
  }
  if (const YamlNode* own = r.Optional("dir")) {
    if (mms == nullptr) own->Fail("dir is where an mms program runs; it goes with mms");
    s.program_dir = FromManifest(dir, own->AsString("dir"));
    if (!IsDirectory(s.program_dir)) own->Fail(s.program_dir + ": no such directory");
  }
  if (const YamlNode* options = r.Optional("mms_options")) {
    if (mms == nullptr) options->Fail("mms_options go with mms");
    for (const auto& item : ListOf(*options, "mms_options").items) {
      s.mms_options.push_back(item.AsString("mms option"));
    }
  }
  if (const YamlNode* sets = r.Optional("link_set")) {
    if (link == nullptr) sets->Fail("link_set goes with link");
    if (!sets->IsMap()) sets->Fail("link_set must be a map of parameter: value lines");
    for (const auto& [k, v] : sets->entries) {
      s.link_sets.push_back(k.scalar + "=" + v.AsString(k.scalar));
    }
  }
  s.firmware_profile = r.String("firmware_profile", "");
  if (!s.firmware_profile.empty() && link == nullptr) {
    r.Required("firmware_profile").Fail("firmware_profile goes with link");
  }
  if (const YamlNode* robot = r.Optional("robot")) {
    if (mms != nullptr) robot->Fail("robot goes with link or controller: an mms program has none");
    s.robot = DataFile(*robot, dir, "robots/", ".yaml");
  }
  s.limits = limits;
  if (const YamlNode* own = r.Optional("limits")) s.limits = ReadLimits(*own, limits);
  return s;
}

ScenarioEntry ReadScenario(const YamlNode& node, const fs::path& dir) {
  ScenarioEntry e;
  e.location = node.location;
  const YamlNode* file_node = &node;
  const YamlNode* sets = nullptr;
  const YamlNode* name = nullptr;
  std::unique_ptr<MapReader> r;
  if (node.IsMap()) {
    r = std::make_unique<MapReader>(node, "scenario",
                                    std::vector<std::string>{"scenario", "name", "set"});
    file_node = &r->Required("scenario");
    sets = r->Optional("set");
    name = r->Optional("name");
  }
  e.file = DataFile(*file_node, dir, "scenarios/", ".lua");
  std::unique_ptr<Scenario> scenario;
  try {
    // the top level only: it declares the name and parameters, and builds nothing
    scenario = Scenario::Load(e.file, {}, 1);
  } catch (const std::exception& error) {
    file_node->Fail(error.what());
  }
  std::map<std::string, std::string> overrides;
  if (sets != nullptr) {
    if (!sets->IsMap()) sets->Fail("set must be a map of parameter: value lines");
    std::vector<std::string> known;
    for (const auto& [k, v] : scenario->params()) known.push_back(k);
    for (const auto& [k, v] : sets->entries) {
      if (!scenario->params().contains(k.scalar)) {
        const std::string near = NearestWord(k.scalar, known);
        k.Fail("scenario '" + scenario->name() + "' has no parameter '" + k.scalar + "'" +
               (near.empty() ? "" : " (did you mean '" + near + "'?)"));
      }
      overrides[k.scalar] = v.AsString(k.scalar);
      e.sets.push_back(k.scalar + "=" + overrides[k.scalar]);
    }
    try {
      // the values' types, as the run will check them
      Scenario::Load(e.file, overrides, 1);
    } catch (const std::exception& error) {
      sets->Fail(error.what());
    }
  }
  e.has_maze = scenario->params().contains("maze");
  e.min_robots = scenario->min_robots();
  if (e.has_maze) e.default_maze = scenario->params().at("maze");
  e.name = name != nullptr ? name->AsString("name") : scenario->name();
  return e;
}

// every maze a `mazes` item names: a file, a bundled name, or a directory's *.txt files
std::vector<MazeEntry> ReadMazes(const YamlNode& node, const fs::path& dir) {
  const std::string& text = node.AsString("maze");
  const std::string beside = FromManifest(dir, text);
  std::vector<std::string> files;
  try {
    files = FindMazeFiles({PathExists(beside) ? beside : text});
  } catch (const InputError& e) {
    node.Fail(e.what());
  }
  if (files.empty()) node.Fail(text + ": no maze files (*.txt) in this directory");
  std::vector<MazeEntry> mazes;
  for (const auto& f : files) {
    mazes.push_back({SanitizeName(fs::path(f).stem().string()), fs::absolute(f).string()});
  }
  return mazes;
}

uint64_t ReadSeed(const YamlNode& node) {
  const int seed = node.AsInteger("seed");
  if (seed < 0) node.Fail("a seed is a whole number, 0 or more");
  return static_cast<uint64_t>(seed);
}

template <typename T>
int IndexByName(const std::vector<T>& list, const YamlNode& node, const std::string& what) {
  const std::string& name = node.AsString(what);
  std::vector<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    if (list[i].name == name) return static_cast<int>(i);
    names.push_back(list[i].name);
  }
  const std::string near = NearestWord(name, names);
  node.Fail("no " + what + " named '" + name + "'" +
            (near.empty() ? "" : " (did you mean '" + near + "'?)"));
}

}  // namespace

std::string SanitizeName(const std::string& text) {
  std::string out = text;
  for (char& c : out) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       c == '.' || c == '_' || c == '-';
    if (!plain) c = '_';
  }
  if (out.empty() || out == "." || out == "..") out = "_";
  return out;
}

Manifest LoadManifest(const std::string& path) {
  Manifest m;
  m.file = fs::absolute(path).lexically_normal().string();
  const fs::path dir = fs::path(m.file).parent_path();
  const YamlNode root = LoadYamlFile(path);
  const MapReader r(root, "manifest",
                    {"robot", "trace", "rank", "higher_is_better", "submissions", "scenarios",
                     "mazes", "seeds", "limits", "jobs"});
  m.rank_score = r.String("rank", "");
  if (const YamlNode* higher = r.Optional("higher_is_better")) {
    for (const auto& item : ListOf(*higher, "higher_is_better").items) {
      m.higher_is_better.push_back(item.AsString("score"));
    }
  }
  if (const YamlNode* robot = r.Optional("robot")) {
    m.robot = DataFile(*robot, dir, "robots/", ".yaml");
  }
  if (const YamlNode* trace = r.Optional("trace")) {
    // a class's traces add up to gigabytes: jobs keep none unless the teacher asks
    const MapReader t(*trace, "trace", {"period_s", "signals"});
    char period[32];
    std::snprintf(period, sizeof(period), "%.17g",
                  Bounded(t.Required("period_s"), "period_s", 0, 3600));
    m.trace_period_s = period;
    m.trace_signals = t.String("signals", "");
  }
  const JobLimits limits =
      r.Optional("limits") ? ReadLimits(*r.Optional("limits"), {}) : JobLimits{};

  std::set<std::string> names;
  for (const auto& item : ListOf(r.Required("submissions"), "submissions").items) {
    m.submissions.push_back(ReadSubmission(item, dir, limits));
    if (!names.insert(SanitizeName(m.submissions.back().name)).second) {
      item.Fail("a second submission named '" + m.submissions.back().name +
                "' (names must differ, also once made safe for a directory)");
    }
  }
  names.clear();
  const bool only_mms = std::all_of(m.submissions.begin(), m.submissions.end(),
                                    [](const Submission& s) { return !s.mms.empty(); });
  const YamlNode* scenarios = only_mms ? r.Optional("scenarios") : &r.Required("scenarios");
  for (size_t i = 0; scenarios != nullptr && i < ListOf(*scenarios, "scenarios").items.size();
       ++i) {
    const YamlNode& item = scenarios->items[i];
    m.scenarios.push_back(ReadScenario(item, dir));
    if (!names.insert(SanitizeName(m.scenarios.back().name)).second) {
      item.Fail("a second scenario named '" + m.scenarios.back().name +
                "': give one of them a name of its own (name: ...)");
    }
  }

  // what a job runs in: a maze from the list, or the scenario's own
  // (an mms program's job, scenario -1, always has a maze)
  const auto add = [&](int submission, int scenario, const MazeEntry* maze, uint64_t seed,
                       const YamlNode& where, std::vector<int> rivals = {}) {
    Job job;
    job.submission = submission;
    job.rivals = std::move(rivals);
    job.scenario = scenario;
    job.seed = seed;
    if (maze != nullptr) {
      job.maze = maze->name;
      job.maze_file = maze->file;
    } else if (const ScenarioEntry& s = m.scenarios[static_cast<size_t>(scenario)]; s.has_maze) {
      job.maze = SanitizeName(fs::path(s.default_maze).stem().string());
    }
    // each submission's name made safe, several joined by '+'
    std::string who = SanitizeName(m.submissions[static_cast<size_t>(submission)].name);
    for (const int rival : job.rivals) {
      who += "+" + SanitizeName(m.submissions[static_cast<size_t>(rival)].name);
    }
    job.id = who + "/" + SanitizeName(ScenarioName(m, job)) + "/" +
             (job.maze.empty() ? "no-maze" : job.maze) + "/seed-" + std::to_string(seed);
    if (m.jobs.size() >= kMaxJobs) {
      where.Fail("more than " + std::to_string(kMaxJobs) + " jobs; split the batch");
    }
    m.jobs.push_back(std::move(job));
  };

  if (const YamlNode* jobs = r.Optional("jobs")) {
    r.Forbid("mazes", "goes with the product of everything; with jobs: each job names its maze");
    r.Forbid("seeds", "goes with the product of everything; with jobs: each job names its seed");
    for (const auto& item : ListOf(*jobs, "jobs").items) {
      const MapReader j(item, "job", {"submission", "submissions", "scenario", "maze", "seed"});
      // one submission, or several in one world (a race): each a robot
      std::vector<int> rivals;
      int submission = 0;
      if (const YamlNode* several = j.Optional("submissions")) {
        j.Forbid("submission", "goes with one submission; submissions: lists several in one world");
        if (ListOf(*several, "submissions").items.size() < 2) {
          several->Fail("submissions: lists two or more, each a robot of the same world");
        }
        for (const YamlNode& name : several->items) {
          const int index = IndexByName(m.submissions, name, "submission");
          if (!m.submissions[static_cast<size_t>(index)].mms.empty()) {
            name.Fail("an mms program runs alone in its maze, not beside other robots");
          }
          for (const int seen : rivals) {
            if (seen == index) name.Fail("submission '" + name.scalar + "' is listed twice");
          }
          rivals.push_back(index);
        }
        submission = rivals.front();
        rivals.erase(rivals.begin());
      } else {
        submission = IndexByName(m.submissions, j.Required("submission"), "submission");
      }
      const bool mms = !m.submissions[static_cast<size_t>(submission)].mms.empty();
      if (mms) j.Forbid("scenario", "does not apply to an mms program: it runs in its maze alone");
      const int scenario = mms ? -1 : IndexByName(m.scenarios, j.Required("scenario"), "scenario");
      if (!mms) {
        const ScenarioEntry& entry = m.scenarios[static_cast<size_t>(scenario)];
        if (static_cast<int>(rivals.size()) + 1 < entry.min_robots) {
          j.Required("scenario")
              .Fail("scenario '" + entry.name + "' needs " + std::to_string(entry.min_robots) +
                    " robots: list as many in submissions: [...]");
        }
      }
      std::vector<MazeEntry> maze;
      if (mms) j.Required("maze");
      if (const YamlNode* node = j.Optional("maze")) {
        if (!mms && !m.scenarios[static_cast<size_t>(scenario)].has_maze) {
          node->Fail("scenario '" + m.scenarios[static_cast<size_t>(scenario)].name +
                     "' has no maze parameter");
        }
        maze = ReadMazes(*node, dir);
        if (maze.size() != 1) node->Fail("a job runs in one maze, not a directory of them");
      }
      const uint64_t seed = j.Optional("seed") ? ReadSeed(*j.Optional("seed")) : 1;
      add(submission, scenario, maze.empty() ? nullptr : &maze[0], seed, item, rivals);
    }
  } else {
    std::vector<MazeEntry> mazes;
    if (const YamlNode* list = r.Optional("mazes")) {
      for (const auto& item : ListOf(*list, "mazes").items) {
        for (auto& maze : ReadMazes(item, dir)) {
          for (const auto& seen : mazes) {
            if (seen.name == maze.name) {
              item.Fail("two mazes named '" + maze.name + "': " + seen.file + " and " + maze.file);
            }
          }
          mazes.push_back(std::move(maze));
        }
      }
      for (const auto& s : m.scenarios) {
        if (!s.has_maze) {
          list->Fail("scenario '" + s.name + "' (" + s.location.ToString() +
                     ") has no maze parameter: mazes go with scenarios that run in a maze");
        }
        for (const auto& set : s.sets) {
          if (set.starts_with("maze=")) {
            list->Fail("scenario '" + s.name + "' (" + s.location.ToString() +
                       ") sets its maze already: give the maze in one place");
          }
        }
      }
    }
    // every submission alone in every scenario: none that needs several robots
    for (const auto& s : m.scenarios) {
      if (s.min_robots > 1) {
        root.Fail("scenario '" + s.name + "' (" + s.location.ToString() + ") needs " +
                  std::to_string(s.min_robots) +
                  " robots: run it as jobs: [{submissions: [a, b], scenario: " + s.name + "}]");
      }
    }
    std::vector<uint64_t> seeds;
    if (const YamlNode* list = r.Optional("seeds")) {
      for (const auto& item : ListOf(*list, "seeds").items) {
        const uint64_t seed = ReadSeed(item);
        if (std::find(seeds.begin(), seeds.end(), seed) != seeds.end()) {
          item.Fail("seed " + std::to_string(seed) + " is listed twice");
        }
        seeds.push_back(seed);
      }
    } else {
      seeds.push_back(1);
    }
    for (int sub = 0; sub < static_cast<int>(m.submissions.size()); ++sub) {
      const Submission& submission = m.submissions[static_cast<size_t>(sub)];
      if (!submission.mms.empty()) {
        if (mazes.empty()) {
          root.Fail("submission '" + submission.name + "' (" + submission.location.ToString() +
                    ") is an mms program, which runs in mazes: give them (mazes: [...])");
        }
        for (const MazeEntry& maze : mazes) {
          for (const uint64_t seed : seeds) add(sub, -1, &maze, seed, root);
        }
        continue;
      }
      for (int sc = 0; sc < static_cast<int>(m.scenarios.size()); ++sc) {
        for (size_t mz = 0; mz < std::max<size_t>(1, mazes.size()); ++mz) {
          for (const uint64_t seed : seeds) {
            add(sub, sc, mazes.empty() ? nullptr : &mazes[mz], seed, root);
          }
        }
      }
    }
  }
  std::sort(m.jobs.begin(), m.jobs.end(), [](const Job& a, const Job& b) { return a.id < b.id; });
  for (size_t i = 1; i < m.jobs.size(); ++i) {
    if (m.jobs[i].id == m.jobs[i - 1].id) {
      root.Fail("job " + m.jobs[i].id + " is asked for twice");
    }
  }
  return m;
}

const Job& FindJob(const Manifest& manifest, const std::string& id) {
  const auto it =
      std::lower_bound(manifest.jobs.begin(), manifest.jobs.end(), id,
                       [](const Job& job, const std::string& key) { return job.id < key; });
  UNIMOUSE_THROW_UNLESS(it != manifest.jobs.end() && it->id == id,
                        manifest.file + ": no job " + id + " in this manifest");
  return *it;
}

std::string ScenarioName(const Manifest& manifest, const Job& job) {
  return job.scenario < 0 ? kMmsScenario
                          : manifest.scenarios[static_cast<size_t>(job.scenario)].name;
}

std::string SubmissionsName(const Manifest& manifest, const Job& job) {
  std::string name = manifest.submissions[static_cast<size_t>(job.submission)].name;
  for (const int rival : job.rivals)
    name += "+" + manifest.submissions[static_cast<size_t>(rival)].name;
  return name;
}

std::vector<std::string> RunArguments(const Manifest& manifest, const Job& job,
                                      const std::string& out_dir) {
  const Submission& sub = manifest.submissions[static_cast<size_t>(job.submission)];
  if (!sub.mms.empty()) {
    // the logic tier has no chance in it: the seed only names the job
    std::vector<std::string> args = {"mms",         "--out",         out_dir,        "--maze",
                                     job.maze_file, "--program-dir", sub.program_dir};
    args.insert(args.end(), sub.mms_options.begin(), sub.mms_options.end());
    args.push_back("--");
    args.insert(args.end(), sub.mms.begin(), sub.mms.end());
    return args;
  }
  const ScenarioEntry& scenario = manifest.scenarios[static_cast<size_t>(job.scenario)];
  std::vector<std::string> args = {"run",
                                   "--out",
                                   out_dir,
                                   "--seed",
                                   std::to_string(job.seed),
                                   "--robot",
                                   sub.robot.empty() ? manifest.robot : sub.robot,
                                   "--scenario",
                                   scenario.file,
                                   "--trace-period",
                                   manifest.trace_period_s};
  if (!manifest.trace_signals.empty()) {
    args.insert(args.end(), {"--trace-signals", manifest.trace_signals});
  }
  for (const auto& set : scenario.sets) args.insert(args.end(), {"--set", set});
  if (!job.maze_file.empty()) args.insert(args.end(), {"--maze", job.maze_file});
  // each submission's own options follow its robot; with several, each robot is named after
  // its submission
  std::vector<int> robots = {job.submission};
  robots.insert(robots.end(), job.rivals.begin(), job.rivals.end());
  for (const int index : robots) {
    const Submission& s = manifest.submissions[static_cast<size_t>(index)];
    if (index != job.submission) {
      args.insert(args.end(), {"--robot", s.robot.empty() ? manifest.robot : s.robot});
    }
    if (!job.rivals.empty()) args.insert(args.end(), {"--name", SanitizeName(s.name)});
    if (!s.controller.empty()) args.insert(args.end(), {"--controller", s.controller});
    if (!s.link.empty()) args.insert(args.end(), {"--link", s.link});
    for (const auto& set : s.link_sets) args.insert(args.end(), {"--link-set", set});
    if (!s.firmware_profile.empty()) {
      args.insert(args.end(), {"--firmware-profile", s.firmware_profile});
    }
  }
  return args;
}

}  // namespace unimouse::batch
