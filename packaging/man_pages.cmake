# SPDX-License-Identifier: GPL-3.0-or-later
# Writes the man pages from the program's own --help, so they cannot drift from it: unimouse.1,
# and unimouse-SUB.1 (unimouse-maze-solve.1, ...) for every subcommand its help lists, with
# help2man. cmake -DPROGRAM=... -DHELP2MAN=... -DOUT_DIR=... -P man_pages.cmake
cmake_minimum_required(VERSION 3.25)
file(REMOVE_RECURSE ${OUT_DIR})
file(MAKE_DIRECTORY ${OUT_DIR})

# writes the page of `words` (a list: "", "run", "maze;solve") and of every subcommand below it
function(write_page words summary)
  execute_process(COMMAND ${PROGRAM} ${words} --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${PROGRAM} ${words} --help failed (${rc})")
  endif()
  list(JOIN words "-" suffix)
  set(page unimouse)
  if(suffix)
    set(page unimouse-${suffix})
  endif()

  # the subcommands are the indented names after "Subcommands:"
  set(see_also "")
  string(FIND "${help}" "\nSubcommands:\n" at)
  if(at GREATER -1)
    string(SUBSTRING "${help}" ${at} -1 listing)
    string(REGEX MATCHALL "\n  [a-z][a-z-]*  +[^\n]*" entries "${listing}")
    foreach(entry IN LISTS entries)
      string(REGEX REPLACE "^\n  ([a-z-]+)  +(.*)$" "\\1" sub "${entry}")
      string(REGEX REPLACE "^\n  ([a-z-]+)  +(.*)$" "\\2" sub_summary "${entry}")
      set(sub_words ${words})
      list(APPEND sub_words ${sub})
      write_page("${sub_words}" "${sub_summary}")
      string(APPEND see_also ".BR ${page}-${sub} (1)\n.br\n")
    endforeach()
  endif()

  set(include_option "")
  if(see_also)
    set(include_option --include=${OUT_DIR}/${page}.h2m)
    file(WRITE ${OUT_DIR}/${page}.h2m "[SEE ALSO]\n${see_also}")
  endif()
  list(JOIN words " " command)
  execute_process(COMMAND ${HELP2MAN} --no-info --no-discard-stderr --version-option=--version
                    "--help-option=${command} --help" "--name=${summary}"
                    ${include_option} --output=${OUT_DIR}/${page}.1 ${PROGRAM}
                  RESULT_VARIABLE rc)
  file(REMOVE ${OUT_DIR}/${page}.h2m)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "help2man failed on '${command} --help' (${rc})")
  endif()
  # a subcommand's page is named after it, not after the program
  file(READ ${OUT_DIR}/${page}.1 text)
  string(TOUPPER ${page} title)
  string(REGEX REPLACE "\n\\.TH UNIMOUSE " "\n.TH ${title} " text "${text}")
  string(REPLACE "-" "\\\\-" page_roff ${page})  # roff hyphen, escaped once more for the regex
  string(REGEX REPLACE "\n\\.SH NAME\n[^ ]+ " "\n.SH NAME\n${page_roff} " text "${text}")
  file(WRITE ${OUT_DIR}/${page}.1 "${text}")
endfunction()

# the program's summary is its help's first line: "unimouse VERSION: SUMMARY"
execute_process(COMMAND ${PROGRAM} --help OUTPUT_VARIABLE help)
string(REGEX MATCH "^[^:\n]*: ([^\n]*)" _ "${help}")
write_page("" "${CMAKE_MATCH_1}")
