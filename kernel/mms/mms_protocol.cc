// SPDX-License-Identifier: GPL-3.0-or-later
#include "mms_protocol.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <vector>

namespace unimouse {
namespace {

// the eight headings, counter-clockwise from east, as half-cell steps
constexpr int kDx[8] = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr int kDy[8] = {0, 1, 1, 1, 0, -1, -1, -1};

// the wall sides in the order of the debug channel's bits 1, 2, 4, 8
constexpr std::string_view kSides = "nesw";

// a straight move of d half-steps counts d up to 2, then d / 2 + 1
double Effective(long d) { return d <= 2 ? double(d) : double(d) / 2 + 1; }

// mms separates tokens by one or more spaces, and by nothing else
std::vector<std::string> Tokens(const std::string& line) {
  std::vector<std::string> tokens;
  size_t i = 0;
  while (i < line.size()) {
    if (line[i] == ' ') {
      ++i;
      continue;
    }
    const size_t end = std::min(line.find(' ', i), line.size());
    tokens.push_back(line.substr(i, end - i));
    i = end;
  }
  return tokens;
}

// an integer in the range of a C int, as mms reads them
bool ParseInt(const std::string& token, long* value) {
  const char* end = token.data() + token.size();
  int parsed = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), end, parsed);
  *value = parsed;
  return ec == std::errc() && ptr == end;
}

MmsResponse Reply(std::string text) {
  MmsResponse response;
  response.kind = MmsResponse::Kind::kReply;
  response.reply = std::move(text);
  return response;
}
MmsResponse Invalid(std::string problem) {
  MmsResponse response;
  response.kind = MmsResponse::Kind::kInvalid;
  response.problem = std::move(problem);
  return response;
}
MmsResponse Bool(bool value) { return Reply(value ? "true" : "false"); }

}  // namespace

std::string MmsNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

double MmsStats::Score() const {
  if (!has_best_run) return 2000;
  return double(best_run_turns) + best_run_effective_distance +
         0.1 * (double(total_turns) + total_effective_distance);
}

bool MmsStats::Find(const std::string& name, double* value) const {
  const double none = -1;
  if (name == "total-distance") {
    *value = double(total_distance);
  } else if (name == "total-turns") {
    *value = double(total_turns);
  } else if (name == "total-effective-distance") {
    *value = total_effective_distance;
  } else if (name == "best-run-distance") {
    *value = has_best_run ? double(best_run_distance) : none;
  } else if (name == "best-run-turns") {
    *value = has_best_run ? double(best_run_turns) : none;
  } else if (name == "best-run-effective-distance") {
    *value = has_best_run ? best_run_effective_distance : none;
  } else if (name == "current-run-distance") {
    *value = in_run ? double(current_run_distance) : none;
  } else if (name == "current-run-turns") {
    *value = in_run ? double(current_run_turns) : none;
  } else if (name == "current-run-effective-distance") {
    *value = in_run ? current_run_effective_distance : none;
  } else if (name == "score") {
    *value = Score();
  } else {
    return false;
  }
  return true;
}

nlohmann::json MmsStats::ToJson() const {
  nlohmann::json stats = nlohmann::json::object();
  for (const char* name :
       {"total-distance", "total-turns", "total-effective-distance", "best-run-distance",
        "best-run-turns", "best-run-effective-distance", "current-run-distance",
        "current-run-turns", "current-run-effective-distance", "score"}) {
    double value = 0;
    Find(name, &value);
    stats[name] = value == std::floor(value) ? nlohmann::json(long(value)) : nlohmann::json(value);
  }
  return stats;
}

MmsWorld::MmsWorld(const Maze& maze, const MmsTiming& timing) : maze_(maze), timing_(timing) {}

Cell MmsWorld::cell() const {
  if (px_ % 2 == 0 || py_ % 2 == 0) return {-1, -1};
  return {px_ / 2, py_ / 2};
}

bool MmsWorld::Blocked(int px, int py) const {
  if (px < 0 || py < 0 || px > 2 * maze_.width() || py > 2 * maze_.height()) return true;
  const bool x_even = px % 2 == 0;
  const bool y_even = py % 2 == 0;
  if (x_even && y_even) return true;
  if (x_even) return maze_.HasVerticalWall(px / 2, py / 2);
  if (y_even) return maze_.HasHorizontalWall(px / 2, py / 2);
  return false;
}

bool MmsWorld::WallWithin(int direction, long half_steps) const {
  int px = px_;
  int py = py_;
  // mms looks at least at the wall right ahead: a count of 0 or less is 1
  for (long k = 0; k < std::max(half_steps, 1L); ++k) {
    px += kDx[direction];
    py += kDy[direction];
    if (Blocked(px, py)) return true;
  }
  return false;
}

MmsResponse MmsWorld::Move(long half_steps) {
  MmsResponse response = Reply("ack");
  response.motion = true;
  ++moves_;
  // not a move: no distance, a half-cell for a body (it moves whole cells only), or a wall right
  // ahead; mms answers crash at once, charging nothing and starting no run
  if (half_steps < 1 || (body_ != nullptr && half_steps % 2 != 0) ||
      Blocked(px_ + kDx[direction_], py_ + kDy[direction_])) {
    response.reply = "crash";
    response.crash = true;
    ++crashes_;
    return response;
  }
  // every move from the start cell begins a run afresh, with the penalty of a reset before it
  // in the run's and the total effective distance
  if (Location() == Cell{0, 0}) {
    const double penalty = stats_.reset_penalty_pending ? 15 : 0;
    stats_.in_run = true;
    stats_.current_run_distance = 0;
    stats_.current_run_turns = 0;
    stats_.current_run_effective_distance = penalty;
    stats_.total_effective_distance += penalty;
    stats_.reset_penalty_pending = false;
  }

  // mms charges the steps asked for, even those a wall stops
  stats_.total_distance += half_steps;
  stats_.total_effective_distance += Effective(half_steps);
  if (stats_.in_run) {
    stats_.current_run_distance += half_steps;
    stats_.current_run_effective_distance += Effective(half_steps);
  }
  long moved = 0;
  while (moved < half_steps && !Blocked(px_ + kDx[direction_], py_ + kDy[direction_])) {
    px_ += kDx[direction_];
    py_ += kDy[direction_];
    ++moved;
  }
  bool contact = false;
  if (body_ == nullptr) {
    contest_time_s_ += double(moved) * timing_.cell_time_s / 2;
  } else if (moved > 0) {
    // from a cell's centre, a wall stops the mouse at a centre too: `moved` is even
    contact = BodyMoved(body_->Drive(moved / 2));
  }
  if (moved < half_steps || contact) {
    response.reply = "crash";
    response.crash = true;
    ++crashes_;
  }
  Stopped();
  return response;
}

Cell MmsWorld::Location() const { return {px_ / 2, py_ / 2}; }

void MmsWorld::Stopped() {
  // as mms places the mouse: the edge between two cells counts as the one east or north of it,
  // so a stop on the edge between two goal cells finishes a run
  const Cell here = Location();
  const auto& goals = maze_.goals();
  const bool in_goal = std::find(goals.begin(), goals.end(), here) != goals.end();
  goal_reached_ = goal_reached_ || in_goal;
  if (!stats_.in_run) return;
  if (in_goal) {
    const double run_cost =
        double(stats_.current_run_turns) + stats_.current_run_effective_distance;
    const double best_cost = double(stats_.best_run_turns) + stats_.best_run_effective_distance;
    if (!stats_.has_best_run || run_cost < best_cost) {
      stats_.has_best_run = true;
      stats_.best_run_distance = stats_.current_run_distance;
      stats_.best_run_turns = stats_.current_run_turns;
      stats_.best_run_effective_distance = stats_.current_run_effective_distance;
    }
    stats_.in_run = false;
  } else if (here == Cell{0, 0}) {
    stats_.in_run = false;
  }
}

MmsResponse MmsWorld::Turn(int eighths) {
  MmsResponse response = Reply("ack");
  response.motion = true;
  ++moves_;
  // a body turns by quarters only: a 45 degree turn is impossible, as a move into a wall
  if (body_ != nullptr && eighths % 2 != 0) {
    response.reply = "crash";
    response.crash = true;
    ++crashes_;
    return response;
  }
  direction_ = (direction_ + eighths + 8) % 8;
  ++stats_.total_turns;
  if (stats_.in_run) ++stats_.current_run_turns;
  if (body_ == nullptr) {
    contest_time_s_ += std::abs(eighths) * timing_.turn_time_s / 2;
  } else if (BodyMoved(body_->Turn(eighths / 2))) {
    response.reply = "crash";
    response.crash = true;
    ++crashes_;
  }
  return response;
}

bool MmsWorld::BodyMoved(const MmsMotion& motion) {
  contest_time_s_ += motion.time_s;
  if (body_failure_.failure.empty()) body_failure_ = motion;
  // a move carried out is a move made, grazed or not, unless the strict reading is asked for
  grazes_ += motion.contact;
  return motion.contact && contact_is_crash_;
}

void MmsWorld::SetBody(MmsBody* body, bool true_walls) {
  body_ = body;
  true_walls_ = true_walls;
}

MmsResponse MmsWorld::WallQuery(int relative, long half_steps) {
  const int direction = (direction_ + relative) % 8;
  const bool maze = WallWithin(direction, half_steps);
  if (body_ == nullptr || true_walls_) return Bool(maze);
  // the sensors see the sides of the mouse's own cell, no farther and not diagonally
  std::optional<bool> seen;
  if (half_steps == 1 && relative % 2 == 0) seen = body_->SensedWall(relative / 2);
  if (!seen) {
    ++wall_counts_.unsensed;
    return Bool(maze);
  }
  ++wall_counts_.sensed;
  MmsResponse response = Bool(*seen);
  if (*seen != maze) {
    ++wall_counts_.wrong;
    static const char* const kHeadings[8] = {"east", "north-east", "north", "north-west",
                                             "west", "south-west", "south", "south-east"};
    const Cell here = cell();
    response.note = "wrong wall reading: the sensors " + std::string(*seen ? "see" : "miss") +
                    " a wall " + kHeadings[direction] + " of cell (" + std::to_string(here.x) +
                    ", " + std::to_string(here.y) + "); the maze has " + (maze ? "one" : "none");
  }
  return response;
}

MmsResponse MmsWorld::Handle(const std::string& raw) {
  std::string line = raw;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::vector<std::string> tokens = Tokens(line);
  if (tokens.empty()) return Invalid("empty line");
  const std::string& name = tokens[0];
  const size_t nargs = tokens.size() - 1;

  // an optional count, 1 when left out
  long count = 1;
  auto optional_count = [&]() { return nargs == 0 || (nargs == 1 && ParseInt(tokens[1], &count)); };

  if (name == "mazeWidth" || name == "mazeHeight") {
    if (nargs != 0) return Invalid("takes no argument");
    return Reply(std::to_string(name == "mazeWidth" ? maze_.width() : maze_.height()));
  }
  static const std::map<std::string, int> kWallQueries = {
      {"wallFront", 0}, {"wallFrontLeft", 1}, {"wallLeft", 2},  {"wallBackLeft", 3},
      {"wallBack", 4},  {"wallBackRight", 5}, {"wallRight", 6}, {"wallFrontRight", 7}};
  if (const auto query = kWallQueries.find(name); query != kWallQueries.end()) {
    if (!optional_count()) return Invalid("takes an optional integer number of half-cells");
    return WallQuery(query->second, count);
  }
  if (name == "moveForward" || name == "moveForwardHalf") {
    if (!optional_count()) return Invalid("takes an optional integer number of cells");
    return Move(name == "moveForward" ? 2 * count : count);
  }
  static const std::map<std::string, int> kTurns = {{"turnLeft", 2},   {"turnLeft90", 2},
                                                    {"turnRight", -2}, {"turnRight90", -2},
                                                    {"turnLeft45", 1}, {"turnRight45", -1}};
  if (const auto turn = kTurns.find(name); turn != kTurns.end()) {
    if (nargs != 0) return Invalid("takes no argument");
    return Turn(turn->second);
  }
  if (name == "wasReset") {
    if (nargs != 0) return Invalid("takes no argument");
    return Bool(false);
  }
  if (name == "ackReset") {
    if (nargs != 0) return Invalid("takes no argument");
    px_ = 1;
    py_ = 1;
    direction_ = 2;
    if (body_ != nullptr) body_->Reset();
    if (stats_.in_run) stats_.in_run = false;
    stats_.reset_penalty_pending = true;
    return Reply("ack");
  }
  if (name == "getStat") {
    double value = 0;
    if (nargs != 1) return Invalid("takes one stat name");
    if (!stats_.Find(tokens[1], &value)) return Invalid("unknown stat '" + tokens[1] + "'");
    return Reply(MmsNumber(value));
  }
  return Show(tokens, line);
}

// the display commands: no reply, out-of-range cells ignored as mms does
MmsResponse MmsWorld::Show(const std::vector<std::string>& tokens, const std::string& line) {
  const std::string& name = tokens[0];
  const size_t nargs = tokens.size() - 1;
  const MmsResponse done;
  if (name == "clearAllColor" || name == "clearAllText") {
    if (nargs != 0) return Invalid("takes no argument");
    if (name == "clearAllColor") {
      colors_.clear();
    } else {
      texts_.clear();
    }
    return done;
  }
  const bool known = name == "setWall" || name == "clearWall" || name == "setColor" ||
                     name == "clearColor" || name == "setText" || name == "clearText";
  if (!known) return Invalid("unknown command");
  long x = 0;
  long y = 0;
  if (nargs < 2 || !ParseInt(tokens[1], &x) || !ParseInt(tokens[2], &y)) {
    return Invalid("takes the integer cell X Y first");
  }
  const bool inside = x >= 0 && y >= 0 && x < maze_.width() && y < maze_.height();
  const std::pair<int, int> at{int(x), int(y)};
  if (name == "clearColor" || name == "clearText") {
    if (nargs != 2) return Invalid("takes X Y");
    if (name == "clearColor") {
      colors_.erase(at);
    } else {
      texts_.erase(at);
    }
    return done;
  }
  if (name == "setText") {
    // the text is everything after the third space, spaces included
    size_t space = std::string::npos;  // npos + 1 is 0: the first search starts at the beginning
    for (int n = 0; n < 3; ++n) {
      space = line.find(' ', space + 1);
      if (space == std::string::npos) break;
    }
    if (nargs < 3 || space == std::string::npos) return Invalid("takes X Y TEXT");
    // up to 10 characters, as mms reads the line (UTF-8); what the pictures cannot draw, a
    // control character or one beyond ASCII, is a '?' each
    std::string text;
    for (size_t i = space + 1; i < line.size() && text.size() < 10; ++i) {
      const auto byte = static_cast<unsigned char>(line[i]);
      text += byte >= 32 && byte <= 126 ? static_cast<char>(byte) : '?';
      if (byte >= 0x80) {
        while (i + 1 < line.size() && (static_cast<unsigned char>(line[i + 1]) & 0xC0) == 0x80) ++i;
      }
    }
    if (inside) texts_[at] = text;
    return done;
  }
  if (nargs != 3 || tokens[3].size() != 1) return Invalid("takes X Y and one letter");
  const char letter = tokens[3][0];
  if (name == "setColor") {
    if (!CellColourOf(letter)) {
      return Invalid("unknown colour '" + tokens[3] + "'");
    }
    if (inside) colors_[at] = letter;
    return done;
  }
  const size_t side = kSides.find(letter);
  if (side == std::string::npos) return Invalid("unknown side '" + tokens[3] + "' (n, e, s, w)");
  if (!inside) return done;
  const bool present = name == "setWall";
  walls_[at][letter] = present;

  // the neighbour across the edge sees the same wall
  const int dx[4] = {0, 1, 0, -1};
  const int dy[4] = {1, 0, -1, 0};
  const std::pair<int, int> next(at.first + dx[side], at.second + dy[side]);
  if (maze_.Contains({next.first, next.second})) walls_[next][kSides[(side + 2) % 4]] = present;
  return done;
}

nlohmann::json MmsWorld::Display() const {
  nlohmann::json walls = nlohmann::json::array();
  for (const auto& [at, sides] : walls_) {
    for (const auto& [side, present] : sides) {
      walls.push_back(
          {{"x", at.first}, {"y", at.second}, {"side", std::string(1, side)}, {"set", present}});
    }
  }
  nlohmann::json colors = nlohmann::json::array();
  for (const auto& [at, letter] : colors_) {
    colors.push_back({{"x", at.first}, {"y", at.second}, {"color", std::string(1, letter)}});
  }
  nlohmann::json texts = nlohmann::json::array();
  for (const auto& [at, text] : texts_) {
    texts.push_back({{"x", at.first}, {"y", at.second}, {"text", text}});
  }
  return {{"walls", walls}, {"colors", colors}, {"texts", texts}};
}

// the walls as the firmware debug channel reports them: a cleared side is known open
FirmwareBeliefs MmsWorld::Beliefs() const {
  FirmwareBeliefs beliefs;
  for (const auto& [at, sides] : walls_) {
    FirmwareBeliefs::CellWalls& w = beliefs.walls[at];
    for (const auto& [side, present] : sides) {
      const auto bit = static_cast<uint8_t>(1 << kSides.find(side));
      w.known |= bit;
      if (present) w.walls |= bit;
    }
  }
  beliefs.colours = colors_;
  beliefs.texts = texts_;
  return beliefs;
}

}  // namespace unimouse
