// SPDX-License-Identifier: GPL-3.0-or-later
// A rectangular micromouse maze: walls on the edges between cells, a start cell and heading,
// goal cells. Cell (0, 0) is the south-west corner; x grows east, y grows north.
#ifndef UNIMOUSE_CORE_MAZE_H_
#define UNIMOUSE_CORE_MAZE_H_

#include <cstdint>
#include <string>
#include <vector>

namespace unimouse {

/// Most cells on a side of a maze that anything reads or builds: 256 x 256 cells (the classic
/// contest maze is 16 x 16, the half-size one 32 x 32). A larger one is refused, not attempted.
inline constexpr int kMaxMazeSide_cells = 256;

/// Throws InputError naming `file` unless a `width` x `height` maze is within
/// kMaxMazeSide_cells a side; takes 64-bit sizes so that a huge one is named, not wrapped.
void CheckMazeSize(int64_t width, int64_t height, const std::string& file);

/// Compass headings, counter-clockwise from east as in the world frame.
enum class Heading : int { kEast = 0, kNorth = 1, kWest = 2, kSouth = 3 };

struct Cell {
  int x = 0;
  int y = 0;
  bool operator==(const Cell&) const = default;
};

/// Returns the heading's angle in radians (east 0, north pi/2).
double HeadingYaw(Heading h);

/// The contest a maze is built for: it sets the size of the cells and walls.
enum class MazeClass { kClassic, kHalfSize };

/// Maze geometry in metres: the lattice pitch of the posts (a cell's side), and the thickness
/// and height of walls and posts. docs/mazes.md cites the rules for both classes.
struct MazeDimensions {
  double cell_m = 0.18;
  double wall_thickness_m = 0.012;
  double wall_height_m = 0.05;
  bool operator==(const MazeDimensions&) const = default;
};

/// Returns the dimensions a contest's rules set: classic 180 mm cells with 12 mm thick, 50 mm
/// high walls (IEEE / All Japan classic rules); half-size 90 mm cells with 6 mm thick, 25 mm high
/// walls (NTF "Rules for Micromouse Halfsize", UKMARS half-size rules 2019).
MazeDimensions DimensionsOf(MazeClass c);

/// Most cells on a side of a classic maze (16 x 16); a larger maze is half-size (up to 32 x 32).
inline constexpr int kClassicMaxSide_cells = 16;

/// Returns the class a maze of this size is taken to be: half-size when a side is longer than
/// kClassicMaxSide_cells, else classic (a 16 x 16 half-size maze needs saying so).
MazeClass DefaultMazeClass(int width, int height);

/// Returns "classic" or "half".
const char* MazeClassName(MazeClass c);

class Maze {
 public:
  /// Creates a maze with no walls at all, start (0, 0) facing north, the centre as goal, and
  /// the dimensions of DefaultMazeClass.
  Maze(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  bool Contains(Cell c) const { return c.x >= 0 && c.y >= 0 && c.x < width_ && c.y < height_; }

  /// Returns whether the side `h` of cell `c` has a wall.
  bool HasWall(Cell c, Heading h) const;
  /// Sets or clears a wall; the neighbour sharing the edge sees the same wall.
  void SetWall(Cell c, Heading h, bool present);

  /// Walls on the east-west line y (0..height) south of cell row y, spanning column x.
  bool HasHorizontalWall(int x, int y) const { return horizontal_[y * width_ + x] != 0; }
  /// Walls on the north-south line x (0..width) west of column x, spanning row y.
  bool HasVerticalWall(int x, int y) const { return vertical_[y * (width_ + 1) + x] != 0; }

  Cell start() const { return start_; }
  Heading start_heading() const { return start_heading_; }
  const std::vector<Cell>& goals() const { return goals_; }
  /// Returns whether `c` is one of the goal cells, in constant time.
  bool IsGoal(Cell c) const { return Contains(c) && is_goal_[c.y * width_ + c.x] != 0; }
  void set_start(Cell c, Heading h) {
    start_ = c;
    start_heading_ = h;
  }
  /// Sets the goal cells; each must be inside the maze.
  void set_goals(std::vector<Cell> goals);

  MazeClass maze_class() const { return class_; }
  const MazeDimensions& dimensions() const { return dims_; }
  /// Builds the maze at another contest's dimensions (a 16 x 16 half-size maze, for one).
  void set_class(MazeClass c) {
    class_ = c;
    dims_ = DimensionsOf(c);
  }

 private:
  int width_;
  int height_;
  std::vector<uint8_t> horizontal_;  // width x (height + 1)
  std::vector<uint8_t> vertical_;    // (width + 1) x height
  Cell start_;
  Heading start_heading_ = Heading::kNorth;
  std::vector<Cell> goals_;
  std::vector<uint8_t> is_goal_;  // width x height: 1 on a goal cell
  MazeClass class_;
  MazeDimensions dims_;
};

/// Turns the start heading towards the start cell's opening: north, as in the classic rules,
/// unless north is walled, then the first open side of east, west and south.
void FaceStartTowardsItsExit(Maze& maze);

/// Returns the classic goal: the 1, 2 or 4 cells at the centre.
std::vector<Cell> CentreCells(int width, int height);

/// Parses the text format of posts ('o' or '+', or left out), '---' and '|' walls, 'S' and 'G'
/// cell markers; free text after the drawing is ignored. Without 'S' the start is (0, 0);
/// without 'G' the goal is the centre. Throws InputError with file:line:col.
Maze ParseMazeText(const std::string& text, const std::string& file);

/// Parses the mms .num format: one "X Y N E S W" line per cell (0/1 for each wall), any order.
/// Every shared wall must be recorded on both sides. Throws InputError with file:line:col.
Maze ParseMazeNum(const std::string& text, const std::string& file);

/// Parses a binary .maz: one byte per cell of a square maze (256 bytes for 16 x 16). The
/// standard layout is column-major from the south-west, bits N=1 E=2 S=4 W=8; other layouts
/// and bit orders circulate, so every combination is tried and the one that is consistent,
/// closed, and has the classic start (east wall, open north) wins. `layout` receives a
/// description of what was inferred.
Maze ParseMazeBinary(const std::string& bytes, const std::string& file, std::string* layout);

/// Reads a maze file in any of the formats above, told apart by content, not by extension.
/// `format` (optional) receives what was read: "text", "num" or the binary layout.
Maze LoadMaze(const std::string& path, std::string* format = nullptr);

/// Returns every maze file the names give: a file or a bundled maze's name as ResolveDataFile
/// finds it, a directory as the *.txt files under it, sorted. Throws InputError for a name that
/// is neither a file, a directory nor a bundled maze.
std::vector<std::string> FindMazeFiles(const std::vector<std::string>& names);

/// Writes the text format: 'o' posts, '---' and '|' walls, 'S' on the start, 'G' on every goal
/// cell; ParseMazeText reads it back to the same maze.
std::string FormatMazeText(const Maze& maze);

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_MAZE_H_
