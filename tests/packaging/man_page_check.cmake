# SPDX-License-Identifier: GPL-3.0-or-later
# `unimouse run --help` and the man page unimouse-run.1 name the same options, both ways.
# cmake -DPROGRAM=... -DPAGE=.../unimouse-run.1 -P man_page_check.cmake
execute_process(COMMAND ${PROGRAM} run --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "unimouse run --help failed (${rc})")
endif()
# help: an option line starts "  --robot TEXT=unimouse" or "  -h,--help"
string(REGEX MATCHALL "\n  (-[a-z],)?--[a-z][a-z-]*" lines "${help}")
set(help_options "")
foreach(line IN LISTS lines)
  string(REGEX MATCH "--[a-z][a-z-]*" option "${line}")
  list(APPEND help_options ${option})
endforeach()

# the page: an option is the line after .TP, "\fB\-\-robot\fR TEXT=unimouse"
file(READ ${PAGE} page)
string(REGEX MATCHALL "\n\\.TP\n[^\n]*" items "${page}")
set(page_options "")
foreach(item IN LISTS items)
  string(REPLACE "\\-" "-" item "${item}")
  string(REGEX MATCH "--[a-z][a-z-]*" option "${item}")
  list(APPEND page_options ${option})
endforeach()

list(SORT help_options)
list(SORT page_options)
if(NOT help_options STREQUAL page_options OR help_options STREQUAL "")
  set(only_help ${help_options})
  list(REMOVE_ITEM only_help ${page_options})
  set(only_page ${page_options})
  list(REMOVE_ITEM only_page ${help_options})
  message(FATAL_ERROR "${PAGE} and `unimouse run --help` disagree: only in --help: [${only_help}], "
                      "only in the page: [${only_page}] (rebuild writes the page from --help)")
endif()
list(LENGTH help_options count)
message(STATUS "${count} options agree")
