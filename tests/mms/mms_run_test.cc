// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse mms` as a user runs it: programs written in mms style, in C++, Python and shell,
// against mazes; what result.json and the exit code say, and what the log shows.
#include "mms_run.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <pty.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>

#include "inline_assets.h"
#include "mms_clients.h"
#include "png_file.h"
#include "run_program.h"
#include "text_file.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;
using testing::FreshDirectory;

// 5 x 5 with a wall from the west side to the centre's east side: a left-wall follower walks
// north to (0, 2), turns right and follows the wall east into the centre (2, 2)
constexpr const char* kWallToTheCentreMaze = R"(o---o---o---o---o---o
|                   |
o   o   o   o   o   o
|                   |
o---o---o---o   o   o
|           |       |
o   o   o   o   o   o
|                   |
o   o   o   o   o   o
| S |               |
o---o---o---o---o---o
)";

struct MmsOutcome {
  testing::Outcome outcome;
  nlohmann::json result;  ///< null when no result.json was written
};

class MmsRunTest : public ::testing::Test {
 protected:
  std::string WriteFile(const std::string& name, const std::string& text) {
    const std::string path = dir_ + "/" + name;
    WriteTextFile(path, text);
    fs::permissions(path, fs::perms::owner_exec, fs::perm_options::add);
    return path;
  }

  MmsOutcome Mms(const std::string& arguments) {
    MmsOutcome run{testing::Unimouse("mms --out " + out_ + " " + arguments), nullptr};
    if (fs::exists(out_ + "/result.json")) {
      run.result = nlohmann::json::parse(ReadTextFile(out_ + "/result.json"));
    }
    return run;
  }

  // a shell client: `ask` sends a line and reads the reply into $reply
  std::string ShellClient(const std::string& body) {
    return WriteFile("client.sh", "#!/bin/sh\nask() { echo \"$1\"; read -r reply; }\n" + body);
  }

  std::string dir_ = FreshDirectory("mms");
  std::string out_ = dir_ + "/out";
  std::string open_maze_ = WriteFile("open.txt", testing::kOpenMaze5x5);
};

using testing::HavePython;
using testing::kFloodFillClient;
using testing::kLeftWallClient;

TEST_F(MmsRunTest, FloodFillClientReachesTheGoalOfTheBundledMaze) {
  const MmsOutcome run = Mms("--maze japan2018 -- " + kFloodFillClient);
  EXPECT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  ASSERT_TRUE(run.result.is_object()) << run.outcome.output;
  EXPECT_EQ(run.result["status"], "goal_reached");
  EXPECT_EQ(run.result["goal_reached"], true);
  EXPECT_EQ(run.result["maze_size"], nlohmann::json::parse("[16, 16]"));
  EXPECT_GT(run.result["moves"].get<int>(), 14);
  EXPECT_EQ(run.result["crashes"], 0);
  EXPECT_EQ(run.result["invalid_commands"], 0);
  // the client colours every cell it stood on, the start first
  EXPECT_EQ(run.result["display"]["colors"][0],
            nlohmann::json::parse(R"({"x": 0, "y": 0, "color": "c"})"));
  EXPECT_NE(run.outcome.output.find("flood fill starting"), std::string::npos);
  // the line docs/mms.md shows for this run, word for word
  const std::string page = ReadTextFile(UNIMOUSE_SOURCE_DIR "/docs/mms.md");
  const size_t shown = page.find("\nmms: goal_reached: ");
  ASSERT_NE(shown, std::string::npos);
  const std::string line = page.substr(shown + 1, page.find('\n', shown + 1) - shown - 1);
  EXPECT_NE(run.outcome.output.find(line), std::string::npos) << line << "\n" << run.outcome.output;
}

TEST_F(MmsRunTest, LeftWallPythonClientFollowsTheWallIntoTheCentre) {
  if (!HavePython()) GTEST_SKIP() << "no python3";
  const std::string maze = WriteFile("wall.txt", kWallToTheCentreMaze);
  const MmsOutcome run = Mms("--maze " + maze + " -- " + kLeftWallClient);
  EXPECT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  ASSERT_TRUE(run.result.is_object());
  EXPECT_EQ(run.result["status"], "goal_reached");
  // two cells north, a right turn, two cells east
  EXPECT_EQ(run.result["moves"], 5);
  EXPECT_DOUBLE_EQ(run.result["contest_time_s"].get<double>(), 2.5);
  EXPECT_EQ(run.result["display"]["texts"][0]["text"], "start here");
}

TEST_F(MmsRunTest, LeftWallClientRunsOutOfContestTimeWhereTheCentreIsAnIsland) {
  if (!HavePython()) GTEST_SKIP() << "no python3";
  // the open maze's centre has no wall to follow in: the follower circles the perimeter
  const MmsOutcome run = Mms("--maze " + open_maze_ + " --time-limit-s 30 -- " + kLeftWallClient);
  EXPECT_EQ(run.outcome.exit_code, 1) << run.outcome.output;
  ASSERT_TRUE(run.result.is_object());
  EXPECT_EQ(run.result["status"], "time_out");
  EXPECT_EQ(run.result["goal_reached"], false);
  EXPECT_GE(run.result["contest_time_s"].get<double>(), 30);
  EXPECT_EQ(run.result["score"], 2000);
}

TEST_F(MmsRunTest, ResultStatsOfAScriptedClientMatchTheHandWorkedValues) {
  // the sequence of mms_protocol_test's ScriptedMoves..., up to the crash, then the program ends
  const std::string client = ShellClient(R"(ask "moveForward 2"
ask turnRight
ask "moveForward 2"
ask "moveForward 3"
echo "$reply" >&2
)");
  const MmsOutcome run = Mms("--until-exit --maze " + open_maze_ + " -- " + client);
  EXPECT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  ASSERT_TRUE(run.result.is_object());
  EXPECT_EQ(run.result["status"], "goal_reached");
  EXPECT_EQ(run.result["moves"], 4);
  EXPECT_EQ(run.result["crashes"], 1);
  const nlohmann::json stats = nlohmann::json::parse(R"({
    "total-distance": 14, "total-turns": 1, "total-effective-distance": 10,
    "best-run-distance": 8, "best-run-turns": 1, "best-run-effective-distance": 6,
    "current-run-distance": -1, "current-run-turns": -1, "current-run-effective-distance": -1,
    "score": 8.1})");
  for (const auto& [name, value] : stats.items()) {
    EXPECT_DOUBLE_EQ(run.result["stats"][name].get<double>(), value.get<double>()) << name;
  }
  EXPECT_DOUBLE_EQ(run.result["score"].get<double>(), 8.1);
  // 2 + 2 + 2 cells at 0.5 s (the crash stops after two) and a quarter turn
  EXPECT_DOUBLE_EQ(run.result["contest_time_s"].get<double>(), 3.5);
  EXPECT_NE(run.outcome.output.find("crash"), std::string::npos);
}

// docs/mms.md: mms's goal is the centre; a maze file may mark another, which --centre-goal
// overrides
TEST_F(MmsRunTest, CentreGoalMakesTheCentreTheGoalWhateverTheMazeFileMarks) {
  // the open 5 x 5 maze with its goal marked in the north-east corner cell
  std::string text = testing::kOpenMaze5x5;
  const std::string dir = FreshDirectory("mms_centre_goal");
  // two cells north of the start: neither the marked goal nor the centre (2, 2)
  const std::string client = ShellClient(R"(ask "moveForward 2"
ask turnRight
ask "moveForward 2"
)");
  const std::string marked = dir + "/corner.txt";
  {
    // the last row's first line of cells is the north row: its last cell is (4, 4)
    const size_t row = text.find('\n') + 1;
    const size_t cell = text.find('|', row) + 2 + 4 * 4;
    ASSERT_EQ(text[cell], ' ') << text;
    text[cell] = 'G';
    std::ofstream(marked) << text;
  }
  MmsOutcome run = Mms("--maze " + marked + " -- " + client);
  EXPECT_EQ(run.result["goal_reached"], false) << run.outcome.output;
  run = Mms("--centre-goal --maze " + marked + " -- " + client);
  EXPECT_EQ(run.result["goal_reached"], true) << run.outcome.output;
  EXPECT_EQ(run.result["status"], "goal_reached") << run.outcome.output;
}

TEST_F(MmsRunTest, InvalidCommandsAreDroppedAndLoggedAndTheRunGoesOn) {
  const std::string client = ShellClient(R"(echo bogus
echo "setColor 0 0 X"
printf 'wallFront\t\n'
ask mazeWidth
echo "$reply" >&2
)");
  const MmsOutcome run = Mms("--maze " + open_maze_ + " -- " + client);
  EXPECT_EQ(run.outcome.exit_code, 3) << run.outcome.output;
  ASSERT_TRUE(run.result.is_object());
  EXPECT_EQ(run.result["status"], "program_exited");
  EXPECT_EQ(run.result["invalid_commands"], 3);
  EXPECT_EQ(run.result["commands"], 4);
  const std::string& log = run.outcome.output;
  EXPECT_NE(log.find("mms: line 1: invalid command 'bogus' dropped: unknown command"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("mms: line 2: invalid command 'setColor 0 0 X' dropped: unknown colour 'X'"),
            std::string::npos);
  EXPECT_NE(log.find("'wallFront\\x09'"), std::string::npos);
  EXPECT_NE(log.find("\n5\n"), std::string::npos) << "the reply to mazeWidth";
}

TEST_F(MmsRunTest, MazePngShowsWhatTheProgramDisplayedUnlessPicturesAreOff) {
  const std::string client = ShellClient("echo 'setColor 3 3 g'\necho 'setWall 1 1 n'\n");
  const MmsOutcome run = Mms("--maze " + open_maze_ + " -- " + client);
  EXPECT_EQ(run.result["display"]["colors"].size(), 1u);
  int width = 0, height = 0;
  const std::vector<uint8_t> rgb = ReadPng(out_ + "/maze.png", &width, &height);
  // cell (3, 3) of the 5 x 5 maze: centre (32 + 3 x 32, 160 - 3 x 32), 32 px cells
  const size_t at = static_cast<size_t>(((160 - 96 + 12) * width + 32 + 96 - 12) * 3);
  EXPECT_EQ((std::vector<int>{rgb[at], rgb[at + 1], rgb[at + 2]}), (std::vector<int>{0, 255, 0}));
  EXPECT_NE(ReadTextFile(out_ + "/maze.svg").find("believed-wall"), std::string::npos);

  fs::remove_all(out_);
  Mms("--no-pictures --maze " + open_maze_ + " -- " + client);
  EXPECT_TRUE(fs::exists(out_ + "/result.json"));
  EXPECT_FALSE(fs::exists(out_ + "/maze.png"));
  EXPECT_FALSE(fs::exists(out_ + "/maze.svg"));
}

TEST_F(MmsRunTest, ACrashEndsTheRunOnlyWhenAsked) {
  const std::string client = ShellClient("ask turnRight\nask moveForward\nask moveForward\n");
  const MmsOutcome mms_rule = Mms("--maze " + open_maze_ + " -- " + client);
  EXPECT_EQ(mms_rule.outcome.exit_code, 3);
  EXPECT_EQ(mms_rule.result["status"], "program_exited");
  EXPECT_EQ(mms_rule.result["crashes"], 2);
  const MmsOutcome contest_rule = Mms("--end-on-crash --maze " + open_maze_ + " -- " + client);
  EXPECT_EQ(contest_rule.outcome.exit_code, 1) << contest_rule.outcome.output;
  EXPECT_EQ(contest_rule.result["status"], "crash");
  EXPECT_EQ(contest_rule.result["crashes"], 1);
}

TEST_F(MmsRunTest, AProgramThatExitsEarlyIsAProgramError) {
  const MmsOutcome run = Mms("--maze " + open_maze_ + " -- " + ShellClient("exit 4\n"));
  EXPECT_EQ(run.outcome.exit_code, 3);
  EXPECT_EQ(run.result["status"], "program_exited");
  EXPECT_NE(run.result["reason"].get<std::string>().find("exited with code 4"), std::string::npos);
}

TEST_F(MmsRunTest, AProgramThatStopsSendingIsStoppedAfterTheReplyTimeout) {
  const std::string client = ShellClient("ask mazeWidth\nsleep 60\n");
  const auto start = std::chrono::steady_clock::now();
  const MmsOutcome run = Mms("--reply-timeout-s 0.3 --maze " + open_maze_ + " -- " + client);
  const double took_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(run.outcome.exit_code, 3) << run.outcome.output;
  EXPECT_EQ(run.result["status"], "program_hang");
  EXPECT_LT(took_s, 10);
}

// a misspelt command gets no reply, as in mms; a program that waits for one is told why it hung
TEST_F(MmsRunTest, AProgramWaitingForAReplyToAnInvalidCommandIsToldSo) {
  const MmsOutcome run = Mms("--reply-timeout-s 0.3 --maze " + open_maze_ + " -- " +
                             ShellClient("ask mazeWidth\nask movForward\n"));
  EXPECT_EQ(run.result["status"], "program_hang");
  EXPECT_EQ(run.result["reason"],
            "the program sent no command line for 0.3 s after its invalid command 'movForward' "
            "(line 2), which gets no reply (does it wait for one?)");
}

TEST_F(MmsRunTest, AProgramThatIsKilledIsAProgramError) {
  const MmsOutcome run = Mms("--maze " + open_maze_ + " -- " + ShellClient("kill -SEGV $$\n"));
  EXPECT_EQ(run.outcome.exit_code, 3);
  EXPECT_EQ(run.result["status"], "program_crashed");
}

TEST_F(MmsRunTest, AnInterruptedRunWritesItsResultAndExitsWithCode3) {
  // a program thinking for a long time; the signal once it has asked its first question
  const std::string client =
      ShellClient("ask mazeWidth\necho asked > " + dir_ + "/asked\nsleep 30\n");
  const testing::Outcome o = testing::Unimouse(
      "mms --reply-timeout-s 60 --out " + out_ + " --maze " + open_maze_ + " -- " + client +
      " >/dev/null 2>&1 & pid=$!; while [ ! -e " + dir_ +
      "/asked ]; do sleep 0.05; done; kill -INT $pid; wait $pid; echo exit=$?; true");
  EXPECT_NE(o.output.find("exit=3"), std::string::npos) << o.output;
  const nlohmann::json result = nlohmann::json::parse(ReadTextFile(out_ + "/result.json"));
  EXPECT_EQ(result["status"], "interrupted");
  EXPECT_EQ(result["reason"], "interrupted by SIGINT");
  EXPECT_EQ(result["exit_code"], 3);
  EXPECT_EQ(result["commands"], 1);
}

TEST_F(MmsRunTest, AFloodOfGarbageIsLoggedWithACapAndEndsByTheCommandLimit) {
  const std::string client = ShellClient(
      "head -c 300000 /dev/zero\nyes 'no such command' | head -n 50000\n"
      "while true; do echo wallFront; done\n");
  const MmsOutcome run = Mms("--max-commands 100000 --maze " + open_maze_ + " -- " + client);
  EXPECT_EQ(run.outcome.exit_code, 1) << run.outcome.output.substr(0, 2000);
  EXPECT_EQ(run.result["status"], "command_limit");
  // the zeros make one over-long line; 20 lines are shown, then one notice
  EXPECT_NE(run.outcome.output.find("longer than 4096 bytes"), std::string::npos);
  EXPECT_NE(run.outcome.output.find("more invalid commands are dropped"), std::string::npos);
  EXPECT_LT(run.outcome.output.size(), 10000u);
}

TEST_F(MmsRunTest, TheViewerGoesWithThePhysicsTierOnly) {
  const MmsOutcome run = Mms("--view --maze " + open_maze_ + " -- " + kFloodFillClient);
  EXPECT_EQ(run.outcome.exit_code, 2);
  EXPECT_EQ(run.result["status"], "error");
  EXPECT_EQ(run.result["reason"], "--view goes with --physical");
}

TEST_F(MmsRunTest, BadInputExitsTwoAndReplacesAStaleResult) {
  Mms("--maze " + open_maze_ + " -- " + ShellClient("exit 0\n"));
  const MmsOutcome missing = Mms("--maze " + dir_ + "/nowhere.txt -- " + kFloodFillClient);
  EXPECT_EQ(missing.outcome.exit_code, 2);
  EXPECT_EQ(missing.result["status"], "error");
  const MmsOutcome no_program = Mms("--maze " + open_maze_ + " -- " + dir_ + "/no-such-program");
  EXPECT_EQ(no_program.outcome.exit_code, 2);
  EXPECT_NE(no_program.outcome.output.find("cannot run"), std::string::npos);
  EXPECT_EQ(Mms("--reply-timeout-s 0 -- " + kFloodFillClient).outcome.exit_code, 2);
}

// the goal cells reachable from the start: a maze the flood fill must solve
bool Solvable(const Maze& maze) {
  std::vector<bool> seen(maze.width() * maze.height(), false);
  std::deque<Cell> queue = {{0, 0}};
  seen[0] = true;
  const int dx[4] = {1, 0, -1, 0};
  const int dy[4] = {0, 1, 0, -1};
  while (!queue.empty()) {
    const Cell c = queue.front();
    queue.pop_front();
    for (const Cell& goal : maze.goals()) {
      if (c == goal) return true;
    }
    for (int h = 0; h < 4; ++h) {
      const Cell n{c.x + dx[h], c.y + dy[h]};
      if (maze.HasWall(c, Heading(h)) || !maze.Contains(n) || seen[n.y * maze.width() + n.x]) {
        continue;
      }
      seen[n.y * maze.width() + n.x] = true;
      queue.push_back(n);
    }
  }
  return false;
}

// the solvable classic mazes of the collection beside the project, sorted; and how many it has
std::vector<fs::path> SolvableClassicMazes(size_t* all = nullptr) {
  const std::string shared = testing::SharedMazesDir();
  std::vector<fs::path> files;
  if (shared.empty()) return files;
  for (const auto& entry : fs::directory_iterator(shared + "/classic")) {
    if (entry.path().extension() == ".txt") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  if (all != nullptr) *all = files.size();
  std::erase_if(files, [](const fs::path& file) { return !Solvable(LoadMaze(file.string())); });
  return files;
}

TEST_F(MmsRunTest, FloodFillClientReachesTheGoalOfEverySolvableClassicMaze) {
  size_t all = 0;
  const std::vector<fs::path> mazes = SolvableClassicMazes(&all);
  if (mazes.empty())
    GTEST_SKIP() << "the maze collection (../shared/mazes) is not beside the project";
  int reached = 0;
  const auto start = std::chrono::steady_clock::now();
  for (const fs::path& file : mazes) {
    const MmsOutcome run = Mms("--maze " + file.string() + " -- " + kFloodFillClient);
    const bool ok = run.outcome.exit_code == 0 && run.result["status"] == "goal_reached";
    EXPECT_TRUE(ok) << file << ": " << run.outcome.output;
    reached += ok ? 1 : 0;
  }
  const double took_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("flood fill over %zu solvable classic mazes of %zu: %d reached, %.1f s\n",
              mazes.size(), all, reached, took_s);
  EXPECT_GT(mazes.size(), 500u);
  EXPECT_EQ(reached, int(mazes.size()));
}

// What the left-wall client must do in `maze`, worked out here on the maze itself: its moves
// (turns included) until it stops in a goal cell, or until the contest clock (0.5 s a move or
// turn) has passed `limit_s`. Returns the moves and whether it reached the goal.
std::pair<long, bool> LeftWallFollower(const Maze& maze, double limit_s) {
  const int dx[4] = {1, 0, -1, 0};
  const int dy[4] = {0, 1, 0, -1};
  Cell at{0, 0};
  int heading = 1;  // north
  long moves = 0;
  auto wall = [&](int h) { return maze.HasWall(at, Heading(h)); };
  auto over = [&] { return 0.5 * double(moves) > limit_s; };
  while (!over()) {
    if (!wall((heading + 1) % 4)) {
      heading = (heading + 1) % 4;
      ++moves;
    } else {
      while (wall(heading) && !over()) {
        heading = (heading + 3) % 4;
        ++moves;
      }
    }
    if (over()) break;
    at = {at.x + dx[heading], at.y + dy[heading]};
    ++moves;
    for (const Cell& goal : maze.goals()) {
      if (at == goal) return {moves, true};
    }
  }
  return {moves, false};
}

TEST_F(MmsRunTest, LeftWallPythonClientDoesWhatALeftWallFollowerDoesInEverySolvableClassicMaze) {
  if (!HavePython()) GTEST_SKIP() << "no python3";
  const std::vector<fs::path> mazes = SolvableClassicMazes();
  if (mazes.empty())
    GTEST_SKIP() << "the maze collection (../shared/mazes) is not beside the project";
  int reached = 0;
  for (const fs::path& file : mazes) {
    const Maze maze = LoadMaze(file.string());
    const auto [moves, goal] = LeftWallFollower(maze, 60);
    const MmsOutcome run =
        Mms("--no-pictures --time-limit-s 60 --maze " + file.string() + " -- " + kLeftWallClient);
    ASSERT_TRUE(run.result.is_object()) << file << ": " << run.outcome.output;
    EXPECT_EQ(run.result["status"], goal ? "goal_reached" : "time_out") << file;
    EXPECT_EQ(run.result["moves"], moves) << file;
    EXPECT_EQ(run.result["crashes"], 0) << file;
    reached += goal ? 1 : 0;
  }
  std::printf("left-wall follower over %zu solvable classic mazes: %d reached the goal\n",
              mazes.size(), reached);
  EXPECT_GT(mazes.size(), 500u);
  // a wall follower reaches the centre of a few mazes only: those whose goal touches a wall
  // connected to the outside
  EXPECT_GT(reached, 0);
  EXPECT_LT(reached, int(mazes.size()));
}

// --- the same protocol from a board or relay: a pty, a serial port, TCP ---

// a port no one listens on now
int FreePort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address));
  socklen_t size = sizeof(address);
  getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size);
  close(fd);
  return ntohs(address.sin_port);
}

// Starts `unimouse mms ARGUMENTS` in the background, waits until it waits for its peer (or has
// ended), runs CLIENT (a shell command line) and then waits for the run: what a user does with a
// board.
std::string MmsWithPeer(const std::string& dir, const std::string& arguments,
                        const std::string& client) {
  const std::string script = dir + "/peer.sh";
  WriteTextFile(script, "(" UNIMOUSE_BINARY " mms " + arguments + " > " + dir +
                            "/mms.log 2>&1; echo $? > " + dir + "/mms.rc) &\n" +
                            "until grep -q waiting " + dir + "/mms.log 2>/dev/null || [ -e " + dir +
                            "/mms.rc ]; do sleep 0.05; done\n" + client + "\nwait\n");
  std::system(("bash " + script + " > " + dir + "/client.log 2>&1").c_str());
  return ReadTextFile(dir + "/mms.log");
}

TEST_F(MmsRunTest, OverTcpAnMmsArduinoStyleClientReachesTheGoalWithItsLogShown) {
  const MmsOutcome piped = Mms("--maze japan2018 -- " + kFloodFillClient);
  ASSERT_EQ(piped.outcome.exit_code, 0);
  const std::string port = std::to_string(FreePort());
  // the board's sketch: a log line, then the algorithm, on one line to the simulator
  const std::string log =
      MmsWithPeer(dir_, "--maze japan2018 --out " + out_ + " --port tcp:127.0.0.1:" + port,
                  "exec 3<>/dev/tcp/127.0.0.1/" + port + "\n{ echo 'log hello from the board'; " +
                      kFloodFillClient + "; } <&3 >&3");
  EXPECT_EQ(ReadTextFile(dir_ + "/mms.rc"), "0\n") << log;
  EXPECT_NE(log.find("mms: log: hello from the board"), std::string::npos) << log;
  const auto result = nlohmann::json::parse(ReadTextFile(out_ + "/result.json"));
  EXPECT_EQ(result["status"], "goal_reached");
  EXPECT_EQ(result["port"], "tcp:127.0.0.1:" + port);
  // the log line is not a command: the same run as over stdin and stdout
  EXPECT_EQ(result["stats"], piped.result["stats"]);
  EXPECT_EQ(result["invalid_commands"], 0);
}

TEST_F(MmsRunTest, OverAPtyTheClientReachesTheGoal) {
  const std::string link = dir_ + "/mouse";
  const std::string log =
      MmsWithPeer(dir_, "--maze japan2018 --out " + out_ + " --port pty:" + link,
                  kFloodFillClient + " <>" + link + " >&0");
  EXPECT_EQ(ReadTextFile(dir_ + "/mms.rc"), "0\n") << log;
  EXPECT_EQ(nlohmann::json::parse(ReadTextFile(out_ + "/result.json"))["status"], "goal_reached");
  EXPECT_FALSE(fs::exists(fs::symlink_status(link))) << "the run removes its link";
}

TEST_F(MmsRunTest, OverASerialPortTheClientReachesTheGoal) {
  // a pseudo-terminal stands for the board's USB serial port: the client on its master side,
  // the simulator opening its slave as a serial port
  int master = -1, slave = -1;
  char name[256] = "";
  ASSERT_EQ(openpty(&master, &slave, name, nullptr, nullptr), 0);
  termios raw{};
  tcgetattr(slave, &raw);
  cfmakeraw(&raw);
  tcsetattr(slave, TCSANOW, &raw);
  const pid_t client = fork();
  if (client == 0) {
    dup2(master, 0);
    dup2(master, 1);
    execl(kFloodFillClient.c_str(), kFloodFillClient.c_str(), nullptr);
    _exit(127);
  }
  const MmsOutcome run = Mms("--maze japan2018 --port serial:" + std::string(name) + "@115200");
  close(slave);
  close(master);
  kill(client, SIGKILL);
  waitpid(client, nullptr, 0);
  EXPECT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  ASSERT_TRUE(run.result.is_object());
  EXPECT_EQ(run.result["status"], "goal_reached");
}

TEST_F(MmsRunTest, ABoardThatNeverSpeaksEndsAfterTheConnectTimeout) {
  const auto start = std::chrono::steady_clock::now();
  const MmsOutcome run = Mms("--maze japan2018 --connect-timeout-s 0.5 --port tcp:127.0.0.1:" +
                             std::to_string(FreePort()));
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
  EXPECT_EQ(run.outcome.exit_code, 3) << run.outcome.output;
  ASSERT_TRUE(run.result.is_object());
  EXPECT_EQ(run.result["status"], "program_hang");
}

TEST_F(MmsRunTest, AProgramAndAPortTogetherAreBadInput) {
  const MmsOutcome run = Mms("--maze japan2018 --port tcp::0 -- " + kFloodFillClient);
  EXPECT_EQ(run.outcome.exit_code, 2) << run.outcome.output;
  EXPECT_NE(run.outcome.output.find("not both"), std::string::npos) << run.outcome.output;
}

TEST_F(MmsRunTest, NeitherAProgramNorAPortIsBadInputSayingHowToNameOne) {
  const MmsOutcome run = Mms("--maze japan2018");
  EXPECT_EQ(run.outcome.exit_code, 2) << run.outcome.output;
  EXPECT_NE(run.outcome.output.find("name the program after -- (unimouse mms --maze MAZE -- "
                                    "./solver), or a board's --port"),
            std::string::npos)
      << run.outcome.output;
}

}  // namespace
}  // namespace unimouse
