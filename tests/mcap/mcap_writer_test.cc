// SPDX-License-Identifier: GPL-3.0-or-later
// The MCAP writer checked by readers that share nothing with it: the tests' own reader written
// from the specification (tests/support/mcap_reader.py, which validates every record, CRC, index
// and the summary) and the official TypeScript reader, npm's @mcap/core, run by node. What they
// read is compared with what the test wrote.
#include "mcap_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "run_program.h"
#include "unimouse/errors.h"

namespace unimouse {

// a compression as the test's name and messages give it
void PrintTo(McapCompression compression, std::ostream* out) {
  const char* name = McapCompressionName(compression);
  *out << (*name ? name : "none");
}

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// a reader's run: its exit code and stdout (the reading), and its stderr (the complaint)
struct Reading {
  testing::Outcome outcome;
  std::string complaint;
};

Reading RunReader(const std::string& command, const std::string& file) {
  const std::string complaint = file + ".err";
  Reading r{testing::Shell("(" + command + " 2>'" + complaint + "')"), ""};
  r.complaint = ReadAll(complaint);
  return r;
}

json Read(const std::string& command, const std::string& file) {
  const Reading r = RunReader(command, file);
  EXPECT_EQ(r.outcome.exit_code, 0) << command << ": " << r.complaint;
  if (r.outcome.exit_code != 0) return json();
  return json::parse(r.outcome.output);
}

std::string PythonReader(const std::string& file, bool cut_ok = false) {
  return std::string(UNIMOUSE_PYTHON3) + " " UNIMOUSE_SOURCE_DIR "/tests/support/mcap_reader.py '" +
         file + "'" + (cut_ok ? " --cut-ok" : "");
}

json ReadWithPython(const std::string& file, bool cut_ok = false) {
  return Read(PythonReader(file, cut_ok), file);
}

// why @mcap/core cannot run here, or "" when it can
std::string McapCoreMissing() {
  if (std::string(UNIMOUSE_NODE).empty()) {
    return "no node: ./setup.sh installs nodejs and npm";
  }
  if (!fs::exists(UNIMOUSE_NODE_MCAP_DIR "/node_modules/@mcap/core/package.json")) {
    std::string why = ReadAll(UNIMOUSE_NODE_MCAP_DIR "/failure.txt");
    return "npm's @mcap/core is not installed in the build tree" +
           (why.empty() ? std::string(" (no npm?)") : ": " + why);
  }
  return "";
}

json ReadWithMcapCore(const std::string& file, const std::string& mode) {
  return Read(std::string(UNIMOUSE_NODE) +
                  " " UNIMOUSE_SOURCE_DIR
                  "/tests/support/mcap_core_read.cjs " UNIMOUSE_NODE_MCAP_DIR "/node_modules " +
                  mode + " '" + file + "'",
              file);
}

constexpr uint64_t kMs = 1'000'000;
constexpr const char* kSchema = R"({"type":"object","properties":{"i":{"type":"integer"}}})";
constexpr int kSteps = 3000;  // 3 s of 1 ms steps
constexpr int kLogEvery = 100;

// a sample run: a pose every 1 ms, a log line every 100 ms, a file attached at 1.5 s and a
// metadata record
void WriteSample(const std::string& path, McapWriterOptions options) {
  McapWriter writer(path, std::move(options));
  uint16_t schema = writer.AddSchema("unimouse.Sample", "jsonschema", kSchema);
  uint16_t pose = writer.AddChannel(schema, "/robot/pose", "json", {{"unit", "m"}});
  uint16_t log = writer.AddChannel(0, "/log", "json");
  for (int i = 0; i < kSteps; ++i) {
    writer.Write(pose, i * kMs, json{{"i", i}}.dump());
    if (i % kLogEvery == 0)
      writer.Write(log, i * kMs, json{{"line", "step " + std::to_string(i)}}.dump());
    if (i == 1500) writer.Attach("result.json", "application/json", i * kMs, R"({"passed":true})");
  }
  writer.AddMetadata("run", {{"seed", "7"}, {"version", "0.1.0"}});
  writer.Close();
}

// the messages WriteSample wrote, in order, as (channel, sequence, time, data)
std::vector<std::tuple<int, int, uint64_t, json>> SampleMessages() {
  std::vector<std::tuple<int, int, uint64_t, json>> out;
  for (int i = 0; i < kSteps; ++i) {
    out.emplace_back(0, i + 1, i * kMs, json{{"i", i}});
    if (i % kLogEvery == 0) {
      out.emplace_back(1, i / kLogEvery + 1, i * kMs, json{{"line", "step " + std::to_string(i)}});
    }
  }
  return out;
}

// the JSON a reader gives of a message's data: parsed already, or text to parse
json Data(const json& message) {
  return message["data"].is_string() ? json::parse(message["data"].get<std::string>())
                                     : message["data"];
}

uint64_t Time(const json& value) {
  return value.is_string() ? std::stoull(value.get<std::string>()) : value.get<uint64_t>();
}

void ExpectSampleRead(const json& read) {
  ASSERT_TRUE(read.is_object());
  EXPECT_TRUE(read["complete"].get<bool>());
  ASSERT_EQ(read["schemas"].size(), 1u);
  EXPECT_EQ(read["schemas"][0]["id"], 1);
  EXPECT_EQ(read["schemas"][0]["name"], "unimouse.Sample");
  EXPECT_EQ(read["schemas"][0]["encoding"], "jsonschema");
  EXPECT_EQ(read["schemas"][0]["data"], kSchema);
  ASSERT_EQ(read["channels"].size(), 2u);
  EXPECT_EQ(read["channels"][0], (json{{"id", 0},
                                       {"schema_id", 1},
                                       {"topic", "/robot/pose"},
                                       {"message_encoding", "json"},
                                       {"metadata", {{"unit", "m"}}}}));
  EXPECT_EQ(read["channels"][1], (json{{"id", 1},
                                       {"schema_id", 0},
                                       {"topic", "/log"},
                                       {"message_encoding", "json"},
                                       {"metadata", json::object()}}));

  auto expected = SampleMessages();
  ASSERT_EQ(read["messages"].size(), expected.size());
  for (size_t k = 0; k < expected.size(); ++k) {
    const json& m = read["messages"][k];
    auto [channel, sequence, time_ns, data] = expected[k];
    ASSERT_EQ(m["channel_id"], channel) << k;
    ASSERT_EQ(m["sequence"], sequence) << k;
    ASSERT_EQ(Time(m["log_time"]), time_ns) << k;
    ASSERT_EQ(Time(m["publish_time"]), time_ns) << k;
    ASSERT_EQ(Data(m), data) << k;
  }

  ASSERT_EQ(read["attachments"].size(), 1u);
  EXPECT_EQ(read["attachments"][0]["name"], "result.json");
  EXPECT_EQ(read["attachments"][0]["media_type"], "application/json");
  EXPECT_EQ(Time(read["attachments"][0]["log_time"]), 1500 * kMs);
  EXPECT_EQ(read["attachments"][0]["data"], R"({"passed":true})");
  ASSERT_EQ(read["metadata"].size(), 1u);
  EXPECT_EQ(read["metadata"][0]["name"], "run");
  EXPECT_EQ(read["metadata"][0]["metadata"], (json{{"seed", "7"}, {"version", "0.1.0"}}));
}

class McapWriterTest : public ::testing::TestWithParam<McapCompression> {
 protected:
  std::string File(const std::string& stem) {
    return testing::FreshDirectory("mcap_" + stem) + "/run.mcap";
  }
  McapWriterOptions Options() {
    McapWriterOptions options;
    options.compression = GetParam();
    return options;
  }
};

TEST_P(McapWriterTest, ItsOwnReaderFromTheSpecificationReadsBackEveryRecord) {
  std::string file = File("python");
  WriteSample(file, Options());
  json read = ReadWithPython(file);
  ExpectSampleRead(read);
  EXPECT_EQ(read["header"]["library"], "unimouse");

  // one chunk per second of log time, each compressed as asked
  ASSERT_EQ(read["chunks"].size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(read["chunks"][k]["compression"], McapCompressionName(GetParam()));
    EXPECT_EQ(read["chunks"][k]["start"], k * 1000 * kMs);
    EXPECT_EQ(read["chunks"][k]["end"], (k * 1000 + 999) * kMs);
  }
  EXPECT_EQ(read["statistics"]["message_count"], SampleMessages().size());
}

TEST_P(McapWriterTest, TheOfficialIndexedReaderReadsBackEveryRecord) {
  std::string missing = McapCoreMissing();
  if (!missing.empty()) GTEST_SKIP() << missing;
  std::string file = File("indexed");
  WriteSample(file, Options());
  json read = ReadWithMcapCore(file, "indexed");
  ExpectSampleRead(read);
  EXPECT_EQ(read["chunk_count"], 3);
}

TEST_P(McapWriterTest, TheOfficialStreamReaderReadsBackEveryRecord) {
  std::string missing = McapCoreMissing();
  if (!missing.empty()) GTEST_SKIP() << missing;
  std::string file = File("stream");
  WriteSample(file, Options());
  ExpectSampleRead(ReadWithMcapCore(file, "stream"));
}

TEST_P(McapWriterTest, AFileCutInHalfReadsToItsLastWholeChunk) {
  std::string file = File("cut");
  WriteSample(file, Options());
  json whole = ReadWithPython(file);
  ASSERT_TRUE(whole.is_object());

  std::string bytes = ReadAll(file);
  const size_t cut = bytes.size() / 2;
  std::string cut_file = file + ".cut.mcap";
  std::ofstream(cut_file, std::ios::binary) << bytes.substr(0, cut);

  // the whole file's reading says which chunks end before the cut, and so which messages stay
  std::vector<json> kept;
  for (const json& m : whole["messages"]) {
    const json& chunk = whole["chunks"][m["chunk"].get<size_t>()];
    if (chunk["offset"].get<size_t>() + chunk["length"].get<size_t>() <= cut) kept.push_back(m);
  }
  ASSERT_GT(kept.size(), 0u);
  ASSERT_LT(kept.size(), whole["messages"].size());

  // strict, the cut is a fault; told that files may be cut, every whole chunk reads
  auto strict = testing::Shell(std::string(UNIMOUSE_PYTHON3) +
                               " " UNIMOUSE_SOURCE_DIR "/tests/support/mcap_reader.py '" +
                               cut_file + "' >/dev/null");
  EXPECT_EQ(strict.exit_code, 1) << strict.output;
  json read = ReadWithPython(cut_file, /*cut_ok=*/true);
  ASSERT_TRUE(read.is_object());
  EXPECT_FALSE(read["complete"].get<bool>());
  ASSERT_EQ(read["messages"].size(), kept.size());
  for (size_t k = 0; k < kept.size(); ++k) ASSERT_EQ(read["messages"][k], kept[k]) << k;

  std::string missing = McapCoreMissing();
  if (!missing.empty()) GTEST_SKIP() << missing;
  json streamed = ReadWithMcapCore(cut_file, "stream");
  ASSERT_TRUE(streamed.is_object());
  EXPECT_FALSE(streamed["complete"].get<bool>());
  ASSERT_EQ(streamed["messages"].size(), kept.size());
  for (size_t k = 0; k < kept.size(); ++k) {
    ASSERT_EQ(Time(streamed["messages"][k]["log_time"]), Time(kept[k]["log_time"])) << k;
    ASSERT_EQ(Data(streamed["messages"][k]), Data(kept[k])) << k;
  }
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapWriterTest,
                         ::testing::Values(McapCompression::kZstd, McapCompression::kLz4,
                                           McapCompression::kNone),
                         [](const auto& param_info) {
                           const char* name = McapCompressionName(param_info.param);
                           return std::string(*name ? name : "none");
                         });

// the tests' reader checks every JSON message against its channel's schema: the recordings'
// schema tests rest on it refusing a message that breaks one
TEST(McapTestReader, RefusesAMessageThatBreaksItsChannelsSchema) {
  const std::string dir = testing::FreshDirectory("mcap_schema_check");
  const auto write = [&](const std::string& name, const json& message) {
    const std::string path = dir + "/" + name + ".mcap";
    McapWriter writer(path, {});
    const uint16_t schema =
        writer.AddSchema("test.Count", "jsonschema",
                         R"({"type":"object","properties":{"n":{"type":"integer","minimum":0},)"
                         R"("kind":{"type":"string","pattern":"^[a-z]+$"}},"required":["n"]})");
    const uint16_t channel = writer.AddChannel(schema, "/count", "json");
    writer.Write(channel, 0, json{{"n", 1}, {"kind", "fine"}}.dump());
    writer.Write(channel, kMs, message.dump());
    writer.Close();
    return path;
  };
  EXPECT_TRUE(ReadWithPython(write("follows", json{{"n", 2}}))["complete"].get<bool>());
  for (const auto& [name, message] :
       std::vector<std::pair<std::string, json>>{{"negative", {{"n", -1}}},
                                                 {"fraction", {{"n", 1.5}}},
                                                 {"missing", {{"kind", "fine"}}},
                                                 {"pattern", {{"n", 1}, {"kind", "Not fine"}}}}) {
    const std::string path = write(name, message);
    const Reading r = RunReader(PythonReader(path), path);
    EXPECT_EQ(r.outcome.exit_code, 1) << name;
    EXPECT_NE(r.complaint.find("the message does not follow schema 'test.Count'"),
              std::string::npos)
        << name << ": " << r.complaint;
  }
}

TEST(McapWriterChunks, CloseAtTheirSizeThreshold) {
  std::string file = testing::FreshDirectory("mcap_size") + "/run.mcap";
  McapWriterOptions options;
  options.chunk_size_bytes = 4096;
  options.chunk_span_ns = 1'000'000 * kMs;
  WriteSample(file, options);
  json read = ReadWithPython(file);
  ASSERT_TRUE(read.is_object());
  const json& chunks = read["chunks"];
  ASSERT_GT(chunks.size(), 10u);
  // every chunk but the last is closed by the message that took it past the threshold
  for (size_t k = 0; k + 1 < chunks.size(); ++k) {
    EXPECT_GE(chunks[k]["uncompressed_size"], 4096) << k;
    EXPECT_LT(chunks[k]["uncompressed_size"], 4096 + 100) << k;
  }
  EXPECT_LT(chunks.back()["uncompressed_size"], 4096 + 100);
}

TEST(McapWriterChunks, SpanAtMostTheirSpanOfLogTime) {
  std::string file = testing::FreshDirectory("mcap_span") + "/run.mcap";
  McapWriterOptions options;
  options.chunk_span_ns = 250 * kMs;
  WriteSample(file, options);
  json read = ReadWithPython(file);
  ASSERT_TRUE(read.is_object());
  ASSERT_EQ(read["chunks"].size(), 12u);
  for (const json& chunk : read["chunks"]) {
    EXPECT_LT(chunk["end"].get<uint64_t>() - chunk["start"].get<uint64_t>(), 250 * kMs);
  }
}

TEST(McapWriterChunks, AreOnDiskAsSoonAsTheyClose) {
  // the writer is never closed here, as in a run killed mid-way: what is on disk is read
  std::string file = testing::FreshDirectory("mcap_open") + "/run.mcap";
  McapWriter writer(file, McapWriterOptions{});
  uint16_t channel = writer.AddChannel(0, "/t", "json");
  for (int i = 0; i < 2500; ++i) writer.Write(channel, i * kMs, json{{"i", i}}.dump());

  json read = ReadWithPython(file, /*cut_ok=*/true);
  ASSERT_TRUE(read.is_object());
  EXPECT_FALSE(read["complete"].get<bool>());
  ASSERT_EQ(read["messages"].size(), 2000u);
  EXPECT_EQ(read["messages"][1999]["data"], (json{{"i", 1999}}));
}

TEST(McapWriterErrors, AFileThatCannotBeCreatedIsOneSentenceNamingIt) {
  std::string file = testing::FreshDirectory("mcap_missing") + "/no/such/dir/run.mcap";
  try {
    McapWriter writer(file, McapWriterOptions{});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              file + ": cannot create the recording: No such file or directory");
  }
}

TEST(McapWriterErrors, AFullDiskIsAnErrorNamingTheFileAndStaysOne) {
  McapWriter writer("/dev/full", McapWriterOptions{});
  uint16_t channel = writer.AddChannel(0, "/t", "json");
  writer.Write(channel, 0, "{}");
  EXPECT_THROW(
      {
        try {
          writer.Flush();
        } catch (const InputError& e) {
          EXPECT_EQ(std::string(e.what()),
                    "/dev/full: cannot write the recording: No space left on device");
          throw;
        }
      },
      InputError);
  EXPECT_THROW(writer.Write(channel, 1, "{}"), InputError);
  EXPECT_THROW(writer.Close(), InputError);
}

}  // namespace
}  // namespace unimouse
