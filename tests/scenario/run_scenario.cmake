# SPDX-License-Identifier: GPL-3.0-or-later
# Runs a scenario with a controller as a user would, and checks the exact exit code of
# `unimouse run` (0 passed, 1 failed: a crash, a script error or bad input fails the test) and
# that result.json says the same.
#
#   cmake -DPROGRAM=unimouse -DSCENARIO=name -DCONTROLLER=file.lua -DOUT=dir -DEXPECT=0|1
#         [-DROBOT=bundled robot or file]
#         [-DSETS=name=value,...] [-DRESULT_RECORDS=dir] -P run_scenario.cmake
#
# The result.json is copied into RESULT_RECORDS, for the schema check (tests/CMakeLists.txt).
set(command "${PROGRAM}" run --out "${OUT}" --scenario "${SCENARIO}" --controller "${CONTROLLER}")
if(ROBOT)
  list(APPEND command --robot "${ROBOT}")
endif()
if(SETS)
  string(REPLACE "," ";" sets "${SETS}")
  foreach(set IN LISTS sets)
    list(APPEND command --set "${set}")
  endforeach()
endif()
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND ${command} RESULT_VARIABLE code OUTPUT_VARIABLE output
  ERROR_VARIABLE output)
list(JOIN command " " shown)
if(RESULT_RECORDS AND EXISTS "${OUT}/result.json")
  get_filename_component(run_name "${OUT}" NAME)
  file(MAKE_DIRECTORY "${RESULT_RECORDS}")
  file(COPY_FILE "${OUT}/result.json" "${RESULT_RECORDS}/BundledScenario.${run_name}__result.json")
endif()
if(NOT code STREQUAL "${EXPECT}")
  message(FATAL_ERROR "${shown}\nexited with '${code}', not ${EXPECT}:\n${output}")
endif()

if(EXPECT STREQUAL "0")
  set(status passed)
else()
  set(status failed)
endif()
file(READ "${OUT}/result.json" result)
string(JSON recorded GET "${result}" scenario status)
string(JSON reason GET "${result}" scenario reason)
if(NOT recorded STREQUAL status)
  message(FATAL_ERROR "${shown}\nresult.json says '${recorded}', not '${status}'")
endif()
message(STATUS "${SCENARIO} ${status}: ${reason}")
