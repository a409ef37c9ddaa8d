// SPDX-License-Identifier: GPL-3.0-or-later
// Every result.json a test produces is checked against docs/result.schema.json: the tests copy
// each one they find into UNIMOUSE_RESULT_RECORDS_DIR, and the last CTest,
// ResultRecordsFollowTheSchema, validates them all (tests/CMakeLists.txt). Nothing in a test
// asks for it: the programs a test runs through Unimouse() are followed by a look through the
// test's temporary directory, and so is the end of every test (for runs made in the test's own
// process). Only files named result.json are taken.
#ifndef UNIMOUSE_TESTS_RESULT_RECORDS_H_
#define UNIMOUSE_TESTS_RESULT_RECORDS_H_

#include <string>

namespace unimouse::testing {

/// Copies every result.json under `dir` not copied before with the same content into
/// UNIMOUSE_RESULT_RECORDS_DIR, named after the test that runs and the file's place under
/// `dir`. Returns how many it copied.
int CollectResultRecords(const std::string& dir);

}  // namespace unimouse::testing

#endif  // UNIMOUSE_TESTS_RESULT_RECORDS_H_
