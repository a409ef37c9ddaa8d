# SPDX-License-Identifier: GPL-3.0-or-later
# Fails when code outside the transport library spells a transport's scheme ("native:",
# "tcp:..."): what a spec means is the transport table's knowledge (kernel/transport), which
# the link, the run, batch, mms and the program read through its header. Tests, docs and data
# may spell specs; the code that interprets them may not. Run as:
#   cmake -DSOURCE_DIR=<repo> -P schemes_only_here.cmake
file(GLOB_RECURSE code ${SOURCE_DIR}/kernel/*.h ${SOURCE_DIR}/kernel/*.cc
  ${SOURCE_DIR}/plugins/*.h ${SOURCE_DIR}/plugins/*.cc)
set(schemes pty serial tcp native avr inproc)
set(bad "")
foreach(file IN LISTS code)
  if(file MATCHES "/kernel/transport/")
    continue()
  endif()
  foreach(scheme IN LISTS schemes)
    # a string literal that is a scheme, or holds a spec with it ("--link native:%s")
    file(STRINGS ${file} lines REGEX "\"(${scheme}\"|([^\"]*[^a-zA-Z0-9_\"])?${scheme}:)")
    foreach(line IN LISTS lines)
      string(REPLACE ";" "," line "${line}")
      list(APPEND bad "${file}: ${line}")
    endforeach()
  endforeach()
endforeach()
if(bad)
  list(JOIN bad "\n  " text)
  message(FATAL_ERROR "transport schemes spelt outside kernel/transport:\n  ${text}")
endif()
list(LENGTH code count)
message(STATUS "${count} files outside the transport library spell no transport scheme")
