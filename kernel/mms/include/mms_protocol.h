// SPDX-License-Identifier: GPL-3.0-or-later
// The mms text protocol's logic tier: a mouse on the discrete maze that answers one command line
// at a time, keeps mms's stats and score, and remembers what the program asked to display.
//
// Positions are on mms's half-cell grid: cell (x, y) has its centre at (2x + 1, 2y + 1), the
// points between two centres are wall places, the points with both coordinates even are posts.
// A half-step is blocked when it would land on a post, on a wall, or outside the maze; `wall*`
// queries and moves use that one rule. Distances count half-steps, as mms 1.2's code does, so
// `moveForward 1` is 2 (docs/mms.md).
#ifndef UNIMOUSE_MMS_MMS_PROTOCOL_H_
#define UNIMOUSE_MMS_MMS_PROTOCOL_H_

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

#include "firmware_beliefs.h"
#include "maze.h"

namespace unimouse {

/// Returns a number as mms prints it, as printf's %g does: 2000, 7.7.
std::string MmsNumber(double value);

/// What the program's clock charges for moving; all of it stays out of the protocol's replies.
struct MmsTiming {
  double cell_time_s = 0.5;  ///< one cell straight on; a half-step costs half
  double turn_time_s = 0.5;  ///< a 90 degree turn in place; a 45 degree turn costs half
};

/// The answer to one command line.
struct MmsResponse {
  enum class Kind { kReply, kNoReply, kInvalid };
  Kind kind = Kind::kNoReply;
  std::string reply;    ///< the line to send back, without its newline (kReply)
  std::string problem;  ///< why the line was dropped (kInvalid)
  bool motion = false;  ///< a move or a turn
  bool crash = false;   ///< the move replied `crash`
  std::string note;     ///< something the log should say, e.g. a wrong wall reading; or ""
};

/// mms's stats (getStat): distances in half-steps, -1 where no value exists yet.
struct MmsStats {
  long total_distance = 0;
  long total_turns = 0;
  double total_effective_distance = 0;
  bool in_run = false;
  long current_run_distance = 0;
  long current_run_turns = 0;
  double current_run_effective_distance = 0;
  bool has_best_run = false;
  long best_run_distance = 0;
  long best_run_turns = 0;
  double best_run_effective_distance = 0;
  bool reset_penalty_pending = false;  ///< ackReset charges 15 to the next run

  /// Returns the score: best run turns and effective distance plus a tenth of the totals, or
  /// 2000 when no run has reached the goal. Lower is better.
  double Score() const;
  /// Returns the value getStat answers for `name`, or false for a name mms does not know.
  bool Find(const std::string& name, double* value) const;
  /// Returns every stat by its getStat name, with getStat's values (-1 where none exists yet).
  nlohmann::json ToJson() const;
};

/// What carrying out one move on a body took.
struct MmsMotion {
  double time_s = 0;     ///< the contest time it took
  bool contact = false;  ///< the robot touched a wall on the way (a `crash` only when strict)
  /// "" when the move finished; else how the run ends ("stuck", "off_course", "error")
  std::string failure;
  std::string why;  ///< the failure's reason, for the log and result.json
};

/// A robot that carries out the moves the discrete world allows (the physics tier): the world
/// keeps the mouse's cell, heading and stats, the body moves, senses and tells the time taken.
class MmsBody {
 public:
  virtual ~MmsBody() = default;
  /// Drives `cells` whole cells straight on, stopping at the last one's centre; the world has
  /// checked that no wall is on the way.
  virtual MmsMotion Drive(long cells) = 0;
  /// Turns in place by `quarter_turns` (positive counter-clockwise: left).
  virtual MmsMotion Turn(int quarter_turns) = 0;
  /// Returns whether the robot's sensors see a wall on `side` of its cell (0 front, 1 left,
  /// 2 back, 3 right), or nothing where it has no reading for that side.
  virtual std::optional<bool> SensedWall(int side) = 0;
  /// Puts the robot back at the start, at rest (ackReset).
  virtual void Reset() = 0;
};

/// How the `wall*` answers of a body's sensors compared with the maze.
struct MmsWallCounts {
  long sensed = 0;    ///< answered from the sensors
  long wrong = 0;     ///< of those, not what the maze has
  long unsensed = 0;  ///< answered from the maze: no reading for that side or distance
};

class MmsWorld {
 public:
  /// Places the mouse at (0, 0) facing north in `maze`; the goal is the maze's goal cells.
  MmsWorld(const Maze& maze, const MmsTiming& timing);

  /// Carries out one command line (without its newline; a trailing '\r' and spaces are allowed).
  MmsResponse Handle(const std::string& line);

  const MmsStats& stats() const { return stats_; }
  /// Returns whether the mouse has stopped in a goal cell (its centre, or an edge mms counts in
  /// it).
  bool goal_reached() const { return goal_reached_; }
  /// Returns the contest time the moves took so far.
  double contest_time_s() const { return contest_time_s_; }
  long moves() const { return moves_; }
  long crashes() const { return crashes_; }
  /// Returns the mouse's cell, or (-1, -1) between two cells.
  Cell cell() const;
  /// Returns the heading in eighths of a turn counter-clockwise from east (2 is north).
  int direction() const { return direction_; }
  /// Carries out the moves on `body` from now on (not owned): whole cells and quarter turns only,
  /// the contest time is the body's. `true_walls`: `wall*` answers come from the maze, not the
  /// body's sensors.
  void SetBody(MmsBody* body, bool true_walls);
  /// Whether a move or turn the body carried out but grazed a wall on replies `crash` (the
  /// strict reading) instead of `ack`: an mms program takes `crash` for a move that did not
  /// happen, and loses its position.
  void set_contact_is_crash(bool strict) { contact_is_crash_ = strict; }
  /// Returns the moves and turns carried out that touched a wall on the way.
  long grazes() const { return grazes_; }
  /// Returns the first move the body could not finish (its `failure` is "" while none).
  const MmsMotion& body_failure() const { return body_failure_; }
  const MmsWallCounts& wall_counts() const { return wall_counts_; }
  /// Returns the walls, colours and texts the program set: {"walls": [...], "colors": [...],
  /// "texts": [...]}, ordered by cell.
  nlohmann::json Display() const;
  /// Returns the same as the model every picture draws: set walls known and present, cleared
  /// ones known and open, the colours and the texts.
  FirmwareBeliefs Beliefs() const;

 private:
  bool Blocked(int px, int py) const;
  bool WallWithin(int direction, long half_steps) const;
  MmsResponse Move(long half_steps);
  MmsResponse Turn(int eighths);
  // adds a body's move to the clock, keeps its first failure; returns whether it touched a wall
  bool BodyMoved(const MmsMotion& motion);
  MmsResponse WallQuery(int relative, long half_steps);
  MmsResponse Show(const std::vector<std::string>& tokens, const std::string& line);
  void Stopped();
  /// The cell mms counts the mouse in: between two cells, the one east or north of the edge.
  Cell Location() const;

  const Maze& maze_;
  MmsTiming timing_;
  int px_ = 1;
  int py_ = 1;
  int direction_ = 2;
  MmsStats stats_;
  bool goal_reached_ = false;
  double contest_time_s_ = 0;
  long moves_ = 0;
  long crashes_ = 0;
  long grazes_ = 0;
  bool contact_is_crash_ = false;
  MmsBody* body_ = nullptr;
  bool true_walls_ = false;
  MmsMotion body_failure_;
  MmsWallCounts wall_counts_;
  std::map<std::pair<int, int>, std::map<char, bool>> walls_;  // cell -> side -> set
  std::map<std::pair<int, int>, char> colors_;
  std::map<std::pair<int, int>, std::string> texts_;
};

}  // namespace unimouse

#endif  // UNIMOUSE_MMS_MMS_PROTOCOL_H_
