# SPDX-License-Identifier: GPL-3.0-or-later
# Empties the collection of result records (support/result_records.h) before the tests run, so
# that no copy from an earlier run is checked, and puts one record there: the result of a short
# run of the program, so that the schema check has a record whatever subset of the tests runs.
#
#   cmake -DDIR=collection -DPROGRAM=unimouse -DWORK=scratch -P clear_result_records.cmake
file(REMOVE_RECURSE "${DIR}" "${WORK}")
file(MAKE_DIRECTORY "${DIR}")
execute_process(COMMAND "${PROGRAM}" run --maze none --duration 0.01 --no-pictures --out "${WORK}"
  RESULT_VARIABLE code OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT code EQUAL 0 OR NOT EXISTS "${WORK}/result.json")
  message(FATAL_ERROR "a short run exited with ${code} and wrote no result.json:\n${output}")
endif()
file(COPY_FILE "${WORK}/result.json" "${DIR}/ResultRecordsCleared__result.json")
