// SPDX-License-Identifier: GPL-3.0-or-later
// result.json, the record of a run that graders read: it says which version of its schema it
// follows (docs/result.schema.json, described field by field in docs/results.md), which
// unimouse wrote it, and what ran, each file with its SHA-256. `unimouse run` (kernel/run) and
// `unimouse mms` (kernel/mms) write it through here.
#ifndef UNIMOUSE_RECORD_RESULT_RECORD_H_
#define UNIMOUSE_RECORD_RESULT_RECORD_H_

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "maze.h"

namespace unimouse {

/// The version of result.json's schema, major.minor. A new key, or a new value where the schema
/// lists them, raises the minor: a reader of 1.0 reads every 1.x record. A key removed or
/// renamed, or one whose type or meaning changes, raises the major.
inline constexpr const char* kResultSchemaVersion = "1.6";

/// The version of unimouse that writes records, e.g. "0.1.0".
const char* UnimouseVersion();

/// A file a run read, and the SHA-256 of its content as the run read it.
struct FileRecord {
  std::string file;
  std::string sha256;
  bool operator==(const FileRecord&) const = default;
};

/// The maze a run took place in: its file, hash and size in cells.
struct MazeRecord {
  std::string file;
  std::string sha256;
  int width = 0;
  int height = 0;
  bool operator==(const MazeRecord&) const = default;
};

/// Returns the file with its SHA-256. Throws InputError when the file cannot be read.
FileRecord IdentifyFile(const std::string& path);

/// Returns the maze's file with its SHA-256 and size. Throws InputError when the file cannot be
/// read.
MazeRecord IdentifyMaze(const std::string& file, const Maze& maze);

/// {"file": ..., "sha256": ...}
nlohmann::json ToJson(const FileRecord& file);

/// Returns the start of every record: its schema (name, version, where it is described), the
/// version of unimouse, and the command that wrote it ("run" or "mms").
nlohmann::json NewResultRecord(const std::string& command);

/// Sets the record's maze keys: "maze" (the file), "maze_name" (the file's name without its
/// extension), "maze_sha256" and "maze_size" ([width, height] in cells); all null without a
/// maze.
void SetMazeIdentity(nlohmann::json& record, const std::optional<MazeRecord>& maze);

/// Writes out_dir/result.json (making the directory) through a temporary file, so that a
/// reader never sees half of it; text that is not UTF-8 is written with replacement
/// characters.
void WriteResultRecord(const std::string& out_dir, const nlohmann::json& record);

}  // namespace unimouse

#endif  // UNIMOUSE_RECORD_RESULT_RECORD_H_
