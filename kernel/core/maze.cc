// SPDX-License-Identifier: GPL-3.0-or-later
#include "maze.h"

#include <algorithm>
#include <filesystem>
#include <numbers>
#include <string_view>

#include "install_paths.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

[[noreturn]] void FailAt(const std::string& file, size_t line_index, size_t column_index,
                         const std::string& reason) {
  throw InputError(file + ":" + std::to_string(line_index + 1) + ":" +
                   std::to_string(column_index + 1) + ": " + reason);
}

std::vector<std::string> SplitLines(const std::string& text) {
  std::vector<std::string> lines;
  size_t begin = 0;
  while (begin <= text.size()) {
    size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(begin, end - begin);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(std::move(line));
    begin = end + 1;
  }
  // trailing blank lines carry nothing
  while (!lines.empty() && lines.back().find_first_not_of(" \t") == std::string::npos) {
    lines.pop_back();
  }
  return lines;
}

}  // namespace

void CheckMazeSize(int64_t width, int64_t height, const std::string& file) {
  if (width > kMaxMazeSide_cells || height > kMaxMazeSide_cells) {
    throw InputError(file + ": a " + std::to_string(width) + " x " + std::to_string(height) +
                     " maze is larger than the " + std::to_string(kMaxMazeSide_cells) + " x " +
                     std::to_string(kMaxMazeSide_cells) + " cells unimouse reads (docs/limits.md)");
  }
}

double HeadingYaw(Heading h) { return static_cast<int>(h) * std::numbers::pi / 2; }

MazeDimensions DimensionsOf(MazeClass c) {
  // the half-size rules halve the cell and the wall's thickness and height
  if (c == MazeClass::kHalfSize) return {0.09, 0.006, 0.025};
  return {0.18, 0.012, 0.05};
}

MazeClass DefaultMazeClass(int width, int height) {
  return std::max(width, height) > kClassicMaxSide_cells ? MazeClass::kHalfSize
                                                         : MazeClass::kClassic;
}

const char* MazeClassName(MazeClass c) { return c == MazeClass::kHalfSize ? "half" : "classic"; }

Maze::Maze(int width, int height)
    : width_(width),
      height_(height),
      horizontal_(static_cast<size_t>(width) * (height + 1), 0),
      vertical_(static_cast<size_t>(width + 1) * height, 0) {
  UNIMOUSE_DEMAND(width > 0 && height > 0 && width <= kMaxMazeSide_cells &&
                  height <= kMaxMazeSide_cells);
  set_goals(CentreCells(width, height));
  set_class(DefaultMazeClass(width, height));
}

void Maze::set_goals(std::vector<Cell> goals) {
  is_goal_.assign(static_cast<size_t>(width_) * height_, 0);
  for (const Cell& c : goals) {
    UNIMOUSE_DEMAND(Contains(c));
    is_goal_[c.y * width_ + c.x] = 1;
  }
  goals_ = std::move(goals);
}

bool Maze::HasWall(Cell c, Heading h) const {
  switch (h) {
    case Heading::kNorth:
      return HasHorizontalWall(c.x, c.y + 1);
    case Heading::kSouth:
      return HasHorizontalWall(c.x, c.y);
    case Heading::kEast:
      return HasVerticalWall(c.x + 1, c.y);
    case Heading::kWest:
      return HasVerticalWall(c.x, c.y);
  }
  return false;
}

void Maze::SetWall(Cell c, Heading h, bool present) {
  const uint8_t v = present ? 1 : 0;
  switch (h) {
    case Heading::kNorth:
      horizontal_[(c.y + 1) * width_ + c.x] = v;
      break;
    case Heading::kSouth:
      horizontal_[c.y * width_ + c.x] = v;
      break;
    case Heading::kEast:
      vertical_[c.y * (width_ + 1) + c.x + 1] = v;
      break;
    case Heading::kWest:
      vertical_[c.y * (width_ + 1) + c.x] = v;
      break;
  }
}

void FaceStartTowardsItsExit(Maze& maze) {
  if (!maze.HasWall(maze.start(), Heading::kNorth)) return;
  for (Heading h : {Heading::kEast, Heading::kWest, Heading::kSouth}) {
    if (!maze.HasWall(maze.start(), h)) {
      maze.set_start(maze.start(), h);
      return;
    }
  }
}

std::vector<Cell> CentreCells(int width, int height) {
  std::vector<Cell> cells;
  for (int y = (height - 1) / 2; y <= height / 2; ++y) {
    for (int x = (width - 1) / 2; x <= width / 2; ++x) {
      cells.push_back({x, y});
    }
  }
  return cells;
}

Maze ParseMazeText(const std::string& text, const std::string& file) {
  std::vector<std::string> lines = SplitLines(text);

  // the maze is the leading block of drawing lines; free text may follow it
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find_first_not_of(' ') == std::string::npos ||
        std::string("o+| -").find(lines[i][0]) == std::string::npos) {
      lines.resize(i);
      break;
    }
  }
  if (lines.size() < 3 || lines.size() % 2 == 0) {
    FailAt(file, lines.empty() ? 0 : lines.size() - 1, 0,
           "a maze has an odd number of lines, at least 3 (post rows and cell rows alternate); "
           "found " +
               std::to_string(lines.size()));
  }
  // trailing spaces are not significant; a short cell row is padded
  for (auto& line : lines) {
    line.erase(line.find_last_not_of(' ') + 1);
  }
  // the north edge sets the width: 4 characters a cell and a post at the end
  if (lines[0].size() < 4 || (lines[0].size() - 1) % 4 == 1 || (lines[0].size() - 1) % 4 == 2) {
    FailAt(file, 0, lines[0].size(),
           "the first line must be a row of posts 'o---o---o', 4 characters "
           "per cell; it has " +
               std::to_string(lines[0].size()) + " characters");
  }
  CheckMazeSize(static_cast<int64_t>((lines[0].size() + 2) / 4),
                static_cast<int64_t>((lines.size() - 1) / 2), file);
  const int width = static_cast<int>((lines[0].size() + 2) / 4);
  const size_t row_length = static_cast<size_t>(4 * width + 1);
  const int height = static_cast<int>((lines.size() - 1) / 2);
  Maze maze(width, height);

  bool has_start = false;
  std::vector<Cell> goals;
  for (size_t i = 0; i < lines.size(); ++i) {
    std::string& line = lines[i];
    if (line.size() > row_length) {
      FailAt(file, i, row_length,
             "line is longer than the first line (" + std::to_string(row_length) +
                 " characters): ragged maze");
    }
    line.resize(row_length, ' ');
    const bool post_row = i % 2 == 0;
    for (int x = 0; x <= width; ++x) {
      const size_t col = static_cast<size_t>(4 * x);
      if (post_row) {
        const int y = height - static_cast<int>(i / 2);
        // posts may be left out where no wall touches them
        if (line[col] != 'o' && line[col] != '+' && line[col] != ' ') {
          FailAt(file, i, col,
                 std::string("expected a post 'o' or '+', found '") + line[col] + "'");
        }
        if (x == width) break;
        const std::string_view span(line.data() + col + 1, 3);
        if (span == "---") {
          maze.SetWall({x, y < height ? y : height - 1},
                       y < height ? Heading::kSouth : Heading::kNorth, true);
        } else if (span != "   ") {
          FailAt(file, i, col + 1,
                 "expected a wall '---' or three spaces, found '" + std::string(span) + "'");
        }
      } else {
        const int y = height - 1 - static_cast<int>(i / 2);
        const char wall = line[col];
        if (wall == '|') {
          maze.SetWall({x < width ? x : width - 1, y}, x < width ? Heading::kWest : Heading::kEast,
                       true);
        } else if (wall != ' ') {
          FailAt(file, i, col, std::string("expected a wall '|' or a space, found '") + wall + "'");
        }
        if (x == width) break;
        for (size_t k = 1; k <= 3; ++k) {
          const char c = line[col + k];
          if (k == 2 && c == 'S') {
            if (has_start) FailAt(file, i, col + k, "a second start 'S'; a maze has one start");
            has_start = true;
            maze.set_start({x, y}, Heading::kNorth);
          } else if (k == 2 && c == 'G') {
            goals.push_back({x, y});
          } else if (c != ' ') {
            FailAt(file, i, col + k,
                   std::string("unexpected '") + c +
                       "' inside a cell (only 'S' or 'G' at its centre)");
          }
        }
      }
    }
  }

  FaceStartTowardsItsExit(maze);
  if (!goals.empty()) {
    // south to north, west to east, as CentreCells lists them
    std::sort(goals.begin(), goals.end(),
              [](Cell a, Cell b) { return a.y != b.y ? a.y < b.y : a.x < b.x; });
    maze.set_goals(goals);
  }
  return maze;
}

std::string FormatMazeText(const Maze& maze) {
  std::string out;
  for (int y = maze.height() - 1; y >= -1; --y) {
    // from the north edge down: the post row north of cell row y, then the row itself
    for (int x = 0; x < maze.width(); ++x) {
      out += 'o';
      out += maze.HasHorizontalWall(x, y + 1) ? "---" : "   ";
    }
    out += "o\n";
    if (y < 0) break;
    for (int x = 0; x <= maze.width(); ++x) {
      out += maze.HasVerticalWall(x, y) ? '|' : ' ';
      if (x == maze.width()) break;
      const Cell c{x, y};
      out += c == maze.start() ? " S " : maze.IsGoal(c) ? " G " : "   ";
    }
    out += '\n';
  }
  return out;
}

std::vector<std::string> FindMazeFiles(const std::vector<std::string>& names) {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  for (const auto& name : names) {
    if (IsDirectory(name)) {
      std::vector<std::string> found;
      for (const auto& e : fs::recursive_directory_iterator(name)) {
        if (e.is_regular_file() && e.path().extension() == ".txt") {
          found.push_back(e.path().string());
        }
      }
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else {
      files.push_back(ResolveDataFile(name, "mazes/", ".txt"));
    }
  }
  return files;
}

}  // namespace unimouse
