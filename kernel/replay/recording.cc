// SPDX-License-Identifier: GPL-3.0-or-later
#include "recording.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "mcap_reader.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

using nlohmann::json;

// the recording format this player reads (RunRecording's kRecordingFormat when it was written)
constexpr int kReadableFormat = 1;

double Seconds(uint64_t time_ns) { return static_cast<double>(time_ns) * 1e-9; }

double Number(const json& value) {
  return value.is_number() ? value.get<double>() : std::numeric_limits<double>::quiet_NaN();
}

// a robot's poses: /robot/pose with one robot, /robots/NAME/pose with several
bool IsPoseTopic(const std::string& t) {
  return t == "/robot/pose" ||
         (t.rfind("/robots/", 0) == 0 && t.size() > 13 && t.compare(t.size() - 5, 5, "/pose") == 0);
}

class RecordingReader : public McapVisitor {
 public:
  explicit RecordingReader(Recording& out) : out_(out) {}

  void OnChannel(const McapChannel& channel) override {
    topics_[channel.id] = channel.topic;
    const std::string& t = channel.topic;
    if (IsPoseTopic(t)) {
      robot_of_channel_[channel.id] = static_cast<int>(out_.robots.size());
      RecordedRobot robot;
      if (t != "/robot/pose") robot.name = t.substr(8, t.size() - 13);
      out_.robots.push_back(std::move(robot));
    }
  }

  void OnMessage(uint16_t channel_id, uint64_t log_time_ns, std::string_view data) override {
    const auto topic = topics_.find(channel_id);
    if (topic == topics_.end()) return;
    const double t = Seconds(log_time_ns);
    out_.end_s = std::max(out_.end_s, t);
    // what a replay does not show (the beams, which it draws from the signals, and the beliefs'
    // 3D scene, which it draws from /beliefs) is not parsed: it is most of a recording's JSON
    if (!ReplayReadsTopic(topic->second)) return;
    const json m = json::parse(data, nullptr, false);
    if (m.is_discarded() || !m.is_object()) return;  // a damaged message is skipped
    try {
      Take(channel_id, topic->second, t, m);
    } catch (const json::exception&) {
      // a message missing a field is skipped, like a damaged one
    } catch (const std::logic_error&) {
      // so is a number that does not read as one (std::stod)
    }
  }

  void OnAttachment(const std::string& name, const std::string&, uint64_t,
                    std::string_view data) override {
    out_.attachments[name] = std::string(data);
  }

  void OnMetadata(const std::string& name,
                  const std::map<std::string, std::string>& values) override {
    if (name == "unimouse.recording") {
      const auto format = values.find("format");
      if (format != values.end() && std::atoi(format->second.c_str()) > kReadableFormat) {
        throw InputError(out_.path + ": a recording of format " + format->second +
                         ", made by a newer unimouse than this one (it reads format " +
                         std::to_string(kReadableFormat) + ")");
      }
      is_unimouse_ = true;
    } else if (name == "unimouse.run") {
      out_.run_metadata = values;
    } else if (name == "unimouse.robots") {
      robot_files_ = values;
    }
  }

  bool is_unimouse() const { return is_unimouse_; }
  const std::map<std::string, std::string>& robot_files() const { return robot_files_; }

 private:
  void Take(uint16_t channel_id, const std::string& topic, double t, const json& m) {
    if (const auto robot = robot_of_channel_.find(channel_id); robot != robot_of_channel_.end()) {
      const json& q = m.at("rotation");
      const double yaw = 2 * std::atan2(Number(q.at("z")), Number(q.at("w")));
      out_.robots[robot->second].poses.push_back(
          {t,
           {Number(m.at("translation").at("x")), Number(m.at("translation").at("y")),
            std::remainder(yaw, 2 * M_PI)}});
    } else if (topic == "/signals") {
      const json& values = m.at("values");
      if (out_.signal_names.empty()) {
        for (const auto& [name, value] : values.items()) out_.signal_names.push_back(name);
      }
      std::vector<double> row;
      row.reserve(out_.signal_names.size());
      for (const std::string& name : out_.signal_names) {
        const auto value = values.find(name);
        row.push_back(value == values.end() ? std::numeric_limits<double>::quiet_NaN()
                                            : Number(*value));
      }
      out_.signal_times_s.push_back(t);
      out_.signal_rows.push_back(std::move(row));
    } else if (topic == "/events") {
      out_.events.push_back({t, m.at("kind"), m.at("robot"), m.at("text")});
    } else if (topic == "/log") {
      out_.log.push_back({t, m.at("level"), m.at("name"), m.at("message")});
    } else if (topic == "/hud") {
      out_.hud.push_back({t, m.at("lines").get<std::vector<std::string>>()});
    } else if (topic == "/firmware/values") {
      std::map<std::string, double> values;
      for (const auto& [name, value] : m.at("values").items()) values[name] = Number(value);
      out_.firmware_values[m.at("robot")].push_back({t, std::move(values)});
    } else if (topic == "/beliefs") {
      FirmwareBeliefs b;
      for (const json& w : m.at("walls")) {
        b.walls[{w.at(0), w.at(1)}] = {w.at(2).get<uint8_t>(), w.at(3).get<uint8_t>()};
      }
      for (const json& c : m.at("visited")) b.visited.push_back({c.at(0), c.at(1)});
      for (const json& c : m.at("path")) b.path.push_back({c.at(0), c.at(1)});
      for (const json& c : m.at("colours")) {
        if (const auto letter = CellColourLetter(c.at(2))) b.colours[{c.at(0), c.at(1)}] = *letter;
      }
      for (const json& c : m.at("texts")) b.texts[{c.at(0), c.at(1)}] = c.at(2);
      out_.beliefs.push_back({t, std::move(b)});
    } else if (topic == "/scenery") {
      Scenery(m.at("entities"));
    }
  }

  void Scenery(const json& entities) {
    for (const json& entity : entities) {
      for (const json& cube : entity.at("cubes")) {
        const json& p = cube.at("pose").at("position");
        const json& q = cube.at("pose").at("orientation");
        const json& size = cube.at("size");
        const json& color = cube.at("color");
        StaticBox box;
        // the kind from its colour, as RunRecording paints them: posts red, walls white
        box.kind = Number(color.at("r")) > 0.8 && Number(color.at("g")) < 0.3
                       ? StaticBox::Kind::kPost
                   : Number(color.at("r")) > 0.9 ? StaticBox::Kind::kWall
                                                 : StaticBox::Kind::kObstacle;
        box.center_m = {Number(p.at("x")), Number(p.at("y")), Number(p.at("z"))};
        box.half_m = {Number(size.at("x")) / 2, Number(size.at("y")) / 2, Number(size.at("z")) / 2};
        box.yaw_rad = 2 * std::atan2(Number(q.at("z")), Number(q.at("w")));
        out_.scenery.push_back(box);
      }
      std::map<std::string, std::string> facts;
      for (const json& pair : entity.value("metadata", json::array()))
        facts[pair.at("key")] = pair.at("value");
      if (facts.count("cell_m") != 0) {
        MazeDimensions dims;
        dims.cell_m = std::stod(facts["cell_m"]);
        dims.wall_thickness_m = std::stod(facts["wall_thickness_m"]);
        dims.wall_height_m = std::stod(facts["wall_height_m"]);
        out_.maze = dims;
        out_.maze_width_cells = std::stoi(facts["maze_width_cells"]);
        out_.maze_height_cells = std::stoi(facts["maze_height_cells"]);
      }
    }
  }

  Recording& out_;
  std::map<uint16_t, std::string> topics_;
  std::map<uint16_t, int> robot_of_channel_;
  std::map<std::string, std::string> robot_files_;
  bool is_unimouse_ = false;
};

}  // namespace

bool ReplayReadsTopic(const std::string& topic) {
  // the topics Take reads: a topic it learns to read goes here too
  static const std::set<std::string, std::less<>> kRead = {
      "/signals", "/events", "/log", "/hud", "/firmware/values", "/beliefs", "/scenery"};
  return IsPoseTopic(topic) || kRead.contains(topic);
}

Pose2D PoseAt(const RecordedRobot& robot, double t_s) {
  const std::vector<Timed<Pose2D>>& poses = robot.poses;
  UNIMOUSE_DEMAND(!poses.empty());
  const int i = Recording::Latest(poses, t_s);
  if (i < 0) return poses.front().value;
  if (i + 1 >= static_cast<int>(poses.size())) return poses.back().value;
  const Timed<Pose2D>& a = poses[i];
  const Timed<Pose2D>& b = poses[i + 1];
  const double f = b.t_s > a.t_s ? (t_s - a.t_s) / (b.t_s - a.t_s) : 0;
  const double turn = std::remainder(b.value.yaw_rad - a.value.yaw_rad, 2 * M_PI);
  return {a.value.x_m + f * (b.value.x_m - a.value.x_m),
          a.value.y_m + f * (b.value.y_m - a.value.y_m),
          std::remainder(a.value.yaw_rad + f * turn, 2 * M_PI)};
}

namespace {

// what every recording needs, checked once it is read
void Finish(Recording& out, const RecordingReader& reader, const McapReadOutcome& outcome) {
  if (!reader.is_unimouse()) {
    throw InputError(out.path +
                     ": an MCAP file that unimouse did not record (no unimouse.recording"
                     " metadata" +
                     (outcome.library.empty() ? "" : "; written by " + outcome.library) + ")");
  }
  if (!outcome.cut_short.empty()) out.cut_short = outcome.cut_short;
  for (size_t i = 0; i < out.robots.size(); ++i) {
    const auto file = reader.robot_files().find(std::to_string(i) + ".file");
    if (file != reader.robot_files().end()) out.robots[i].file = file->second;
    if (out.robots[i].poses.empty()) {
      throw InputError(out.path + ": the recording holds no pose of robot " +
                       (out.robots[i].name.empty() ? std::to_string(i) : out.robots[i].name));
    }
  }
  if (out.robots.empty()) throw InputError(out.path + ": the recording holds no robot's pose");
}

}  // namespace

Recording ParseRecording(std::string_view bytes, const std::string& name) {
  Recording out;
  out.path = name;
  RecordingReader reader(out);
  Finish(out, reader, ReadMcapBytes(bytes, name, reader));
  return out;
}

Recording ReadRecording(const std::string& path) {
  namespace fs = std::filesystem;
  Recording out;
  out.path = path;
  std::error_code error;
  if (fs::is_directory(path, error)) {
    out.path = (fs::path(path) / "run.mcap").string();
    if (!fs::exists(out.path, error)) {
      throw InputError(path + ": no run.mcap in this folder (was the run made with --record off?)");
    }
  } else if (!fs::exists(path, error)) {
    throw InputError(path + ": no such file or folder");
  }
  RecordingReader reader(out);
  Finish(out, reader, ReadMcap(out.path, reader));
  return out;
}

}  // namespace unimouse
