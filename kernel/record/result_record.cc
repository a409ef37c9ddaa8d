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
          {"unimouse_version", UNIMOUSE_VERSION},
          {"command", command}};
}

nlohmann::json FileIdentity(const std::string& path) {
  return {{"file", path}, {"sha256", FileSha256(path)}};
}

void SetMazeIdentity(nlohmann::json& record, const std::string& file, const Maze* maze) {
  const bool known = !file.empty() && maze != nullptr;
  record["maze"] = known ? nlohmann::json(file) : nullptr;
  record["maze_name"] = known ? nlohmann::json(fs::path(file).stem().string()) : nullptr;
  record["maze_sha256"] = known ? nlohmann::json(FileSha256(file)) : nullptr;
  record["maze_size"] = known ? nlohmann::json{maze->width(), maze->height()} : nullptr;
}

void WriteResultRecord(const std::string& out_dir, const nlohmann::json& record) {
  fs::create_directories(out_dir);
  WriteTextFile((fs::path(out_dir) / "result.json").string(),
                record.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

}  // namespace unimouse
