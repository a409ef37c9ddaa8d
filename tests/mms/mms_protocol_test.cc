// SPDX-License-Identifier: GPL-3.0-or-later
// The mms protocol's logic tier, one command line at a time, against numbers worked out by hand
// from the rules in docs/mms.md.
#include "mms_protocol.h"

#include <gtest/gtest.h>

#include <optional>

#include "inline_assets.h"

namespace unimouse {
namespace {

class MmsWorldTest : public ::testing::Test {
 protected:
  // the reply to a command that has one
  std::string Ask(const std::string& line) {
    const MmsResponse r = world_.Handle(line);
    EXPECT_EQ(r.kind, MmsResponse::Kind::kReply) << line << ": " << r.problem;
    return r.reply;
  }
  MmsResponse::Kind KindOf(const std::string& line) { return world_.Handle(line).kind; }

  Maze maze_ = ParseMazeText(testing::kOpenMaze5x5, "open.txt");
  MmsWorld world_{maze_, MmsTiming{}};
};

TEST_F(MmsWorldTest, AnswersTheSizeAndTheWallsAroundTheStart) {
  EXPECT_EQ(Ask("mazeWidth"), "5");
  EXPECT_EQ(Ask("mazeHeight"), "5");
  EXPECT_EQ(Ask("wallFront"), "false");
  EXPECT_EQ(Ask("wallRight"), "true");
  EXPECT_EQ(Ask("wallLeft"), "true");
  EXPECT_EQ(Ask("wallBack"), "true");
  // a diagonal from a cell centre looks straight at a post
  EXPECT_EQ(Ask("wallFrontLeft"), "true");
  // from the centre of row 0, the north perimeter of row 4 is 1 + 2 x 4 = 9 half-cells ahead
  EXPECT_EQ(Ask("wallFront 8"), "false");
  EXPECT_EQ(Ask("wallFront 9"), "true");
}

TEST_F(MmsWorldTest, ScriptedMovesGiveTheStatsAndScoreWorkedOutByHand) {
  // run 1: two cells north (4 half-steps, effective 4/2+1 = 3), a turn, two cells east to (2, 2)
  EXPECT_EQ(Ask("moveForward 2"), "ack");
  EXPECT_EQ(Ask("getStat current-run-distance"), "4");
  EXPECT_EQ(Ask("turnRight"), "ack");
  EXPECT_EQ(Ask("moveForward 2"), "ack");
  EXPECT_TRUE(world_.goal_reached());
  EXPECT_EQ(Ask("getStat current-run-distance"), "-1");
  EXPECT_EQ(Ask("getStat best-run-distance"), "8");
  EXPECT_EQ(Ask("getStat best-run-turns"), "1");
  EXPECT_EQ(Ask("getStat best-run-effective-distance"), "6");
  // best 1 + 6, plus a tenth of the totals 1 + 6
  EXPECT_EQ(Ask("getStat score"), "7.7");

  // three cells east from (2, 2): two are free, then the perimeter; all 6 half-steps charged
  EXPECT_EQ(Ask("moveForward 3"), "crash");
  EXPECT_EQ(world_.cell(), (Cell{4, 2}));
  EXPECT_EQ(Ask("getStat total-distance"), "14");
  EXPECT_EQ(Ask("getStat total-effective-distance"), "10");
  EXPECT_EQ(Ask("getStat score"), "8.1");

  // run 2 after a reset carries the 15 penalty: (0,0) -> (0,1) -> (2,1) -> (2,2)
  EXPECT_EQ(Ask("ackReset"), "ack");
  EXPECT_EQ(world_.cell(), (Cell{0, 0}));
  EXPECT_EQ(Ask("moveForward"), "ack");
  EXPECT_EQ(Ask("getStat current-run-effective-distance"), "17");
  EXPECT_EQ(Ask("turnRight90"), "ack");
  EXPECT_EQ(Ask("moveForward 2"), "ack");
  EXPECT_EQ(Ask("turnLeft90"), "ack");
  EXPECT_EQ(Ask("moveForward"), "ack");
  // run 2 cost 2 turns + 22 > 7: the best run stays; totals 3 turns, 22 half-steps, and
  // 10 + 15 + 2 + 3 + 2 = 32 effective (mms adds the penalty to the total too)
  EXPECT_EQ(Ask("getStat best-run-effective-distance"), "6");
  EXPECT_EQ(Ask("getStat total-turns"), "3");
  EXPECT_EQ(Ask("getStat total-distance"), "22");
  EXPECT_EQ(Ask("getStat total-effective-distance"), "32");
  // 1 + 6 + (3 + 32) / 10
  EXPECT_EQ(Ask("getStat score"), "10.5");
  EXPECT_EQ(world_.moves(), 9);
  EXPECT_EQ(world_.crashes(), 1);
}

TEST_F(MmsWorldTest, ScoreIs2000AndRunStatsAreMinusOneBeforeAnyRun) {
  EXPECT_EQ(Ask("getStat score"), "2000");
  EXPECT_EQ(Ask("getStat best-run-turns"), "-1");
  EXPECT_EQ(Ask("getStat current-run-turns"), "-1");
  EXPECT_EQ(Ask("getStat total-turns"), "0");
}

// as mms: a move with a wall right ahead is refused before it starts, charging nothing and
// starting no run (a move a wall stops later is charged whole, above)
TEST_F(MmsWorldTest, AMoveIntoAWallRightAheadCrashesUnchargedAndStartsNoRun) {
  EXPECT_EQ(Ask("turnRight"), "ack");
  EXPECT_EQ(Ask("moveForward"), "crash");
  EXPECT_EQ(world_.cell(), (Cell{0, 0}));
  EXPECT_EQ(Ask("getStat total-distance"), "0");
  EXPECT_EQ(Ask("getStat current-run-distance"), "-1");
  EXPECT_EQ(Ask("moveForward 0"), "crash");
  EXPECT_EQ(Ask("getStat total-distance"), "0");
  EXPECT_EQ(world_.crashes(), 2);

  // after a reset, a bump at the start keeps the penalty for the run that follows
  EXPECT_EQ(Ask("turnLeft"), "ack");
  EXPECT_EQ(Ask("moveForward"), "ack");
  EXPECT_EQ(Ask("ackReset"), "ack");
  EXPECT_EQ(Ask("turnRight"), "ack");
  EXPECT_EQ(Ask("moveForward"), "crash");
  EXPECT_EQ(Ask("turnLeft"), "ack");
  EXPECT_EQ(Ask("moveForward"), "ack");
  EXPECT_EQ(Ask("getStat current-run-effective-distance"), "17");
  // the first run's 2, the penalty's 15, the second's 2
  EXPECT_EQ(Ask("getStat total-effective-distance"), "19");
}

// as mms: a count of 0 or less asks about the wall right ahead, as 1 does
TEST_F(MmsWorldTest, AWallQueryWithACountOfZeroOrLessLooksRightAhead) {
  for (const char* query : {"wallRight 0", "wallRight -2", "wallBack 0", "wallLeft -1"}) {
    EXPECT_EQ(Ask(query), "true") << query;
  }
  EXPECT_EQ(Ask("wallFront 0"), "false");
}

// as mms: a stop on the edge between two goal cells counts in the one east (or north) of it,
// and finishes the run
TEST_F(MmsWorldTest, AStopOnTheEdgeBetweenTwoGoalCellsFinishesTheRun) {
  const Maze maze = ParseMazeText(
      "o---o---o---o---o---o\n"
      "|                   |\n"
      "o   o   o   o   o   o\n"
      "|                   |\n"
      "o   o   o   o   o   o\n"
      "|         G   G     |\n"
      "o   o   o   o   o   o\n"
      "|                   |\n"
      "o   o   o   o   o   o\n"
      "| S |               |\n"
      "o---o---o---o---o---o\n",
      "two_goals.txt");
  MmsWorld world(maze, MmsTiming{});
  for (const char* line : {"moveForward 2", "turnRight", "moveForwardHalf 5"}) {
    EXPECT_EQ(world.Handle(line).reply, "ack") << line;
  }
  EXPECT_EQ(world.cell(), (Cell{-1, -1}));  // between (2, 2) and (3, 2)
  EXPECT_TRUE(world.goal_reached());
  // 4 + 5 half-steps, effective 3 + 3.5, and one turn: 1 + 6.5 + (1 + 6.5) / 10
  EXPECT_EQ(world.Handle("getStat best-run-distance").reply, "9");
  EXPECT_EQ(world.Handle("getStat score").reply, "8.25");
}

// a body that carries out every move and turn, grazing a wall each time
class GrazingBody : public MmsBody {
 public:
  MmsMotion Drive(long) override { return {0.5, /*contact=*/true, "", ""}; }
  MmsMotion Turn(int) override { return {0.3, /*contact=*/true, "", ""}; }
  std::optional<bool> SensedWall(int) override { return std::nullopt; }
  void Reset() override {}
};

TEST_F(MmsWorldTest, AMoveTheBodyCarriedOutRepliesAckThoughItGrazedAWallUnlessStrict) {
  GrazingBody body;
  world_.SetBody(&body, /*true_walls=*/true);
  EXPECT_EQ(Ask("moveForward"), "ack");
  EXPECT_EQ(Ask("turnRight"), "ack");
  EXPECT_EQ(world_.cell(), (Cell{0, 1}));
  EXPECT_EQ(world_.crashes(), 0);
  EXPECT_EQ(world_.grazes(), 2);
  // the strict reading: a graze is a crash, though the mouse moved
  world_.set_contact_is_crash(true);
  EXPECT_EQ(Ask("moveForward"), "crash");
  EXPECT_EQ(world_.cell(), (Cell{1, 1}));
  EXPECT_EQ(world_.crashes(), 1);
}

TEST_F(MmsWorldTest, HalfStepsAndFortyFiveDegreeTurnsFollowTheHalfCellGrid) {
  EXPECT_EQ(Ask("moveForwardHalf"), "ack");
  EXPECT_EQ(world_.cell(), (Cell{-1, -1}));
  // on the edge between (0,0) and (0,1): a diagonal north-east reaches the east wall place of
  // (0, 1), which is open
  EXPECT_EQ(Ask("turnRight45"), "ack");
  EXPECT_EQ(Ask("wallFront"), "false");
  EXPECT_EQ(Ask("moveForwardHalf"), "ack");
  EXPECT_EQ(Ask("turnLeft45"), "ack");
  // from the edge point (2, 3), one half-step north is the post (2, 4)
  EXPECT_EQ(Ask("moveForwardHalf"), "crash");
  EXPECT_EQ(Ask("getStat total-turns"), "2");
  EXPECT_EQ(world_.direction(), 2);
}

TEST_F(MmsWorldTest, AcceptsEverySpellingTrailingSpacesAndCarriageReturns) {
  for (const char* line : {"turnLeft", "turnLeft90", "turnRight", "turnRight90", "turnLeft45",
                           "turnRight45", "wallFront  ", "wallBackLeft 2", "wallBackRight\r",
                           "wallFrontRight 1 ", "wasReset", "ackReset"}) {
    EXPECT_EQ(KindOf(line), MmsResponse::Kind::kReply) << line;
  }
  EXPECT_EQ(Ask("wasReset"), "false");
}

TEST_F(MmsWorldTest, DropsInvalidCommandsWithAReason) {
  for (const char* line :
       {"", "wallfront", "wallFront\t", "wallFront x", "wallFront 1 2", "moveForward 1.5",
        "moveForward 99999999999", "mazeWidth 3", "getStat", "getStat speed", "setColor 0 0 X",
        "setColor 0 0", "setWall 0 0 N", "setText 0 0", "clearColor 0", "clearAllText now"}) {
    const MmsResponse r = world_.Handle(line);
    EXPECT_EQ(r.kind, MmsResponse::Kind::kInvalid) << "'" << line << "'";
    EXPECT_FALSE(r.problem.empty()) << line;
  }
  EXPECT_EQ(world_.moves(), 0);
}

TEST_F(MmsWorldTest, KeepsTheDisplayCommandsWithoutReplying) {
  for (const char* line :
       {"setWall 0 0 n", "setWall 4 4 e", "clearWall 1 1 w", "setColor 1 1 V", "setColor 2 2 r",
        "clearColor 2 2", "setColor 9 9 g", "setText 1 0 hello big world", "setText 2 0 \x01",
        "setText 3 0 x", "clearText 3 0", "setText 3 3 h\xc3\xa9llo w\xc3\xb6rld"}) {
    EXPECT_EQ(KindOf(line), MmsResponse::Kind::kNoReply) << line;
  }
  const nlohmann::json expected = nlohmann::json::parse(R"({
    "walls": [{"x": 0, "y": 0, "side": "n", "set": true}, {"x": 0, "y": 1, "side": "e", "set": false},
              {"x": 0, "y": 1, "side": "s", "set": true}, {"x": 1, "y": 1, "side": "w", "set": false},
              {"x": 4, "y": 4, "side": "e", "set": true}],
    "colors": [{"x": 1, "y": 1, "color": "V"}],
    "texts": [{"x": 1, "y": 0, "text": "hello big "}, {"x": 2, "y": 0, "text": "?"},
              {"x": 3, "y": 3, "text": "h?llo w?rl"}]})");
  EXPECT_EQ(world_.Display(), expected);
  EXPECT_EQ(KindOf("clearAllColor"), MmsResponse::Kind::kNoReply);
  EXPECT_EQ(world_.Display()["colors"].size(), 0u);
}

TEST_F(MmsWorldTest, TheDisplayBecomesTheBeliefsEveryPictureDraws) {
  for (const char* line :
       {"setWall 0 0 n", "clearWall 1 1 w", "setColor 1 1 V", "setText 2 0 hi"}) {
    EXPECT_EQ(KindOf(line), MmsResponse::Kind::kNoReply) << line;
  }
  const FirmwareBeliefs beliefs = world_.Beliefs();
  // bits north 1, east 2, south 4, west 8: set walls known and present, cleared ones known open
  using W = FirmwareBeliefs::CellWalls;
  auto walls = [&](int x, int y) {
    const W w = beliefs.walls.at({x, y});
    return std::pair<int, int>(w.walls, w.known);
  };
  EXPECT_EQ(beliefs.walls.size(), 3u);
  EXPECT_EQ(walls(0, 0), (std::pair<int, int>(1, 1)));
  EXPECT_EQ(walls(0, 1), (std::pair<int, int>(4 | 0, 4 | 2)));  // south set, east cleared
  EXPECT_EQ(walls(1, 1), (std::pair<int, int>(0, 8)));
  EXPECT_EQ(beliefs.colours, (std::map<std::pair<int, int>, char>{{{1, 1}, 'V'}}));
  EXPECT_EQ(beliefs.texts, (std::map<std::pair<int, int>, std::string>{{{2, 0}, "hi"}}));
}

TEST_F(MmsWorldTest, ChargesTheContestClockForMotionOnly) {
  Ask("wallFront");
  Ask("moveForward 2");
  Ask("turnRight");
  Ask("turnLeft45");
  // 2 cells at 0.5 s, a quarter turn at 0.5 s, an eighth at 0.25 s
  EXPECT_DOUBLE_EQ(world_.contest_time_s(), 1.75);
}

}  // namespace
}  // namespace unimouse
