// SPDX-License-Identifier: GPL-3.0-or-later
// The link's frame table: which signal goes out as which frame id, in which encoding and how
// often, and which incoming frame writes which signal. Parameters are scalars, so a table is a
// string of entries separated by ';', each a few words separated by spaces:
//
//   send:    ID SIGNAL ENCODING [PERIOD_S]   ENCODING tof, i16 or f32; PERIOD_S 0 or omitted:
//                                            every link step
//   receive: ID SIGNAL ENCODING              ENCODING motor, i16 or f32
//
// The defaults are the original UnimouseSim's wire format.
#ifndef UNIMOUSE_PLUGINS_LINK_FRAME_TABLE_H_
#define UNIMOUSE_PLUGINS_LINK_FRAME_TABLE_H_

#include <cstdint>
#include <string>
#include <vector>

#include "frame_codec.h"

namespace unimouse::link {

/// The original's sensor frames: both encoders every step, then the three ToF sensors every
/// 30 ms.
inline constexpr const char* kOriginalSend =
    "3 left.encoder_counts i16; 4 right.encoder_counts i16; 0 tof.left_m tof 0.03; "
    "1 tof.right_m tof 0.03; 2 tof.front_m tof 0.03";
/// The original's command frames: the two H-bridge commands.
inline constexpr const char* kOriginalReceive = "5 left.command motor; 6 right.command motor";

/// One entry of a frame table.
struct TableEntry {
  uint8_t id = 0;
  std::string signal;
  Encoding encoding = Encoding::kI16;
  double period_s = 0;  ///< sent frames: 0 for every link step
  std::string where;    ///< "send entry 2 ('4 right.encoder_counts i16')", for messages
};

/// Parses the `send` parameter. Throws InputError naming the parameter and the entry.
std::vector<TableEntry> ParseSendTable(const std::string& text);
/// Parses the `receive` parameter. Throws InputError naming the parameter and the entry.
std::vector<TableEntry> ParseReceiveTable(const std::string& text);

/// Returns every how many link steps a sent entry goes out, 1 for a period of 0. Throws
/// InputError when its period is not a whole number of `link_period_s`.
int StepsPerFrame(const TableEntry& entry, double link_period_s);

/// Returns the bytes a second the sent entries take on the line, each frame its id and payload,
/// at their periods on a link that steps every `link_period_s`.
double SendBytesPerSecond(const std::vector<TableEntry>& entries, double link_period_s);

/// Returns an encoding's name as the table writes it.
const char* EncodingName(Encoding encoding);

}  // namespace unimouse::link

#endif  // UNIMOUSE_PLUGINS_LINK_FRAME_TABLE_H_
