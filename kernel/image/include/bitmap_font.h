// SPDX-License-Identifier: GPL-3.0-or-later
// A 5 x 7 pixel font for printable ASCII, for text in pictures drawn pixel by pixel (the maze
// plot's cell texts and numbers), so that no font file or library is needed.
#ifndef UNIMOUSE_IMAGE_BITMAP_FONT_H_
#define UNIMOUSE_IMAGE_BITMAP_FONT_H_

#include <array>
#include <cstdint>

namespace unimouse {

inline constexpr int kGlyphWidth_px = 5;
inline constexpr int kGlyphHeight_px = 7;

/// One character's pixels: rows from the top, the leftmost column in bit 4 (0x10).
using Glyph = std::array<uint8_t, kGlyphHeight_px>;

/// Returns the glyph of a printable ASCII character (32 to 126); '?' for any other.
const Glyph& GlyphOf(char c);

}  // namespace unimouse

#endif  // UNIMOUSE_IMAGE_BITMAP_FONT_H_
