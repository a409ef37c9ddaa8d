// SPDX-License-Identifier: GPL-3.0-or-later
#include "frame_table.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "unimouse/errors.h"

namespace unimouse::link {
namespace {

struct Direction {
  const char* param;
  std::vector<Encoding> encodings;
  const char* encodings_text;
  bool has_period;
};

const Direction kSend{
    "send", {Encoding::kTof, Encoding::kI16, Encoding::kF32}, "tof, i16 or f32", true};
const Direction kReceive{
    "receive", {Encoding::kMotor, Encoding::kI16, Encoding::kF32}, "motor, i16 or f32", false};

const char* ControlName(int id) {
  switch (id) {
    case UNIMOUSE_ID_MANAGER:
      return "manager";
    case UNIMOUSE_ID_LOG:
      return "log";
    case UNIMOUSE_ID_CLOCK:
      return "clock";
    case UNIMOUSE_ID_FRAME_SIZE:
      return "frame size";
    case UNIMOUSE_ID_MAZE_INFO:
    case UNIMOUSE_ID_MAZE_SIZE:
      return "maze";
    default:
      return "debug";
  }
}

std::string Trim(const std::string& s) {
  size_t begin = 0, end = s.size();
  while (begin < end && std::isspace(static_cast<unsigned char>(s[begin]))) ++begin;
  while (end > begin && std::isspace(static_cast<unsigned char>(s[end - 1]))) --end;
  return s.substr(begin, end - begin);
}

int ParseId(const std::string& word) {
  const bool digits = !word.empty() && word.size() <= 3 &&
                      word.find_first_not_of("0123456789") == std::string::npos;
  const int id = digits ? std::atoi(word.c_str()) : -1;
  UNIMOUSE_THROW_UNLESS(id >= 0 && id <= 255, "'" + word + "' is not a frame id (0 to 255)");
  return id;
}

std::vector<TableEntry> ParseTable(const std::string& text, const Direction& dir) {
  std::vector<TableEntry> entries;
  // a blank table has no entries; otherwise every ';' separates two real ones
  if (Trim(text).empty()) return entries;
  std::stringstream pieces(text + ";");
  int n = 0;
  for (std::string piece; std::getline(pieces, piece, ';');) {
    const std::string entry = Trim(piece);
    ++n;
    TableEntry e;
    e.where = std::string(dir.param) + " entry " + std::to_string(n) + " ('" + entry + "')";
    try {
      UNIMOUSE_THROW_UNLESS(!entry.empty(), "empty entry; entries are separated by one ';'");
      std::vector<std::string> words;
      std::stringstream in(entry);
      for (std::string w; in >> w;) words.push_back(w);
      const std::string shape =
          dir.has_period ? "ID SIGNAL ENCODING [PERIOD_S]" : "ID SIGNAL ENCODING";
      UNIMOUSE_THROW_UNLESS(words.size() == 3 || (dir.has_period && words.size() == 4),
                            "write " + shape);
      const int id = ParseId(words[0]);
      UNIMOUSE_THROW_UNLESS(!IsControlId(id), "id " + std::to_string(id) + " is the protocol's " +
                                                  ControlName(id) +
                                                  " frame (ids 7 to 15 and 127 are taken)");
      for (const TableEntry& other : entries) {
        UNIMOUSE_THROW_UNLESS(other.id != id, "id " + words[0] + " is already in " + other.where);
        UNIMOUSE_THROW_UNLESS(dir.has_period || other.signal != words[1],
                              "signal '" + words[1] + "' is already written by " + other.where);
      }
      e.id = static_cast<uint8_t>(id);
      e.signal = words[1];
      bool known = false;
      for (const Encoding enc : dir.encodings) {
        if (words[2] == EncodingName(enc)) {
          e.encoding = enc;
          known = true;
        }
      }
      UNIMOUSE_THROW_UNLESS(known, "unknown encoding '" + words[2] + "'; " + dir.param + " takes " +
                                       dir.encodings_text);
      if (words.size() == 4) {
        char* end = nullptr;
        e.period_s = std::strtod(words[3].c_str(), &end);
        UNIMOUSE_THROW_UNLESS(*end == '\0' && std::isfinite(e.period_s) && e.period_s >= 0,
                              "'" + words[3] + "' is not a period in seconds (0 or more)");
      }
    } catch (const InputError& error) {
      throw InputError(e.where + ": " + error.what());
    }
    entries.push_back(std::move(e));
  }
  return entries;
}

}  // namespace

const char* EncodingName(Encoding encoding) {
  switch (encoding) {
    case Encoding::kTof:
      return "tof";
    case Encoding::kI16:
      return "i16";
    case Encoding::kF32:
      return "f32";
    case Encoding::kMotor:
      return "motor";
  }
  return "?";
}

std::vector<TableEntry> ParseSendTable(const std::string& text) { return ParseTable(text, kSend); }

std::vector<TableEntry> ParseReceiveTable(const std::string& text) {
  return ParseTable(text, kReceive);
}

int StepsPerFrame(const TableEntry& entry, double link_period_s) {
  if (entry.period_s == 0) return 1;
  const double steps = entry.period_s / link_period_s;
  const long n = std::lround(steps);
  std::ostringstream why;
  why << entry.where << ": period " << entry.period_s << " s is not a whole number of the link's "
      << link_period_s << " s steps";
  UNIMOUSE_THROW_UNLESS(
      n >= 1 && n < (1L << 30) && std::fabs(steps - static_cast<double>(n)) < 1e-6 * steps,
      why.str());
  return static_cast<int>(n);
}

double SendBytesPerSecond(const std::vector<TableEntry>& entries, double link_period_s) {
  double bytes_per_s = 0;
  for (const TableEntry& e : entries) {
    bytes_per_s +=
        (1 + EncodingSize(e.encoding)) / (StepsPerFrame(e, link_period_s) * link_period_s);
  }
  return bytes_per_s;
}

}  // namespace unimouse::link
