// SPDX-License-Identifier: GPL-3.0-or-later
#include "result_record.h"

#include <filesystem>

#include "sha256.h"
#include "text_file.h"

namespace unimouse {

namespace fs = std::filesystem;

nlohmann::json NewResultRecord(const std::string& command) {
  return {{"schema",
           {{"name", "unimouse-result"},
            {"version", kResultSchemaVersion},
            {"docs", "docs/results.md"}}},
          {"unimouse_version", UnimouseVersion()},
          {"command", command}};
}

const char* UnimouseVersion() { return UNIMOUSE_VERSION; }

FileRecord IdentifyFile(const std::string& path) { return {path, FileSha256(path)}; }

MazeRecord IdentifyMaze(const std::string& file, const Maze& maze) {
  return {file, FileSha256(file), maze.width(), maze.height()};
}

nlohmann::json ToJson(const FileRecord& file) {
  return {{"file", file.file}, {"sha256", file.sha256}};
}

void SetMazeIdentity(nlohmann::json& record, const std::optional<MazeRecord>& maze) {
  record["maze"] = maze ? nlohmann::json(maze->file) : nullptr;
  record["maze_name"] = maze ? nlohmann::json(fs::path(maze->file).stem().string()) : nullptr;
  record["maze_sha256"] = maze ? nlohmann::json(maze->sha256) : nullptr;
  record["maze_size"] = maze ? nlohmann::json{maze->width, maze->height} : nullptr;
}

void WriteResultRecord(const std::string& out_dir, const nlohmann::json& record) {
  fs::create_directories(out_dir);
  WriteTextFile((fs::path(out_dir) / "result.json").string(),
                record.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

}  // namespace unimouse
