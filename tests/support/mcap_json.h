// SPDX-License-Identifier: GPL-3.0-or-later
// A recording (run.mcap) as the tests' own MCAP reader, tests/support/mcap_reader.py, reads it:
// written from the specification and sharing nothing with the writer, so it is an independent
// truth for what a recording holds.
#ifndef UNIMOUSE_TESTS_MCAP_JSON_H_
#define UNIMOUSE_TESTS_MCAP_JSON_H_

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace unimouse::testing {

/// The reader's JSON of `file`: "schemas", "channels" (id, topic, ...), "messages" (channel_id,
/// log_time in ns, data parsed), "complete". With `cut_ok`, a file that stops short (a killed
/// run) reads up to its last whole record. Null, and a failed expectation, when it cannot read it.
nlohmann::json ReadRecording(const std::string& file, bool cut_ok = false);

/// The messages of `recording` on `topic`, in the file's order.
std::vector<nlohmann::json> OnTopic(const nlohmann::json& recording, const std::string& topic);

}  // namespace unimouse::testing

#endif  // UNIMOUSE_TESTS_MCAP_JSON_H_
