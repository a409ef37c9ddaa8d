// SPDX-License-Identifier: GPL-3.0-or-later
// The MCAP reader on files it did not write: the official TypeScript writer's (npm's @mcap/core,
// run by node, tests/support/mcap_core_write.cjs, whose content the test knows), those files cut
// short or damaged, and files that are not MCAP at all.
#include "mcap_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "run_program.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;

struct Seen : McapVisitor {
  std::map<uint16_t, McapChannel> channels;
  std::map<uint16_t, McapSchema> schemas;
  struct Message {
    uint16_t channel;
    uint64_t time_ns;
    std::string data;
  };
  std::vector<Message> messages;
  std::map<std::string, std::string> attachments;
  std::map<std::string, std::map<std::string, std::string>> metadata;

  void OnSchema(const McapSchema& s) override { schemas[s.id] = s; }
  void OnChannel(const McapChannel& c) override { channels[c.id] = c; }
  void OnMessage(uint16_t channel, uint64_t time_ns, std::string_view data) override {
    messages.push_back({channel, time_ns, std::string(data)});
  }
  void OnAttachment(const std::string& name, const std::string&, uint64_t,
                    std::string_view data) override {
    attachments[name] = std::string(data);
  }
  void OnMetadata(const std::string& name,
                  const std::map<std::string, std::string>& values) override {
    metadata[name] = values;
  }
};

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void WriteAll(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

class McapReaderTest : public ::testing::TestWithParam<const char*> {
 protected:
  void SetUp() override {
    if (std::string(UNIMOUSE_NODE).empty()) GTEST_SKIP() << "no node: ./setup.sh installs nodejs";
    if (!fs::exists(UNIMOUSE_NODE_MCAP_DIR "/node_modules/@mcap/core/package.json")) {
      GTEST_SKIP() << "npm's @mcap/core is not installed in the build tree";
    }
    dir_ = testing::FreshDirectory("mcap_reader");
    file_ = (dir_ / "official.mcap").string();
    const testing::Outcome o = testing::Shell(
        std::string(UNIMOUSE_NODE) +
        " " UNIMOUSE_SOURCE_DIR "/tests/support/mcap_core_write.cjs " UNIMOUSE_NODE_MCAP_DIR
        "/node_modules " +
        GetParam() + " '" + file_ + "' 2>&1");
    ASSERT_EQ(o.exit_code, 0) << o.output;
  }

  fs::path dir_;
  std::string file_;
};

TEST_P(McapReaderTest, ReadsEverythingTheOfficialWriterWrote) {
  Seen seen;
  const McapReadOutcome outcome = ReadMcap(file_, seen);
  EXPECT_EQ(outcome.cut_short, "");
  EXPECT_EQ(outcome.library, "mcap_core_write");
  ASSERT_EQ(seen.schemas.size(), 1u);
  EXPECT_EQ(seen.schemas.begin()->second.name, "test.Count");
  EXPECT_EQ(seen.schemas.begin()->second.data,
            R"({"type":"object","properties":{"i":{"type":"integer"}}})");
  ASSERT_EQ(seen.channels.size(), 2u);
  std::map<std::string, uint16_t> id;
  for (const auto& [channel_id, c] : seen.channels) id[c.topic] = channel_id;
  EXPECT_EQ(seen.channels[id["/even"]].metadata,
            (std::map<std::string, std::string>{{"side", "even"}}));
  EXPECT_EQ(seen.channels[id["/odd"]].message_encoding, "json");

  ASSERT_EQ(seen.messages.size(), 1000u);
  for (int i = 0; i < 1000; ++i) {
    const Seen::Message& m = seen.messages[static_cast<size_t>(i)];
    ASSERT_EQ(m.channel, id[i % 2 == 0 ? "/even" : "/odd"]) << i;
    ASSERT_EQ(m.time_ns, static_cast<uint64_t>(i) * 1'000'000) << i;
    ASSERT_EQ(m.data, "{\"i\":" + std::to_string(i) + "}") << i;
  }
  EXPECT_EQ(seen.attachments, (std::map<std::string, std::string>{{"notes.txt", "hello"}}));
  EXPECT_EQ(seen.metadata["test.meta"],
            (std::map<std::string, std::string>{{"a", "1"}, {"b", "two"}}));
}

TEST_P(McapReaderTest, AFileCutShortReadsUpToItsLastWholeRecordAndSaysWhere) {
  const std::string bytes = ReadAll(file_);
  const std::string cut = (dir_ / "cut.mcap").string();
  WriteAll(cut, bytes.substr(0, bytes.size() / 2));
  Seen seen;
  const McapReadOutcome outcome = ReadMcap(cut, seen);
  EXPECT_NE(outcome.cut_short.find("the file ends at byte"), std::string::npos)
      << outcome.cut_short;
  // a prefix of the messages, in order, each whole
  ASSERT_GT(seen.messages.size(), 100u);
  ASSERT_LT(seen.messages.size(), 1000u);
  for (size_t i = 0; i < seen.messages.size(); ++i) {
    ASSERT_EQ(seen.messages[i].data, "{\"i\":" + std::to_string(i) + "}") << i;
  }
}

TEST_P(McapReaderTest, AChunkThatFailsItsCheckEndsTheReadingThereSayingWhy) {
  std::string bytes = ReadAll(file_);
  // a byte in the middle of the second chunk, found by walking the records (opcode, length)
  size_t at = 8, chunks = 0;
  while (at + 9 <= bytes.size()) {
    uint64_t length = 0;
    for (int i = 0; i < 8; ++i)
      length |= uint64_t{static_cast<uint8_t>(bytes[at + 1 + i])} << (8 * i);
    if (bytes[at] == 0x06 && ++chunks == 2) break;
    at += 9 + length;
  }
  ASSERT_EQ(chunks, 2u);
  const size_t middle = at + bytes.size() / 1000 + 60;  // past the chunk's own fields
  bytes[middle] = static_cast<char>(bytes[middle] ^ 0x5A);
  const std::string damaged = (dir_ / "damaged.mcap").string();
  WriteAll(damaged, bytes);
  Seen seen;
  const McapReadOutcome outcome = ReadMcap(damaged, seen);
  EXPECT_NE(outcome.cut_short.find("the chunk at byte " + std::to_string(at)), std::string::npos)
      << outcome.cut_short;
  // what the first chunk held, and nothing of the second
  EXPECT_GT(seen.messages.size(), 10u);
  EXPECT_LT(seen.messages.size(), 500u);
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapReaderTest, ::testing::Values("zstd", "none"));

// the sentence a file gets, or "" when it reads
std::string Refusal(const std::string& path) {
  Seen seen;
  try {
    ReadMcap(path, seen);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(McapReaderRefusalTest, AFileThatIsNotMcapIsOneSentenceNamingIt) {
  const fs::path dir = testing::FreshDirectory("mcap_refusals");
  const std::string empty = (dir / "empty.mcap").string();
  WriteAll(empty, "");
  EXPECT_EQ(Refusal(empty), empty + ": the file is empty, not an MCAP recording");
  const std::string text = (dir / "notes.mcap").string();
  WriteAll(text, "time_s,x_m\n0,1\n");
  EXPECT_EQ(Refusal(text), text + ": not an MCAP recording (it does not start with MCAP's magic)");
  const std::string newer = (dir / "newer.mcap").string();
  WriteAll(newer, std::string("\x89MCAP1\r\n", 8) + std::string(64, '\0'));
  EXPECT_EQ(
      Refusal(newer),
      newer + ": an MCAP file of major version 1, newer than the version 0 this unimouse reads");
  const std::string missing = (dir / "missing.mcap").string();
  EXPECT_NE(Refusal(missing).find(missing + ": cannot open the recording"), std::string::npos);
}

}  // namespace
}  // namespace unimouse
