# SPDX-License-Identifier: GPL-3.0-or-later
# Fails when a file of kernel/core includes a project header from outside kernel/core and the
# plugin API (kernel/include): the kernel proper knows nothing of scenarios, pictures, maze
# tools, runs or the program. Run as: cmake -DSOURCE_DIR=<repo> -P core_includes.cmake
file(GLOB core_files ${SOURCE_DIR}/kernel/core/*.h ${SOURCE_DIR}/kernel/core/*.cc
  ${SOURCE_DIR}/kernel/core/include/*.h)
set(bad "")
foreach(file IN LISTS core_files)
  file(STRINGS ${file} lines REGEX "^#include \"")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" header "${line}")
    if(NOT EXISTS ${SOURCE_DIR}/kernel/core/${header} AND
       NOT EXISTS ${SOURCE_DIR}/kernel/core/include/${header} AND
       NOT EXISTS ${SOURCE_DIR}/kernel/include/${header})
      list(APPEND bad "${file}: ${header}")
    endif()
  endforeach()
endforeach()
if(bad)
  list(JOIN bad "\n  " text)
  message(FATAL_ERROR "kernel/core includes from outside itself:\n  ${text}")
endif()
list(LENGTH core_files count)
message(STATUS "${count} files of kernel/core include only kernel/core and the plugin API")
