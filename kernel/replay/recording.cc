// SPDX-License-Identifier: GPL-3.0-or-later
#include "recording.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <span>
#include <string_view>

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

// A quicker JSON reader for what recordings hold: plain ASCII keys and strings, numbers, a few
// levels deep. It calls a SAX handler as nlohmann's parser would, and gives up (false) on
// anything else, an escape or a syntax error alike, which that parser then reads or refuses.
class QuickJson {
 public:
  QuickJson(std::string_view text, nlohmann::json_sax<json>& sax)
      : p_(text.data()), end_(text.data() + text.size()), sax_(sax) {}

  bool Read() {
    if (!Value(0)) return false;
    SkipSpace();
    return p_ == end_;
  }

 private:
  static constexpr int kMaxDepth = 16;

  void SkipSpace() {
    while (p_ != end_ && (*p_ == ' ' || *p_ == '\n' || *p_ == '\r' || *p_ == '\t')) ++p_;
  }
  bool At(char c) const { return p_ != end_ && *p_ == c; }
  bool Digit() const { return p_ != end_ && *p_ >= '0' && *p_ <= '9'; }

  bool Value(int depth) {
    SkipSpace();
    if (p_ == end_) return false;
    switch (*p_) {
      case '{':
        return Container(depth, '}');
      case '[':
        return Container(depth, ']');
      case '"':
        return String() && sax_.string(text_);
      case 't':
        return Word("true") && sax_.boolean(true);
      case 'f':
        return Word("false") && sax_.boolean(false);
      case 'n':
        return Word("null") && sax_.null();
      default:
        return Number();
    }
  }

  // an object ('}') or an array (']'), its opening bracket at p_
  bool Container(int depth, char close) {
    if (depth == kMaxDepth) return false;
    ++p_;
    const bool object = close == '}';
    if (!(object ? sax_.start_object(std::size_t(-1)) : sax_.start_array(std::size_t(-1)))) {
      return false;
    }
    SkipSpace();
    if (!At(close)) {
      while (true) {
        if (object) {
          SkipSpace();
          if (!At('"') || !String()) return false;
          SkipSpace();
          if (!At(':')) return false;
          ++p_;
          if (!sax_.key(text_)) return false;
        }
        if (!Value(depth + 1)) return false;
        SkipSpace();
        if (At(close)) break;
        if (!At(',')) return false;
        ++p_;
      }
    }
    ++p_;
    return object ? sax_.end_object() : sax_.end_array();
  }

  // a string without escapes or bytes beyond ASCII, its opening quote at p_, into text_
  bool String() {
    const char* start = ++p_;
    while (p_ != end_ && *p_ != '"') {
      const auto c = static_cast<unsigned char>(*p_);
      if (c == '\\' || c < 0x20 || c >= 0x80) return false;
      ++p_;
    }
    if (p_ == end_) return false;
    text_.assign(start, p_);
    ++p_;
    return true;
  }

  bool Word(std::string_view word) {
    if (static_cast<size_t>(end_ - p_) < word.size() || std::string_view(p_, word.size()) != word) {
      return false;
    }
    p_ += word.size();
    return true;
  }

  // JSON's number syntax; an integer as nlohmann reads one (-0 is 0), a fraction correctly
  // rounded as strtod has it
  bool Number() {
    const char* start = p_;
    if (At('-')) ++p_;
    if (At('0')) {
      ++p_;
    } else if (Digit()) {
      while (Digit()) ++p_;
    } else {
      return false;
    }
    bool integer = true;
    if (At('.')) {
      ++p_;
      if (!Digit()) return false;
      while (Digit()) ++p_;
      integer = false;
    }
    if (At('e') || At('E')) {
      ++p_;
      if (At('+') || At('-')) ++p_;
      if (!Digit()) return false;
      while (Digit()) ++p_;
      integer = false;
    }
    if (integer && *start == '-') {
      int64_t v = 0;
      const auto [end, error] = std::from_chars(start, p_, v);
      if (error == std::errc() && end == p_) return sax_.number_integer(v);
    } else if (integer) {
      uint64_t v = 0;
      const auto [end, error] = std::from_chars(start, p_, v);
      if (error == std::errc() && end == p_) return sax_.number_unsigned(v);
    }
    double v = 0;
    const auto [end, error] = std::from_chars(start, p_, v);
    if (error != std::errc() || end != p_) return false;  // out of range: the parser says
    text_.assign(start, p_);
    return sax_.number_float(v, text_);
  }

  const char* p_;
  const char* end_;
  nlohmann::json_sax<json>& sax_;
  std::string text_;  // the string, key or number just read
};

// The values of a message's objects up to two deep, each under its key and its parent's ("" at
// the top), read without building a document: poses and signals are most of a recording, and a
// document of each took half of a replay's time. A value that is not a number reads as NaN, as
// Number(const json&) has it; what is inside arrays and deeper objects is passed over.
class NumberFields final : public nlohmann::json_sax<json> {
 public:
  struct Field {
    std::string parent, key;
    double value;
  };

  /// Reads `data`; false when it is not a JSON object.
  bool Read(std::string_view data) {
    Clear();
    if (QuickJson(data, *this).Read()) return top_is_object_;
    Clear();
    return json::sax_parse(data, this) && top_is_object_;
  }
  std::span<const Field> fields() const { return {fields_.data(), count_}; }
  /// Whether the message has an object under `key`.
  bool HasObject(std::string_view key) const {
    return std::find(objects_.begin(), objects_.end(), key) != objects_.end();
  }
  /// The number under parent.key, or nullopt when there is none.
  std::optional<double> Find(std::string_view parent, std::string_view key) const {
    // the last, as a document keeps the last of a name given twice
    for (auto f = fields().rbegin(); f != fields().rend(); ++f) {
      if (f->key == key && f->parent == parent) return f->value;
    }
    return std::nullopt;
  }

  bool null() override { return Value(std::numeric_limits<double>::quiet_NaN()); }
  bool boolean(bool) override { return null(); }
  bool number_integer(number_integer_t v) override { return Value(static_cast<double>(v)); }
  bool number_unsigned(number_unsigned_t v) override { return Value(static_cast<double>(v)); }
  bool number_float(number_float_t v, const string_t&) override { return Value(v); }
  bool string(string_t&) override { return null(); }
  bool binary(binary_t&) override { return null(); }
  bool start_object(std::size_t) override { return Open(kObject); }
  bool key(string_t& k) override {
    key_ = k;
    return true;
  }
  bool end_object() override {
    open_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override { return Open(kArray); }
  bool end_array() override { return end_object(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    return false;
  }

 private:
  static constexpr char kObject = 'o', kArray = 'a';

  void Clear() {
    count_ = 0;
    objects_.clear();
    open_.clear();
    top_is_object_ = false;
  }

  bool Open(char kind) {
    Value(std::numeric_limits<double>::quiet_NaN());  // where a number could be, as Number(const
                                                      // json&) has it
    if (open_.empty()) top_is_object_ = kind == kObject;
    if (open_.size() == 1 && open_[0] == kObject) {
      parent_ = key_;  // a field of the message: its key names the children
      if (kind == kObject) objects_.push_back(key_);
    }
    open_.push_back(kind);
    return true;
  }
  bool Value(double v) {
    // a field of the message, or of an object in it: every container above is an object
    if (open_.empty() || open_.size() > 2 ||
        std::find(open_.begin(), open_.end(), kArray) != open_.end()) {
      return true;
    }
    // the fields' strings are kept from message to message, their memory with them
    if (count_ == fields_.size()) fields_.emplace_back();
    Field& f = fields_[count_++];
    f.parent.assign(open_.size() == 1 ? std::string_view() : std::string_view(parent_));
    f.key.assign(key_);
    f.value = v;
    return true;
  }

  std::vector<Field> fields_;
  size_t count_ = 0;                  // the fields of the message read last
  std::vector<std::string> objects_;  // the message's fields that are objects
  std::vector<char> open_;            // the containers around the value being read
  std::string key_, parent_;
  bool top_is_object_ = false;
};

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
    if (const auto robot = robot_of_channel_.find(channel_id); robot != robot_of_channel_.end()) {
      Pose(robot->second, t, data);
      return;
    }
    if (topic->second == "/signals") {
      Signals(t, data);
      return;
    }
    const json m = json::parse(data, nullptr, false);
    if (m.is_discarded() || !m.is_object()) return;  // a damaged message is skipped
    try {
      Take(topic->second, t, m);
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
  // a damaged message, or one without a field read here, is skipped
  void Pose(int robot, double t, std::string_view data) {
    if (!fields_.Read(data)) return;
    const auto x = fields_.Find("translation", "x"), y = fields_.Find("translation", "y");
    const auto qz = fields_.Find("rotation", "z"), qw = fields_.Find("rotation", "w");
    if (!x || !y || !qz || !qw) return;
    const double yaw = 2 * std::atan2(*qz, *qw);
    out_.robots[robot].poses.push_back({t, {*x, *y, std::remainder(yaw, 2 * M_PI)}});
  }

  void Signals(double t, std::string_view data) {
    if (!fields_.Read(data) || !fields_.HasObject("values")) return;
    if (out_.signal_names.empty()) {
      // the first message's names, sorted
      for (const auto& f : fields_.fields()) {
        if (f.parent == "values") signal_index_.emplace(f.key, 0);
      }
      for (auto& [name, index] : signal_index_) {
        index = static_cast<int>(out_.signal_names.size());
        out_.signal_names.push_back(name);
      }
    }
    std::vector<double> row(out_.signal_names.size(), std::numeric_limits<double>::quiet_NaN());
    for (const auto& f : fields_.fields()) {
      if (f.parent != "values") continue;
      if (const auto i = signal_index_.find(f.key); i != signal_index_.end()) {
        row[static_cast<size_t>(i->second)] = f.value;
      }
    }
    out_.signal_times_s.push_back(t);
    out_.signal_rows.push_back(std::move(row));
  }

  void Take(const std::string& topic, double t, const json& m) {
    if (topic == "/events") {
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
  NumberFields fields_;
  std::map<std::string, int, std::less<>> signal_index_;  // a signal's column in signal_rows
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
