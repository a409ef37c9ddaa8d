# SPDX-License-Identifier: GPL-3.0-or-later
# Installs into a scratch prefix, then runs the installed program from an unrelated directory;
# its result.json goes into RESULT_RECORDS for the schema check (tests/CMakeLists.txt).
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX}
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install failed")
endif()
execute_process(COMMAND ${PREFIX}/bin/unimouse run --scenario none --duration 0.05 --out ${PREFIX}/out
                WORKING_DIRECTORY /
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "share/unimouse/mazes/japan2018.txt|in maze japan2018")
  message(FATAL_ERROR "installed unimouse failed (${rc}): ${out} ${err}")
endif()
if(NOT EXISTS ${PREFIX}/out/result.json)
  message(FATAL_ERROR "no result.json from the installed program")
endif()
file(MAKE_DIRECTORY ${RESULT_RECORDS})
file(COPY_FILE ${PREFIX}/out/result.json ${RESULT_RECORDS}/InstalledProgramFindsItsData__result.json)
file(READ ${PREFIX}/out/result.json result)
if(NOT result MATCHES "${PREFIX}/share/unimouse/robots/unimouse.yaml")
  message(FATAL_ERROR "the installed program did not use its installed robot: ${result}")
endif()
