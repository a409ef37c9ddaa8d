# SPDX-License-Identifier: GPL-3.0-or-later
# The example plugin outside the tree (examples/out-of-tree-plugin) builds against an install of
# this build, through find_package(unimouse), and the installed program loads it.
# cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK=... -DGENERATOR=... -P out_of_tree_plugin_check.cmake
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${ARGN} failed (${rc}):\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK})
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK}/prefix)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/out-of-tree-plugin -B ${WORK}/build -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${WORK}/prefix)
run(${CMAKE_COMMAND} --build ${WORK}/build)
if(NOT EXISTS ${WORK}/build/libunimouse_lab.so)
  message(FATAL_ERROR "no libunimouse_lab.so in ${WORK}/build")
endif()
run(${WORK}/prefix/bin/unimouse --plugin-path ${WORK}/build plugins)
foreach(expected "lab.voltage_divider" "top_ohm" "bottom_ohm" "unimouse.dc_motor")
  string(FIND "${out}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "`unimouse plugins` does not list ${expected}:\n${out}")
  endif()
endforeach()
