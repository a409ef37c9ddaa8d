// SPDX-License-Identifier: GPL-3.0-or-later
#include "mcap_json.h"

#include <gtest/gtest.h>

#include "run_program.h"
#include "text_file.h"

namespace unimouse::testing {

using nlohmann::json;

json ReadRecording(const std::string& file, bool cut_ok) {
  const std::string complaint = file + ".err";
  const Outcome o = Shell("(" + std::string(UNIMOUSE_PYTHON3) +
                          " " UNIMOUSE_SOURCE_DIR "/tests/support/mcap_reader.py '" + file + "'" +
                          (cut_ok ? " --cut-ok" : "") + " 2>'" + complaint + "')");
  EXPECT_EQ(o.exit_code, 0) << ReadTextFile(complaint);
  if (o.exit_code != 0) return json();
  return json::parse(o.output);
}

std::vector<json> OnTopic(const json& recording, const std::string& topic) {
  int channel = -1;
  for (const json& c : recording["channels"]) {
    if (c["topic"] == topic) channel = c["id"];
  }
  std::vector<json> out;
  for (const json& m : recording["messages"]) {
    if (m["channel_id"] == channel) out.push_back(m);
  }
  return out;
}

}  // namespace unimouse::testing
