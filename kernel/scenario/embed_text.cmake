# SPDX-License-Identifier: GPL-3.0-or-later
# Writes a text file into a C++ source, as bytes, so that the library carries the file and reads
# nothing at run time. The source defines `std::string_view FUNCTION()`, declared in HEADER.
#
#   cmake -DINPUT=prelude.lua -DOUTPUT=prelude_source.cc -DFUNCTION=PreludeSource
#         -DHEADER=prelude.h -P embed_text.cmake
foreach(variable INPUT OUTPUT FUNCTION HEADER)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "embed_text.cmake: -D${variable}=... is missing")
  endif()
endforeach()

file(READ "${INPUT}" hex HEX)
if(hex STREQUAL "")
  message(FATAL_ERROR "embed_text.cmake: ${INPUT} is empty")
endif()
# every byte as 0xNN, twelve to a line
string(REPEAT "[0-9a-f]" 24 line)
string(REGEX REPLACE "(${line})" "\\1\n    " bytes "${hex}")
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1, " bytes "${bytes}")
string(REPLACE ", \n" ",\n" bytes "${bytes}")
get_filename_component(input_name "${INPUT}" NAME)

file(WRITE "${OUTPUT}" "// generated from ${input_name} by embed_text.cmake: edit ${input_name}
#include \"${HEADER}\"

namespace unimouse {

namespace {

constexpr unsigned char kBytes[] = {
    ${bytes}};

}  // namespace

std::string_view ${FUNCTION}() {
  return std::string_view(reinterpret_cast<const char*>(kBytes), sizeof(kBytes));
}

}  // namespace unimouse
")
