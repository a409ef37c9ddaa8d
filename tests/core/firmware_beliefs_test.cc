// SPDX-License-Identifier: GPL-3.0-or-later
// A firmware's reports become its beliefs about the maze; a cell that no maze has (a report's
// mistake, or a hostile one) never reaches a picture or a route.
#include "firmware_beliefs.h"

#include <gtest/gtest.h>

#include <string>

namespace unimouse {
namespace {

unimouse_report Report(int kind, int x, int y) {
  unimouse_report r{};
  r.size = sizeof(r);
  r.kind = kind;
  r.x = x;
  r.y = y;
  return r;
}

TEST(FirmwareBeliefsTest, APathWithACellOutsideEveryMazeIsIgnoredWhole) {
  FirmwareBeliefs beliefs;
  int cells[] = {0, 0, 0, 1};
  unimouse_report path = Report(UNIMOUSE_REPORT_PATH, 0, 0);
  path.cells = cells;
  path.ncells = 2;
  beliefs.Apply(path);
  ASSERT_EQ(beliefs.path.size(), 2u);
  int extreme[] = {2147483647, 0, -2147483647 - 1, 0};
  path.cells = extreme;
  beliefs.Apply(path);
  EXPECT_EQ(beliefs.path.size(), 2u);  // the earlier path stands
  EXPECT_EQ(beliefs.path[1], (Cell{0, 1}));
}

TEST(FirmwareBeliefsTest, WallsAndVisitsOutsideEveryMazeAreLeftOut) {
  FirmwareBeliefs beliefs;
  beliefs.Apply(Report(UNIMOUSE_REPORT_VISITED, kMaxMazeSide_cells, 0));
  beliefs.Apply(Report(UNIMOUSE_REPORT_WALLS, -1, 3));
  EXPECT_TRUE(beliefs.empty());
  beliefs.Apply(Report(UNIMOUSE_REPORT_VISITED, kMaxMazeSide_cells - 1, 0));
  EXPECT_EQ(beliefs.visited.size(), 1u);
}

TEST(FirmwareBeliefsTest, EveryMmsColourLetterHasAColourAndNoOtherCharacterHas) {
  const std::string letters = "kbacgorwyBACGORYV";
  for (int c = 0; c < 128; ++c) {
    EXPECT_EQ(CellColourOf(static_cast<char>(c)).has_value(),
              letters.find(static_cast<char>(c)) != std::string::npos)
        << c;
  }
  EXPECT_EQ(CellColourOf('r'), (Rgb8{255, 0, 0}));
  EXPECT_EQ(CellColourOf('B'), (Rgb8{0, 0, 128}));
  EXPECT_EQ(CellColourOf('k'), (Rgb8{0, 0, 0}));
}

TEST(FirmwareBeliefsTest, ColoursAndTextsAloneAreSomethingReported) {
  FirmwareBeliefs beliefs;
  EXPECT_TRUE(beliefs.empty());
  beliefs.texts[{0, 0}] = "x";
  EXPECT_FALSE(beliefs.empty());
  beliefs.texts.clear();
  beliefs.colours[{0, 0}] = 'r';
  EXPECT_FALSE(beliefs.empty());
}

}  // namespace
}  // namespace unimouse

namespace unimouse {
namespace {

// a recording writes cell colours as #rrggbb and a replay reads the letters back
TEST(CellColourTest, EveryLetterComesBackFromItsHexColourAndNoOtherColourDoes) {
  for (char letter : std::string("kbacgorwyBACGORYV")) {
    const std::string hex = HexColour(*CellColourOf(letter));
    ASSERT_EQ(hex.size(), 7u);
    EXPECT_EQ(CellColourLetter(hex), letter) << hex;
  }
  EXPECT_EQ(HexColour({255, 165, 0}), "#ffa500");
  EXPECT_EQ(CellColourLetter("#123456"), std::nullopt);
  EXPECT_EQ(CellColourLetter("red"), std::nullopt);
}

}  // namespace
}  // namespace unimouse
