// SPDX-License-Identifier: GPL-3.0-or-later
// The bitmap font: a known letter pixel by pixel, and every printable character its own glyph.
#include "bitmap_font.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace unimouse {
namespace {

// a glyph as rows of '#' and '.'
std::vector<std::string> Rows(const Glyph& glyph) {
  std::vector<std::string> rows;
  for (uint8_t bits : glyph) {
    std::string row;
    for (int column = 0; column < kGlyphWidth_px; ++column) {
      row += (bits >> (kGlyphWidth_px - 1 - column) & 1) ? '#' : '.';
    }
    rows.push_back(row);
  }
  return rows;
}

TEST(BitmapFontTest, TheCapitalAIsAnArchWithACrossbar) {
  EXPECT_EQ(Rows(GlyphOf('A')), (std::vector<std::string>{".###.", "#...#", "#...#", "#####",
                                                          "#...#", "#...#", "#...#"}));
  EXPECT_EQ(Rows(GlyphOf('7')), (std::vector<std::string>{"#####", "....#", "...#.", "..#..",
                                                          ".#...", ".#...", ".#..."}));
}

TEST(BitmapFontTest, EveryPrintableCharacterHasItsOwnGlyphWithinFiveColumns) {
  std::set<Glyph> seen;
  for (char c = ' '; c <= '~'; ++c) {
    const Glyph& glyph = GlyphOf(c);
    for (uint8_t row : glyph) EXPECT_EQ(row & ~0x1F, 0) << "'" << c << "'";
    EXPECT_TRUE(seen.insert(glyph).second) << "'" << c << "' looks like another character";
  }
}

TEST(BitmapFontTest, CharactersOutsidePrintableAsciiAreQuestionMarks) {
  for (char c : {'\0', '\t', '\x7f', static_cast<char>(0xe9)}) {
    EXPECT_EQ(GlyphOf(c), GlyphOf('?')) << int(c);
  }
}

}  // namespace
}  // namespace unimouse
