# SPDX-License-Identifier: MIT
# Builds Arduino sketches written against UnimouseSim, for the PC and for an Arduino Mega 2560.
# Used by the library's own examples, by `unimouse firmware build`, and by any CMake project
# through find_package(UnimouseFirmware):
#   unimouse_add_firmware(NAME SKETCH [OUTPUT_DIRECTORY DIR]): the program NAME (`unimouse run
#     --link native:NAME`) and the module NAME.so (`--link inproc:NAME.so`); needs C and C++
#   unimouse_add_avr_firmware(TARGET [SKETCHES NAME=SKETCH...] [BINARY_DIR DIR]
#     [OUTPUT_DIRECTORY DIR]): NAME.elf and NAME.hex for the emulated or a real board (`--link
#     avr:NAME.elf`), by avr-gcc and Debian's Arduino core (gcc-avr, avr-libc, arduino-core-avr),
#     in a build of their own (another toolchain); the library's examples by default

# the library's root (src/, pc/, avr/) is this file's parent folder, wherever it is installed
get_filename_component(root "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
set_property(GLOBAL PROPERTY UNIMOUSE_ARDUINO_LIB_DIR "${root}")

# the PC Arduino core (pc/) with the library's headers (src/), once per project: Serial on the
# process's protocol descriptor, millis() on the simulator's clock, main() calling setup()/loop();
# and its variant for a module loaded into the simulator (Serial on the simulator's queues, exit()
# bound inside the module)
function(unimouse_add_pc_cores)
  get_property(root GLOBAL PROPERTY UNIMOUSE_ARDUINO_LIB_DIR)
  set(common ${root}/pc/clock.cc ${root}/pc/print.cc ${root}/pc/wiring.cc ${root}/pc/WString.cc)
  add_library(unimouse_arduino_pc_core STATIC ${root}/pc/core.cc ${common})
  add_library(unimouse_arduino_inproc_core STATIC ${root}/pc/inproc_core.cc ${common}
    ${root}/pc/inproc_stdio.c ${root}/pc/inproc_exit.c)
  foreach(core unimouse_arduino_pc_core unimouse_arduino_inproc_core)
    target_include_directories(${core} PUBLIC ${root}/pc ${root}/src)
    target_compile_features(${core} PUBLIC cxx_std_17)
  endforeach()
  set_target_properties(unimouse_arduino_inproc_core PROPERTIES POSITION_INDEPENDENT_CODE ON)
  # -fno-gnu-unique: unique symbols would keep a module loaded after its run, and its globals
  # with it
  target_compile_options(unimouse_arduino_inproc_core PUBLIC
    $<$<COMPILE_LANGUAGE:CXX>:-fno-gnu-unique>)
endfunction()

# A sketch folder as the Arduino IDE builds it, for SKETCH = FOLDER/FOLDER.ino: its tabs (the
# folder's other .ino files, after it in name order) as #include lines into `includes_var`, and
# its .c and .cpp files into `sources_var`. Any other .ino file is a sketch alone.
function(unimouse_sketch_parts sketch includes_var sources_var)
  get_filename_component(folder ${sketch} DIRECTORY)
  get_filename_component(stem ${sketch} NAME_WE)
  get_filename_component(folder_name ${folder} NAME)
  set(includes "#include \"${sketch}\"\n")
  set(sources "")
  if(folder_name STREQUAL stem)
    file(GLOB tabs LIST_DIRECTORIES false CONFIGURE_DEPENDS ${folder}/*.ino)
    list(SORT tabs)
    foreach(tab IN LISTS tabs)
      if(NOT tab STREQUAL sketch)
        string(APPEND includes "#include \"${tab}\"\n")
      endif()
    endforeach()
    file(GLOB sources LIST_DIRECTORIES false CONFIGURE_DEPENDS ${folder}/*.cpp ${folder}/*.c)
    list(SORT sources)
  endif()
  set(${includes_var} "${includes}" PARENT_SCOPE)
  set(${sources_var} "${sources}" PARENT_SCOPE)
endfunction()

function(unimouse_add_firmware name sketch)
  cmake_parse_arguments(PARSE_ARGV 2 arg "" "OUTPUT_DIRECTORY" "")
  if(NOT arg_OUTPUT_DIRECTORY)
    set(arg_OUTPUT_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  endif()
  if(NOT TARGET unimouse_arduino_pc_core)
    unimouse_add_pc_cores()
  endif()
  get_filename_component(sketch ${sketch} ABSOLUTE)
  unimouse_sketch_parts(${sketch} includes sources)
  # a sketch is C++ without its includes, as the Arduino IDE compiles it: Arduino.h first
  set(source ${CMAKE_CURRENT_BINARY_DIR}/${name}_sketch.cc)
  file(CONFIGURE OUTPUT ${source} CONTENT "#include <Arduino.h>\n${includes}")
  add_executable(${name} ${source} ${sources})
  target_link_libraries(${name} PRIVATE unimouse_arduino_pc_core)
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${arg_OUTPUT_DIRECTORY})
  add_library(${name}_module MODULE ${source} ${sources})
  target_link_libraries(${name}_module PRIVATE unimouse_arduino_inproc_core)
  target_link_options(${name}_module PRIVATE -Wl,-Bsymbolic -Wl,--no-undefined)
  set_target_properties(${name}_module PROPERTIES PREFIX "" OUTPUT_NAME ${name}
    LIBRARY_OUTPUT_DIRECTORY ${arg_OUTPUT_DIRECTORY})
endfunction()

function(unimouse_add_avr_firmware target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "BINARY_DIR;OUTPUT_DIRECTORY" "SKETCHES")
  if(NOT arg_BINARY_DIR)
    set(arg_BINARY_DIR ${CMAKE_CURRENT_BINARY_DIR}/${target})
  endif()
  get_property(root GLOBAL PROPERTY UNIMOUSE_ARDUINO_LIB_DIR)
  set(sketches "")
  set(copies "")
  foreach(pair IN LISTS arg_SKETCHES)
    string(REGEX MATCH "^([^=]+)=(.+)$" matched "${pair}")
    if(NOT matched)
      message(FATAL_ERROR "unimouse_add_avr_firmware: '${pair}' is not NAME=SKETCH")
    endif()
    get_filename_component(sketch ${CMAKE_MATCH_2} ABSOLUTE)
    list(APPEND sketches ${CMAKE_MATCH_1}=${sketch})
    list(APPEND copies <BINARY_DIR>/${CMAKE_MATCH_1}.elf <BINARY_DIR>/${CMAKE_MATCH_1}.hex)
  endforeach()
  set(install_command ${CMAKE_COMMAND} -E true)
  if(arg_OUTPUT_DIRECTORY)
    set(install_command ${CMAKE_COMMAND} -E make_directory ${arg_OUTPUT_DIRECTORY}
      COMMAND ${CMAKE_COMMAND} -E copy ${copies} ${arg_OUTPUT_DIRECTORY})
  endif()
  string(REPLACE ";" "|" sketches "${sketches}")
  include(ExternalProject)
  ExternalProject_Add(${target}
    SOURCE_DIR ${root}/avr
    BINARY_DIR ${arg_BINARY_DIR}
    LIST_SEPARATOR |
    # the host's CFLAGS, CXXFLAGS and LDFLAGS (a package build's hardening) are not for an AVR
    CMAKE_ARGS -DCMAKE_TOOLCHAIN_FILE=${root}/avr/avr-toolchain.cmake
      -DCMAKE_C_FLAGS= -DCMAKE_CXX_FLAGS= -DCMAKE_ASM_FLAGS= -DCMAKE_EXE_LINKER_FLAGS=
      "-DSKETCHES=${sketches}"
    BUILD_ALWAYS ON
    INSTALL_COMMAND ${install_command})
endfunction()
