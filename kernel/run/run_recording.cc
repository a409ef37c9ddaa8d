// SPDX-License-Identifier: GPL-3.0-or-later
#include "run_recording.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "mcap_writer.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

using nlohmann::json;

// the JSON Schemas of Foxglove's message types, as far as the recording uses them: their
// names tell Foxglove and Lichtblick what a channel holds
constexpr const char* kTimeSchema =
    R"({"type":"object","properties":{"sec":{"type":"integer","minimum":0},)"
    R"("nsec":{"type":"integer","minimum":0,"maximum":999999999}}})";
constexpr const char* kVector3Schema =
    R"({"type":"object","properties":{"x":{"type":"number"},"y":{"type":"number"},)"
    R"("z":{"type":"number"}}})";
constexpr const char* kQuaternionSchema =
    R"({"type":"object","properties":{"x":{"type":"number"},"y":{"type":"number"},)"
    R"("z":{"type":"number"},"w":{"type":"number"}}})";

std::string FrameTransformSchema() {
  return json{{"title", "foxglove.FrameTransform"},
              {"description", "where a robot is: its frame in the world's"},
              {"type", "object"},
              {"properties",
               {{"timestamp", json::parse(kTimeSchema)},
                {"parent_frame_id", {{"type", "string"}}},
                {"child_frame_id", {{"type", "string"}}},
                {"translation", json::parse(kVector3Schema)},
                {"rotation", json::parse(kQuaternionSchema)}}}}
      .dump();
}

std::string LogSchema() {
  json levels = json::array();
  for (int level = 0; level <= 5; ++level) levels.push_back({{"const", level}});
  return json{{"title", "foxglove.Log"},
              {"description", "a line of the run's log"},
              {"type", "object"},
              {"properties",
               {{"timestamp", json::parse(kTimeSchema)},
                {"level", {{"oneOf", levels}}},
                {"message", {{"type", "string"}}},
                {"name", {{"type", "string"}}},
                {"file", {{"type", "string"}}},
                {"line", {{"type", "integer"}, {"minimum", 0}}}}}}
      .dump();
}

std::string SceneUpdateSchema() {
  const json pose = {{"type", "object"},
                     {"properties",
                      {{"position", json::parse(kVector3Schema)},
                       {"orientation", json::parse(kQuaternionSchema)}}}};
  const json color = {{"type", "object"},
                      {"properties",
                       {{"r", {{"type", "number"}}},
                        {"g", {{"type", "number"}}},
                        {"b", {{"type", "number"}}},
                        {"a", {{"type", "number"}}}}}};
  const json cube = {
      {"type", "object"},
      {"properties", {{"pose", pose}, {"size", json::parse(kVector3Schema)}, {"color", color}}}};
  const json line = {{"type", "object"},
                     {"properties",
                      {{"type", {{"enum", {0, 1, 2}}}},  // line strip, loop, list
                       {"pose", pose},
                       {"thickness", {{"type", "number"}, {"minimum", 0}}},
                       {"scale_invisible", {{"type", "boolean"}}},
                       {"points", {{"type", "array"}, {"items", json::parse(kVector3Schema)}}},
                       {"color", color},
                       {"colors", {{"type", "array"}, {"items", color}}},
                       {"indices", {{"type", "array"}, {"items", {{"type", "integer"}}}}}}}};
  const json text = {{"type", "object"},
                     {"properties",
                      {{"pose", pose},
                       {"billboard", {{"type", "boolean"}}},
                       {"font_size", {{"type", "number"}}},
                       {"scale_invisible", {{"type", "boolean"}}},
                       {"color", color},
                       {"text", {{"type", "string"}}}}}};
  const json entity = {
      {"type", "object"},
      {"properties",
       {{"timestamp", json::parse(kTimeSchema)},
        {"frame_id", {{"type", "string"}}},
        {"id", {{"type", "string"}}},
        {"lifetime", json::parse(kTimeSchema)},
        {"frame_locked", {{"type", "boolean"}}},
        {"metadata",
         {{"type", "array"},
          {"items",
           {{"type", "object"},
            {"properties", {{"key", {{"type", "string"}}}, {"value", {{"type", "string"}}}}}}}}},
        {"cubes", {{"type", "array"}, {"items", cube}}}}}};
  return json{
      {"title", "foxglove.SceneUpdate"},
      {"description", "a 3D scene: the scenery, the ToF beams or what the firmware believes"},
      {"type", "object"},
      {"properties",
       {{"deletions", {{"type", "array"}}}, {"entities", {{"type", "array"}, {"items", entity}}}}}}
      .dump();
}

std::string SignalsSchema(const std::vector<std::string>& names) {
  json values = json::object();
  for (const std::string& name : names) values[name] = {{"type", {"number", "null"}}};
  return json{{"title", "unimouse.Signals"},
              {"description",
               "every signal of the run's robots, by name (SI units, the unit in the name); "
               "null for a value that is not a number"},
              {"type", "object"},
              {"properties",
               {{"timestamp", json::parse(kTimeSchema)},
                {"values", {{"type", "object"}, {"properties", values}}}}}}
      .dump();
}

std::string EventSchema() {
  return json{{"title", "unimouse.Event"},
              {"description",
               "something that happened in the run, for a replay to jump to (docs/replay.md)"},
              {"type", "object"},
              {"required", {"timestamp", "kind", "robot", "text", "data"}},
              {"properties",
               {{"timestamp", json::parse(kTimeSchema)},
                // the run's own kinds, contact and lost, and a scenario's (sim.event)
                {"kind", {{"type", "string"}, {"pattern", "^[a-z0-9_]{1,32}$"}}},
                {"robot", {{"type", "string"}}},
                {"text", {{"type", "string"}}},
                {"data", {{"type", "object"}}}}}}
      .dump();
}

// a list of cells, each [x, y] and more
json CellsSchema(int extra_items, const json& extra) {
  json items = json::array({{{"type", "integer"}}, {{"type", "integer"}}});
  for (int i = 0; i < extra_items; ++i) items.push_back(extra);
  return {{"type", "array"},
          {"items",
           {{"type", "array"},
            {"prefixItems", items},
            {"minItems", 2 + extra_items},
            {"maxItems", 2 + extra_items}}}};
}

std::string BeliefsSchema() {
  return json{{"title", "unimouse.Beliefs"},
              {"description",
               "what the firmware (or an mms program) believes about the maze, whole, whenever it "
               "changes: walls [x, y, walls, known] (side bits N 1, E 2, S 4, W 8), visited "
               "cells, the path it plans, cell colours as #rrggbb and cell texts"},
              {"type", "object"},
              {"required", {"timestamp", "robot", "walls", "visited", "path", "colours", "texts"}},
              {"properties",
               {{"timestamp", json::parse(kTimeSchema)},
                {"robot", {{"type", "string"}}},
                {"walls", CellsSchema(2, {{"type", "integer"}, {"minimum", 0}, {"maximum", 15}})},
                {"visited", CellsSchema(0, {})},
                {"path", CellsSchema(0, {})},
                {"colours", CellsSchema(1, {{"type", "string"}, {"pattern", "^#[0-9a-f]{6}$"}})},
                {"texts", CellsSchema(1, {{"type", "string"}})}}}}
      .dump();
}

std::string HudSchema() {
  return json{{"title", "unimouse.Hud"},
              {"description", "the lines the scenario shows, whenever they change"},
              {"type", "object"},
              {"required", {"timestamp", "lines"}},
              {"properties",
               {{"timestamp", json::parse(kTimeSchema)},
                {"lines", {{"type", "array"}, {"items", {{"type", "string"}}}}}}}}
      .dump();
}

std::string FirmwareValuesSchema() {
  return json{{"title", "unimouse.FirmwareValues"},
              {"description",
               "the named numbers a robot's firmware reported (debug value frames), the latest "
               "of each, whenever one changes"},
              {"type", "object"},
              {"required", {"timestamp", "robot", "values"}},
              {"properties",
               {{"timestamp", json::parse(kTimeSchema)},
                {"robot", {{"type", "string"}}},
                {"values",
                 {{"type", "object"}, {"additionalProperties", {{"type", {"number", "null"}}}}}}}}}
      .dump();
}

// a number as JSON, in the fewest digits that read back to the same double; JSON has no NaN
// or infinity
void AppendNumber(std::string& out, double value) {
  if (!std::isfinite(value)) {
    out += "null";
    return;
  }
  char digits[32];
  const auto [end, error] = std::to_chars(digits, digits + sizeof(digits), value);
  UNIMOUSE_DEMAND(error == std::errc());
  out.append(digits, end);
}

// a name from a robot file as a JSON string; text that is not UTF-8 is replaced, never refused
std::string JsonText(const std::string& text) {
  return json(text).dump(-1, ' ', false, json::error_handler_t::replace);
}

void AppendTimestamp(std::string& out, uint64_t time_ns) {
  out += "{\"sec\":" + std::to_string(time_ns / 1'000'000'000) +
         ",\"nsec\":" + std::to_string(time_ns % 1'000'000'000) + "}";
}

uint64_t Nanoseconds(double time_s) {
  return time_s <= 0 ? 0 : static_cast<uint64_t>(std::llround(time_s * 1e9));
}

json Timestamp(uint64_t time_ns) {
  return {{"sec", time_ns / 1'000'000'000}, {"nsec", time_ns % 1'000'000'000}};
}

// Scenes, beliefs and beams are written by hand, not through a JSON library: the firmware's
// beliefs are written whole each time they change, hundreds of cubes each time, and building them
// as JSON objects cost a run half its time again

// Foxglove's colours as JSON
constexpr const char* kWallColour = R"({"r":0.93,"g":0.93,"b":0.9,"a":1})";
constexpr const char* kPostColour = R"({"r":0.85,"g":0.15,"b":0.1,"a":1})";
constexpr const char* kObstacleColour = R"({"r":0.55,"g":0.55,"b":0.6,"a":1})";
constexpr const char* kBelievedWallColour = R"({"r":0.2,"g":0.5,"b":1,"a":1})";
constexpr const char* kVisitedColour = R"({"r":0.3,"g":0.75,"b":0.75,"a":0.8})";
constexpr const char* kPathColour = R"({"r":0.95,"g":0.8,"b":0.1,"a":1})";
constexpr const char* kLabelColour = R"({"r":1,"g":1,"b":1,"a":1})";
constexpr const char* kHitColour = R"({"r":0.1,"g":0.95,"b":0.2,"a":1})";
constexpr const char* kMissColour = R"({"r":0.95,"g":0.15,"b":0.1,"a":1})";

void AppendVector(std::string& out, double x, double y, double z) {
  out += "{\"x\":";
  AppendNumber(out, x);
  out += ",\"y\":";
  AppendNumber(out, y);
  out += ",\"z\":";
  AppendNumber(out, z);
  out += '}';
}

// a pose at a point, turned by `yaw_rad` about z
void AppendPose(std::string& out, double x, double y, double z, double yaw_rad = 0) {
  out += "{\"position\":";
  AppendVector(out, x, y, z);
  out += ",\"orientation\":{\"x\":0,\"y\":0,\"z\":";
  AppendNumber(out, std::sin(yaw_rad / 2));
  out += ",\"w\":";
  AppendNumber(out, std::cos(yaw_rad / 2));
  out += "}}";
}

// a cube of the given full sizes at a point, after a comma unless it is the list's first
void AppendCube(std::string& out, double x, double y, double z, double size_x, double size_y,
                double size_z, const char* colour, double yaw_rad = 0) {
  if (out.back() != '[') out += ',';
  out += "{\"pose\":";
  AppendPose(out, x, y, z, yaw_rad);
  out += ",\"size\":";
  AppendVector(out, size_x, size_y, size_z);
  out += ",\"color\":";
  out += colour;
  out += '}';
}

// a SceneUpdate of one entity in the world frame, with every primitive list Foxglove's schema
// has: `metadata`, `cubes`, `lines` and `texts` are JSON arrays
std::string SceneUpdate(const char* id, uint64_t time_ns, const std::string& metadata,
                        const std::string& cubes, const std::string& lines,
                        const std::string& texts) {
  std::string out = "{\"deletions\":[],\"entities\":[{\"timestamp\":";
  AppendTimestamp(out, time_ns);
  out += ",\"frame_id\":\"world\",\"id\":\"";
  out += id;
  // lifetime 0: until replaced
  out += "\",\"lifetime\":{\"sec\":0,\"nsec\":0},\"frame_locked\":false,\"metadata\":" + metadata +
         ",\"arrows\":[],\"cubes\":" + cubes +
         ",\"spheres\":[],\"cylinders\":[],\"lines\":" + lines +
         ",\"triangles\":[],\"texts\":" + texts + ",\"models\":[]}]}";
  return out;
}

// what the firmware believes as Foxglove draws it: its walls as blue strips on the walls' tops,
// visited cells as small tiles, cell colours as floor tiles, texts as labels, its path as a line
std::string BeliefsScene(const FirmwareBeliefs& beliefs, const MazeDimensions& dims,
                         uint64_t time_ns) {
  auto centre = [&](int x, int y) { return CellCentre({x, y}, Heading::kNorth, dims); };
  std::string cubes = "[", lines = "[", texts = "[";
  for (const auto& [cell, w] : beliefs.walls) {
    const Pose2D c = centre(cell.first, cell.second);
    for (int side = 0; side < 4; ++side) {  // north, east, south, west
      const uint8_t bit = static_cast<uint8_t>(1 << side);
      if (!(w.known & bit) || !(w.walls & bit)) continue;
      const bool north_south = side == 0 || side == 2;
      const double dx = side == 1 ? 0.5 : side == 3 ? -0.5 : 0;
      const double dy = side == 0 ? 0.5 : side == 2 ? -0.5 : 0;
      AppendCube(cubes, c.x_m + dims.cell_m * dx, c.y_m + dims.cell_m * dy,
                 dims.wall_height_m + 0.003, north_south ? dims.cell_m : 0.008,
                 north_south ? 0.008 : dims.cell_m, 0.004, kBelievedWallColour);
    }
  }
  std::set<std::pair<int, int>> seen;
  for (const Cell& v : beliefs.visited) {
    if (!seen.insert({v.x, v.y}).second) continue;
    const Pose2D c = centre(v.x, v.y);
    AppendCube(cubes, c.x_m, c.y_m, 0.001, dims.cell_m / 3, dims.cell_m / 3, 0.001, kVisitedColour);
  }
  for (const auto& [cell, letter] : beliefs.colours) {
    const std::optional<Rgb8> rgb = CellColourOf(letter);
    if (!rgb) continue;
    char colour[64];
    std::snprintf(colour, sizeof(colour), R"({"r":%.4g,"g":%.4g,"b":%.4g,"a":1})", rgb->r / 255.0,
                  rgb->g / 255.0, rgb->b / 255.0);
    const Pose2D c = centre(cell.first, cell.second);
    const double side_m = dims.cell_m - dims.wall_thickness_m;
    AppendCube(cubes, c.x_m, c.y_m, 0.0005, side_m, side_m, 0.0008, colour);
  }
  for (const auto& [cell, text] : beliefs.texts) {
    const Pose2D c = centre(cell.first, cell.second);
    if (texts.back() != '[') texts += ',';
    texts += "{\"pose\":";
    AppendPose(texts, c.x_m, c.y_m, 0.01);
    texts += ",\"billboard\":true,\"font_size\":12,\"scale_invisible\":true,\"color\":";
    texts += kLabelColour;
    texts += ",\"text\":" + JsonText(text) + "}";
  }
  if (beliefs.path.size() > 1) {
    lines += "{\"type\":0,\"pose\":";  // a line strip through the cells' centres
    AppendPose(lines, 0, 0, 0);
    lines += ",\"thickness\":";
    AppendNumber(lines, dims.cell_m / 15);
    lines += ",\"scale_invisible\":false,\"points\":[";
    for (size_t i = 0; i < beliefs.path.size(); ++i) {
      if (i > 0) lines += ',';
      const Pose2D c = centre(beliefs.path[i].x, beliefs.path[i].y);
      AppendVector(lines, c.x_m, c.y_m, 0.004);
    }
    lines += "],\"color\":";
    lines += kPathColour;
    lines += ",\"colors\":[],\"indices\":[]}";
  }
  return SceneUpdate("beliefs", time_ns, "[]", cubes + "]", lines + "]", texts + "]");
}

// the ToF beams, each a segment from its sensor, green on a hit and red on a miss as drawn
std::string BeamsScene(const Kernel& kernel, uint64_t time_ns) {
  const mjData& d = kernel.state().data();
  std::string points, colours;
  for (const BeamSpec& beam : kernel.model().beams) {
    const BeamLine line = BeamLineOf(beam, d, kernel.state().signals());
    for (const auto& p : {line.from_m, line.to_m}) {
      if (!points.empty()) {
        points += ',';
        colours += ',';
      }
      AppendVector(points, p[0], p[1], p[2]);
      colours += line.hit ? kHitColour : kMissColour;
    }
  }
  std::string list = "[{\"type\":2,\"pose\":";  // a list of segments
  AppendPose(list, 0, 0, 0);
  list += ",\"thickness\":0.004,\"scale_invisible\":false,\"points\":[" + points +
          "],\"color\":" + kLabelColour + ",\"colors\":[" + colours + "],\"indices\":[]}]";
  return SceneUpdate("beams", time_ns, "[]", "[]", list, "[]");
}

// the scenery (a maze's walls and posts, a scenario's boxes) as cubes in the world frame; with a
// maze, its dimensions ride along as the entity's metadata, for a player to place cells
std::string SceneryUpdate(const World& world) {
  std::string cubes = "[";
  for (const StaticBox& box : world.scenery()) {
    const char* colour = box.kind == StaticBox::Kind::kPost   ? kPostColour
                         : box.kind == StaticBox::Kind::kWall ? kWallColour
                                                              : kObstacleColour;
    AppendCube(cubes, box.center_m[0], box.center_m[1], box.center_m[2], 2 * box.half_m[0],
               2 * box.half_m[1], 2 * box.half_m[2], colour, box.yaw_rad);
  }
  json metadata = json::array();
  if (const Maze* maze = world.maze()) {
    const MazeDimensions& dims = maze->dimensions();
    auto add = [&](const char* key, const std::string& value) {
      metadata.push_back({{"key", key}, {"value", value}});
    };
    add("maze_width_cells", std::to_string(maze->width()));
    add("maze_height_cells", std::to_string(maze->height()));
    add("cell_m", json(dims.cell_m).dump());
    add("wall_thickness_m", json(dims.wall_thickness_m).dump());
    add("wall_height_m", json(dims.wall_height_m).dump());
  }
  return SceneUpdate("scenery", 0, metadata.dump(), cubes + "]", "[]", "[]");
}

// Foxglove's levels: 2 info, 3 warning, 4 error
int FoxgloveLevel(int level) {
  switch (level) {
    case UNIMOUSE_LOG_WARNING:
      return 3;
    case UNIMOUSE_LOG_ERROR:
      return 4;
    case UNIMOUSE_LOG_DETAIL:
      return 1;  // DEBUG: Foxglove's viewers can hide it, as the console does
  }
  return 2;
}

}  // namespace

RecordLevel ParseRecordLevel(const std::string& text) {
  if (text == "off") return RecordLevel::kOff;
  if (text == "light") return RecordLevel::kLight;
  if (text == "full") return RecordLevel::kFull;
  throw InputError("--record " + text + ": give off, light or full");
}

RunRecording::RunRecording(const std::string& path, RecordLevel level) : level_(level) {
  UNIMOUSE_DEMAND(level != RecordLevel::kOff);
  writer_ = std::make_unique<McapWriter>(path, McapWriterOptions{});
  // first, so that a player meets it before anything it might misread
  writer_->AddMetadata("unimouse.recording", {{"format", std::to_string(kRecordingFormat)}});
  frame_transform_schema_ =
      writer_->AddSchema("foxglove.FrameTransform", "jsonschema", FrameTransformSchema());
  auto channel = [&](const char* schema_name, const std::string& schema, const char* topic) {
    return writer_->AddChannel(writer_->AddSchema(schema_name, "jsonschema", schema), topic,
                               "json");
  };
  log_channel_ = channel("foxglove.Log", LogSchema(), "/log");
  events_channel_ = channel("unimouse.Event", EventSchema(), "/events");
  beliefs_channel_ = channel("unimouse.Beliefs", BeliefsSchema(), "/beliefs");
  hud_channel_ = channel("unimouse.Hud", HudSchema(), "/hud");
  values_channel_ = channel("unimouse.FirmwareValues", FirmwareValuesSchema(), "/firmware/values");
}

RunRecording::~RunRecording() = default;

void RunRecording::OpenRobotChannels(const Kernel& kernel) {
  const uint16_t scene_schema =
      writer_->AddSchema("foxglove.SceneUpdate", "jsonschema", SceneUpdateSchema());
  const uint16_t scenery = writer_->AddChannel(scene_schema, "/scenery", "json");
  writer_->Write(scenery, 0, SceneryUpdate(kernel.world()));
  if (!kernel.model().beams.empty()) {
    beams_channel_ = writer_->AddChannel(scene_schema, "/beams", "json");
    beam_every_steps_ =
        std::max<int64_t>(1, std::llround(kBeamRecordPeriod_s / kernel.timestep_s()));
  }
  if (const Maze* maze = kernel.world().maze()) {
    maze_dimensions_ = maze->dimensions();
    beliefs_scene_channel_ = writer_->AddChannel(scene_schema, "/beliefs/scene", "json");
  }
  const int robots = kernel.robot_count();
  for (int i = 0; i < robots; ++i) {
    const std::string& name = kernel.robot_name(i);
    frame_names_.push_back(JsonText(name.empty() ? "robot" : name));
    const std::string topic = name.empty() ? "/robot/pose" : "/robots/" + name + "/pose";
    pose_channels_.push_back(writer_->AddChannel(frame_transform_schema_, topic, "json"));
  }
  const std::vector<std::string>& names = kernel.model().signal_names;
  for (const std::string& name : names) signal_keys_.push_back(JsonText(name) + ":");
  signals_channel_ = writer_->AddChannel(
      writer_->AddSchema("unimouse.Signals", "jsonschema", SignalsSchema(names)), "/signals",
      "json");
  sample_every_steps_ =
      level_ == RecordLevel::kFull
          ? 1
          : std::max<int64_t>(1, std::llround(kLightRecordPeriod_s / kernel.timestep_s()));
}

bool RunRecording::Sample(const Kernel& kernel) {
  if (sample_every_steps_ == 0) OpenRobotChannels(kernel);
  const State& state = kernel.state();
  if (beam_every_steps_ > 0 && state.step() % beam_every_steps_ == 0) {
    const uint64_t time_ns = Nanoseconds(state.data().time);
    writer_->Write(beams_channel_, time_ns, BeamsScene(kernel, time_ns));
  }
  if (state.step() % sample_every_steps_ != 0) return false;
  const mjData& d = state.data();
  const uint64_t time_ns = Nanoseconds(d.time);

  // written by hand, not through a JSON library: this runs a hundred times a simulated second
  std::string& m = message_;
  for (size_t i = 0; i < pose_channels_.size(); ++i) {
    const Pose2D pose = kernel.world().RobotPose(d, static_cast<int>(i));
    m = "{\"timestamp\":";
    AppendTimestamp(m, time_ns);
    m += ",\"parent_frame_id\":\"world\",\"child_frame_id\":" + frame_names_[i];
    m += ",\"translation\":{\"x\":";
    AppendNumber(m, pose.x_m);
    m += ",\"y\":";
    AppendNumber(m, pose.y_m);
    m += ",\"z\":0},\"rotation\":{\"x\":0,\"y\":0,\"z\":";
    AppendNumber(m, std::sin(pose.yaw_rad / 2));
    m += ",\"w\":";
    AppendNumber(m, std::cos(pose.yaw_rad / 2));
    m += "}}";
    writer_->Write(pose_channels_[i], time_ns, m);
  }
  const std::vector<double>& signals = state.signals();
  m = "{\"timestamp\":";
  AppendTimestamp(m, time_ns);
  m += ",\"values\":{";
  for (size_t i = 0; i < signal_keys_.size() && i < signals.size(); ++i) {
    if (i > 0) m += ',';
    m += signal_keys_[i];
    AppendNumber(m, signals[i]);
  }
  m += "}}";
  writer_->Write(signals_channel_, time_ns, m);
  return true;
}

void RunRecording::Beliefs(double time_s, const std::string& robot,
                           const FirmwareBeliefs& beliefs) {
  const uint64_t time_ns = Nanoseconds(time_s);
  // each entry [x, y, ...], after a comma unless it is the list's first
  std::string m = ",\"robot\":" + JsonText(robot) + ",\"walls\":[";
  auto entry = [&m](int x, int y) {
    if (m.back() != '[') m += ',';
    m += '[' + std::to_string(x) + ',' + std::to_string(y);
  };
  for (const auto& [cell, w] : beliefs.walls) {
    entry(cell.first, cell.second);
    m += ',' + std::to_string(w.walls) + ',' + std::to_string(w.known) + ']';
  }
  // each cell once, in the order first visited: a snapshot stays as small as the maze
  m += "],\"visited\":[";
  std::set<std::pair<int, int>> seen;
  for (const Cell& c : beliefs.visited) {
    if (!seen.insert({c.x, c.y}).second) continue;
    entry(c.x, c.y);
    m += ']';
  }
  m += "],\"path\":[";
  for (const Cell& c : beliefs.path) {
    entry(c.x, c.y);
    m += ']';
  }
  m += "],\"colours\":[";
  for (const auto& [cell, letter] : beliefs.colours) {
    if (const std::optional<Rgb8> rgb = CellColourOf(letter)) {
      entry(cell.first, cell.second);
      m += ",\"" + HexColour(*rgb) + "\"]";
    }
  }
  m += "],\"texts\":[";
  for (const auto& [cell, text] : beliefs.texts) {
    entry(cell.first, cell.second);
    m += ',' + JsonText(text) + ']';
  }
  m += "]}";
  // a firmware often says again what it said (the cell it is in, on a speed run): a snapshot that
  // shows nothing new is left out, and so is its scene, about half of them in a contest
  std::string& last = last_beliefs_[robot];
  if (m == last) return;
  last = m;
  std::string stamped = "{\"timestamp\":";
  AppendTimestamp(stamped, time_ns);
  writer_->Write(beliefs_channel_, time_ns, stamped + m);
  if (maze_dimensions_) {
    writer_->Write(beliefs_scene_channel_, time_ns,
                   BeliefsScene(beliefs, *maze_dimensions_, time_ns));
  }
}

void RunRecording::Hud(double time_s, const std::vector<std::string>& lines) {
  const uint64_t time_ns = Nanoseconds(time_s);
  const json message = {{"timestamp", Timestamp(time_ns)}, {"lines", lines}};
  writer_->Write(hud_channel_, time_ns,
                 message.dump(-1, ' ', false, json::error_handler_t::replace));
}

void RunRecording::FirmwareValues(double time_s, const std::string& robot,
                                  const std::map<std::string, double>& values) {
  const uint64_t time_ns = Nanoseconds(time_s);
  std::string m = "{\"timestamp\":";
  AppendTimestamp(m, time_ns);
  m += ",\"robot\":" + JsonText(robot) + ",\"values\":{";
  bool first = true;
  for (const auto& [name, value] : values) {
    if (!first) m += ',';
    first = false;
    m += JsonText(name) + ":";
    AppendNumber(m, value);
  }
  m += "}}";
  writer_->Write(values_channel_, time_ns, m);
}

void RunRecording::Event(double time_s, const std::string& kind, const std::string& robot,
                         const std::string& text, const std::string& data_json) {
  const uint64_t time_ns = Nanoseconds(time_s);
  std::string m = "{\"timestamp\":";
  AppendTimestamp(m, time_ns);
  m += ",\"kind\":" + JsonText(kind) + ",\"robot\":" + JsonText(robot) +
       ",\"text\":" + JsonText(text) + ",\"data\":" + data_json + "}";
  writer_->Write(events_channel_, time_ns, m);
}

void RunRecording::Log(double time_s, int level, const std::string& component,
                       const std::string& message) {
  const uint64_t time_ns = Nanoseconds(time_s);
  json line = {{"timestamp", Timestamp(time_ns)},
               {"level", FoxgloveLevel(level)},
               {"message", message},
               {"name", component},
               {"file", ""},
               {"line", 0}};
  // a line of a firmware or a script need not be UTF-8: replaced, never refused
  writer_->Write(log_channel_, time_ns, line.dump(-1, ' ', false, json::error_handler_t::replace));
}

bool RunRecording::AttachFile(const std::string& name, const std::string& path,
                              const std::string& media_type, double time_s) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::stringstream content;
  content << in.rdbuf();
  Attach(name, content.str(), media_type, time_s);
  return true;
}

void RunRecording::Attach(const std::string& name, const std::string& content,
                          const std::string& media_type, double time_s) {
  writer_->Attach(name, media_type, Nanoseconds(time_s), content);
}

void RunRecording::AddMetadata(const std::string& name,
                               const std::map<std::string, std::string>& values) {
  writer_->AddMetadata(name, values);
}

void RunRecording::Close() { writer_->Close(); }

}  // namespace unimouse
