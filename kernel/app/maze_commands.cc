// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse maze ...`: the maze module on its own, without physics.
#include "maze_commands.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "command_line.h"
#include "install_paths.h"
#include "maze_explorer.h"
#include "maze_generator.h"
#include "maze_plot.h"
#include "maze_solver.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* kHeadingNames[] = {"east", "north", "west", "south"};

// a file name or maze text that is not UTF-8 is shown with replacement characters, not refused
void PrintJson(const json& value) {
  std::cout << value.dump(2, ' ', false, json::error_handler_t::replace) << "\n";
}

// every maze file the arguments name; none is an error here
std::vector<std::string> MazeFiles(const std::vector<std::string>& arguments) {
  std::vector<std::string> files = FindMazeFiles(arguments);
  UNIMOUSE_THROW_UNLESS(!files.empty(), "no maze files found in the arguments");
  return files;
}

// "3F R 2F L": runs of forward moves and the turns between them
std::string ActionText(const MazePath& path, Heading start) {
  std::ostringstream out;
  int heading = static_cast<int>(start), run = 0;
  auto flush = [&] {
    if (run > 0) out << (out.tellp() > 0 ? " " : "") << run << "F";
    run = 0;
  };
  for (size_t i = 1; i < path.cells.size(); ++i) {
    const Cell a = path.cells[i - 1], b = path.cells[i];
    const int move = b.x > a.x ? 0 : b.x < a.x ? 2 : b.y > a.y ? 1 : 3;
    const int turn = (move - heading) & 3;
    if (turn != 0) {
      flush();
      out << (out.tellp() > 0 ? " " : "") << (turn == 1 ? "L" : turn == 3 ? "R" : "B");
    }
    heading = move;
    ++run;
  }
  flush();
  return out.str();
}

json PathJson(const MazePath& path, Heading start) {
  if (!path.found) return nullptr;
  json cells = json::array();
  for (Cell c : path.cells) cells.push_back({c.x, c.y});
  return {{"cost", path.Cost()},
          {"straights", path.straights},
          {"turns", path.turns},
          {"actions", ActionText(path, start)},
          {"cells", cells}};
}

std::string CostText(int cost) { return cost < 0 ? "-" : std::to_string(cost); }

std::string Clock(double seconds) {
  char text[16];
  const int s = static_cast<int>(seconds + 0.5);
  std::snprintf(text, sizeof(text), "%02d:%02d", s / 60, s % 60);
  return text;
}

// progress on stderr when there are many files, so that stdout stays clean
class Progress {
 public:
  explicit Progress(size_t total) : total_(total) {}
  void Step(const std::string& file) {
    ++done_;
    // a line redrawn in place is for a person watching, not for a file or a pipe
    if (total_ < 2 || !::isatty(2)) return;
    std::fprintf(stderr, "\r[%zu/%zu] %-60.60s", done_, total_, file.c_str());
    if (done_ == total_) std::fprintf(stderr, "\n");
  }

 private:
  size_t total_, done_ = 0;
};

// a CSV cell, quoted when it has to be
std::string Csv(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

struct Summary {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  void Write(const std::string& path) const {
    if (path.empty()) return;
    std::ostringstream out;
    for (size_t i = 0; i < header.size(); ++i) out << (i ? "," : "") << header[i];
    out << "\n";
    for (const auto& row : rows) {
      for (size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << Csv(row[i]);
      out << "\n";
    }
    WriteTextFile(path, out.str());
  }
};

}  // namespace

int MazeShow(const MazeOptions& o) {
  json all = json::array();
  for (const auto& file : MazeFiles(o.files)) {
    std::string format;
    const Maze maze = LoadMaze(file, &format);
    if (o.json) {
      json goals = json::array();
      for (Cell g : maze.goals()) goals.push_back({g.x, g.y});
      all.push_back({{"file", file},
                     {"format", format},
                     {"width", maze.width()},
                     {"height", maze.height()},
                     {"start", {maze.start().x, maze.start().y}},
                     {"start_heading", kHeadingNames[static_cast<int>(maze.start_heading())]},
                     {"goals", goals},
                     {"text", FormatMazeText(maze)}});
      continue;
    }
    std::printf("%s (%s): %d x %d, start (%d, %d) facing %s, %zu goal cells\n%s", file.c_str(),
                format.c_str(), maze.width(), maze.height(), maze.start().x, maze.start().y,
                kHeadingNames[static_cast<int>(maze.start_heading())], maze.goals().size(),
                FormatMazeText(maze).c_str());
  }
  if (o.json) PrintJson(all);
  return kExitPassed;
}

int MazeCheck(const MazeOptions& o) {
  const std::vector<std::string> files = MazeFiles(o.files);
  Progress progress(o.json ? 1 : files.size());
  Summary summary{{"file", "width", "height", "status", "reason"}, {}};
  int bad = 0;
  for (const auto& file : files) {
    progress.Step(file);
    std::string status = "ok", reason;
    try {
      const Maze maze = LoadMaze(file);
      std::vector<std::string> warnings;
      for (int x = 0; x < maze.width(); ++x) {
        if (!maze.HasHorizontalWall(x, 0) || !maze.HasHorizontalWall(x, maze.height())) {
          warnings.push_back("open perimeter at column " + std::to_string(x));
          break;
        }
      }
      for (int y = 0; y < maze.height(); ++y) {
        if (!maze.HasVerticalWall(0, y) || !maze.HasVerticalWall(maze.width(), y)) {
          warnings.push_back("open perimeter at row " + std::to_string(y));
          break;
        }
      }
      const OpenSides sides(maze);
      CellFloodFill fill;
      fill.Compute(sides, maze.goals());
      if (fill.Distance(maze.start()) == CellFloodFill::kUnreachable) {
        warnings.push_back("no goal cell can be reached from the start");
      }
      if (!warnings.empty()) {
        status = o.strict ? "error" : "warning";
        for (const auto& w : warnings) reason += (reason.empty() ? "" : "; ") + w;
      }
      summary.rows.push_back(
          {file, std::to_string(maze.width()), std::to_string(maze.height()), status, reason});
    } catch (const InputError& e) {
      status = "error";
      reason = e.what();
      summary.rows.push_back({file, "", "", status, reason});
    }
    if (status == "error") ++bad;
    if (o.json) continue;
    if (status != "ok" || files.size() == 1) {
      std::printf("%s: %s%s%s\n", file.c_str(), status.c_str(), reason.empty() ? "" : ": ",
                  reason.c_str());
    }
  }
  summary.Write(o.csv);
  if (o.json) {
    json all = json::array();
    for (const auto& row : summary.rows) {
      all.push_back({{"file", row[0]}, {"status", row[3]}, {"reason", row[4]}});
    }
    PrintJson(all);
  } else if (files.size() > 1) {
    std::printf("%zu mazes checked, %d with errors\n", files.size(), bad);
  }
  return bad > 0 ? kExitBadInput : kExitPassed;
}

int MazeSolve(const MazeOptions& o) {
  const TieRule rule = TieRule::Parse(o.tie_rule);
  const std::vector<std::string> files = MazeFiles(o.files);
  Progress progress(o.json || files.size() < 2 ? 1 : files.size());
  Summary summary{{"file", "modified_cost", "modified_straights", "modified_turns",
                   "traditional_cost", "traditional_straights", "traditional_turns"},
                  {}};
  json all = json::array();
  for (const auto& file : files) {
    progress.Step(file);
    const Maze maze = LoadMaze(file);
    const OpenSides sides(maze);
    StateFloodFill states;
    states.Compute(sides, maze.goals());
    CellFloodFill cells;
    cells.Compute(sides, maze.goals());
    const MazePath modified = states.PathFrom(sides, maze.start(), maze.start_heading());
    const MazePath traditional = cells.PathFrom(sides, maze.start(), maze.start_heading(), rule);
    summary.rows.push_back(
        {file, CostText(modified.found ? modified.Cost() : -1), std::to_string(modified.straights),
         std::to_string(modified.turns), CostText(traditional.found ? traditional.Cost() : -1),
         std::to_string(traditional.straights), std::to_string(traditional.turns)});
    if (o.json) {
      all.push_back({{"file", file},
                     {"tie_rule", rule.Name()},
                     {"modified", PathJson(modified, maze.start_heading())},
                     {"traditional", PathJson(traditional, maze.start_heading())}});
    } else if (files.size() == 1) {
      if (!modified.found) {
        std::printf("%s: no path from the start to a goal cell\n", file.c_str());
        continue;
      }
      std::printf("%s (%d x %d)\n", file.c_str(), maze.width(), maze.height());
      std::printf("  modified flood fill:    cost %3d = %d straights + %d turns\n    %s\n",
                  modified.Cost(), modified.straights, modified.turns,
                  ActionText(modified, maze.start_heading()).c_str());
      std::printf(
          "  traditional flood fill: cost %3d = %d straights + %d turns (ties: %s)\n    %s\n",
          traditional.Cost(), traditional.straights, traditional.turns, rule.Name().c_str(),
          ActionText(traditional, maze.start_heading()).c_str());
    }
  }
  if (o.json) PrintJson(all);
  if (!o.json && files.size() > 1) {
    std::printf("%-50s %9s %12s\n", "maze", "modified", "traditional");
    for (const auto& row : summary.rows) {
      std::printf("%-50s %9s %12s\n", row[0].c_str(), row[1].c_str(), row[4].c_str());
    }
  }
  summary.Write(o.csv);
  return kExitPassed;
}

int MazeExplore(const MazeOptions& o) {
  ExploreOptions options;
  options.cell_time_s = o.cell_time_s;
  options.turn_time_s = o.turn_time_s;
  const std::vector<std::string> files = MazeFiles(o.files);
  Progress progress(o.json || files.size() < 2 ? 1 : files.size());
  Summary summary{{"file", "trips", "optimal_found", "best_cost", "cells_visited", "time_s"}, {}};
  json all = json::array();
  for (const auto& file : files) {
    progress.Step(file);
    const Maze maze = LoadMaze(file);
    const Exploration e = ExploreAdachi(maze, options);
    double total_s = 0;
    for (const auto& t : e.trips) total_s += t.time_s;
    const int visited = e.trips.empty() ? 0 : e.trips.back().cells_visited;
    summary.rows.push_back({file, std::to_string(e.trips.size()), e.optimal_found ? "yes" : "no",
                            CostText(e.best.found ? e.best.Cost() : -1), std::to_string(visited),
                            std::to_string(total_s)});
    if (o.json) {
      json trips = json::array();
      for (const auto& t : e.trips) {
        trips.push_back({{"trip", t.trip},
                         {"to", t.to_goal ? "goal" : "start"},
                         {"open_cost", t.open_cost},
                         {"closed_cost", t.closed_cost},
                         {"cells_visited", t.cells_visited},
                         {"forward_moves", t.forward_moves},
                         {"turns", t.turns},
                         {"time_s", t.time_s}});
      }
      all.push_back({{"file", file},
                     {"trips", trips},
                     {"optimal_found", e.optimal_found},
                     {"goal_unreachable", e.goal_unreachable},
                     {"best", PathJson(e.best, maze.start_heading())}});
      continue;
    }
    if (!o.plot_dir.empty()) {
      // one picture per trip, as figures 5.7-5.13
      const std::string stem = fs::path(file).stem().string();
      fs::create_directories(o.plot_dir);
      for (size_t i = 0; i < e.trips.size(); ++i) {
        MazePicture picture;
        picture.maze = &maze;
        picture.knowledge = &e.knowledge[i];
        picture.open_path = e.trips[i].open_path;
        picture.closed_path = e.trips[i].closed_path;
        const fs::path base = fs::path(o.plot_dir) / (stem + "_trip" + std::to_string(i + 1));
        WriteMazePicture(picture, base.string() + ".png");
        WriteMazePicture(picture, base.string() + ".svg");
      }
    }
    if (files.size() > 1) continue;
    std::printf("%s (%d x %d): Adachi method 0, modified flood fill\n", file.c_str(), maze.width(),
                maze.height());
    std::printf("  trip  to     open  closed  visited  moves  turns  time\n");
    for (const auto& t : e.trips) {
      std::printf("  %4d  %-5s %5s %7s %8d %6d %6d  %s\n", t.trip, t.to_goal ? "goal" : "start",
                  CostText(t.open_cost).c_str(), CostText(t.closed_cost).c_str(), t.cells_visited,
                  t.forward_moves, t.turns, Clock(t.time_s).c_str());
    }
    if (e.goal_unreachable) {
      std::printf("  no path from the start to a goal cell\n");
    } else if (e.optimal_found) {
      std::printf("  optimal path found: cost %d = %d straights + %d turns\n    %s\n",
                  e.best.Cost(), e.best.straights, e.best.turns,
                  ActionText(e.best, maze.start_heading()).c_str());
    } else {
      std::printf("  stopped after %zu trips without proving the best path\n", e.trips.size());
    }
  }
  if (o.json) PrintJson(all);
  if (!o.json && files.size() > 1) {
    int optimal = 0;
    for (const auto& row : summary.rows) optimal += row[2] == "yes";
    std::printf("%zu mazes explored, the best path proven in %d\n", files.size(), optimal);
  }
  summary.Write(o.csv);
  return kExitPassed;
}

int MazePlot(const MazeOptions& o) {
  UNIMOUSE_THROW_UNLESS(o.files.size() == 1, "plot takes one maze");
  UNIMOUSE_THROW_UNLESS(!o.out.empty(), "plot needs --out FILE.png or --out FILE.svg");
  const Maze maze = LoadMaze(MazeFiles(o.files)[0]);
  const OpenSides sides(maze);
  MazePicture picture;
  picture.maze = &maze;
  if (o.path == "modified" || o.path == "both") {
    StateFloodFill fill;
    fill.Compute(sides, maze.goals());
    picture.closed_path = fill.PathFrom(sides, maze.start(), maze.start_heading());
  }
  CellFloodFill cells;
  cells.Compute(sides, maze.goals());
  if (o.path == "traditional" || o.path == "both") {
    picture.open_path =
        cells.PathFrom(sides, maze.start(), maze.start_heading(), TieRule::Parse(o.tie_rule));
  }
  UNIMOUSE_THROW_UNLESS(
      o.path == "modified" || o.path == "traditional" || o.path == "both" || o.path == "none",
      "--path is modified, traditional, both or none");
  if (o.costs) {
    for (int y = 0; y < maze.height(); ++y) {
      for (int x = 0; x < maze.width(); ++x) {
        const uint16_t d = cells.Distance({x, y});
        picture.numbers.push_back(d == CellFloodFill::kUnreachable ? -1 : d);
      }
    }
  }
  WriteMazePicture(picture, o.out);
  std::printf("%s\n", o.out.c_str());
  return kExitPassed;
}

int MazeConvert(const MazeOptions& o) {
  UNIMOUSE_THROW_UNLESS(o.files.size() == 1, "convert takes one maze");
  std::string format;
  const std::string file = MazeFiles(o.files)[0];
  const std::string text = FormatMazeText(LoadMaze(file, &format));
  if (o.out.empty()) {
    std::cout << text;
  } else {
    WriteTextFile(o.out, text);
    std::printf("%s (%s) -> %s (text)\n", file.c_str(), format.c_str(), o.out.c_str());
  }
  return kExitPassed;
}

int MazeGenerate(const MazeOptions& o) {
  GenerateOptions g;
  const size_t x = o.size.find('x');
  UNIMOUSE_THROW_UNLESS(x != std::string::npos, "--size is WIDTHxHEIGHT, e.g. 16x16");
  try {
    g.width = std::stoi(o.size.substr(0, x));
    g.height = std::stoi(o.size.substr(x + 1));
  } catch (const std::exception&) {
    throw InputError("--size is WIDTHxHEIGHT, e.g. 16x16, not '" + o.size + "'");
  }
  g.seed = o.seed;
  g.loops = o.loops;
  const std::string text = FormatMazeText(GenerateMaze(g));
  if (o.out.empty()) {
    std::cout << text;
  } else {
    WriteTextFile(o.out, text);
    std::printf("%s: %dx%d maze, seed %llu\n", o.out.c_str(), g.width, g.height,
                static_cast<unsigned long long>(g.seed));
  }
  return kExitPassed;
}

void AddMazeCommands(CommandLine& cli) {
  auto maze = std::make_shared<MazeOptions>();
  CLI::App* maze_cmd = cli.app().add_subcommand(
      "maze", "maze tools: show, check, solve, explore, plot, convert, generate");
  maze_cmd->require_subcommand(1);
  auto with_files = [&](CLI::App* cmd) {
    cmd->add_option("mazes", maze->files,
                    "maze files, bundled maze names, or directories searched for *.txt")
        ->required();
  };
  auto with_outputs = [&](CLI::App* cmd) {
    cmd->add_flag("--json", maze->json, "print JSON instead of text");
    cmd->add_option("--csv", maze->csv, "write a one-line-per-maze summary to this CSV file");
  };
  CLI::App* show_cmd = maze_cmd->add_subcommand("show", "print mazes with size, start and goal");
  with_files(show_cmd);
  show_cmd->add_flag("--json", maze->json, "print JSON instead of text");
  CLI::App* check_cmd_maze = maze_cmd->add_subcommand("check", "validate maze files");
  with_files(check_cmd_maze);
  check_cmd_maze->add_flag("--strict", maze->strict,
                           "treat warnings (open perimeter, unreachable goal) as errors");
  with_outputs(check_cmd_maze);
  CLI::App* solve_cmd = maze_cmd->add_subcommand(
      "solve", "shortest paths by the modified and the traditional flood fill");
  with_files(solve_cmd);
  with_outputs(solve_cmd);
  solve_cmd
      ->add_option("--tie", maze->tie_rule,
                   "traditional flood fill tie rule: compass:<NESW order>, "
                   "relative:<FLRB order> or straight:<NESW order>")
      ->capture_default_str();
  CLI::App* explore_cmd =
      maze_cmd->add_subcommand("explore", "Adachi method 0 exploration, trip by trip");
  with_files(explore_cmd);
  with_outputs(explore_cmd);
  explore_cmd->add_option("--cell-time", maze->cell_time_s, "seconds per cell moved")
      ->capture_default_str();
  explore_cmd->add_option("--turn-time", maze->turn_time_s, "seconds per 90 degree turn")
      ->capture_default_str();
  explore_cmd->add_option("--plots", maze->plot_dir,
                          "write a PNG and an SVG of every trip into this directory");
  CLI::App* plot_cmd = maze_cmd->add_subcommand(
      "plot", "a top-down picture of a maze and its shortest path, PNG or SVG");
  plot_cmd->add_option("maze", maze->files, "maze file or bundled maze name")->required();
  plot_cmd->add_option("--out", maze->out, "FILE.png or FILE.svg")->required();
  plot_cmd->add_option("--path", maze->path, "modified (blue), traditional (orange), both or none")
      ->capture_default_str();
  plot_cmd->add_option("--tie", maze->tie_rule, "tie rule of the traditional flood fill")
      ->capture_default_str();
  plot_cmd->add_flag("--costs", maze->costs, "write each cell's distance to the goal in it");
  CLI::App* convert_cmd = maze_cmd->add_subcommand(
      "convert", "read a maze in any format (text, .num, binary .maz) and write the text format");
  convert_cmd->add_option("maze", maze->files, "maze file")->required();
  convert_cmd->add_option("--out", maze->out, "file to write instead of printing");
  CLI::App* generate_cmd = maze_cmd->add_subcommand(
      "generate", "a random maze under the classic rules, in the text format");
  generate_cmd->add_option("--size", maze->size, "WIDTHxHEIGHT")->capture_default_str();
  generate_cmd->add_option("--seed", maze->seed, "random seed")->capture_default_str();
  generate_cmd->add_option("--loops", maze->loops, "share of inner walls removed, 0 to 1")
      ->capture_default_str();
  generate_cmd->add_option("--out", maze->out, "file to write instead of printing");

  cli.Add(show_cmd, [maze] { return MazeShow(*maze); });
  cli.Add(check_cmd_maze, [maze] { return MazeCheck(*maze); });
  cli.Add(solve_cmd, [maze] { return MazeSolve(*maze); });
  cli.Add(explore_cmd, [maze] { return MazeExplore(*maze); });
  cli.Add(plot_cmd, [maze] { return MazePlot(*maze); });
  cli.Add(convert_cmd, [maze] { return MazeConvert(*maze); });
  cli.Add(generate_cmd, [maze] { return MazeGenerate(*maze); });
}

}  // namespace unimouse
