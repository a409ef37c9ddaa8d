# SPDX-License-Identifier: GPL-3.0-or-later
# Firmware in the style of the original UnimouseSim's Arduino examples, built for the PC against
# a stand-in for its library, and the tests that run them against the challenges over a
# pseudo-terminal and over the native link. Included from tests/CMakeLists.txt.
set(ORIGINAL_STYLE_DIR ${CMAKE_CURRENT_LIST_DIR})
set(ORIGINAL_FIRMWARE_DIR ${CMAKE_CURRENT_BINARY_DIR}/original_style)

add_library(unimouse_original_sim_robot STATIC ${ORIGINAL_STYLE_DIR}/sim_robot.cc)
target_include_directories(unimouse_original_sim_robot PUBLIC ${ORIGINAL_STYLE_DIR})
target_compile_options(unimouse_original_sim_robot PRIVATE ${UNIMOUSE_WARNINGS})

foreach(firmware wall_distance speed_control time_trial blocking_turns)
  add_executable(unimouse_original_${firmware} ${ORIGINAL_STYLE_DIR}/${firmware}.cc)
  target_link_libraries(unimouse_original_${firmware} PRIVATE unimouse_original_sim_robot)
  target_compile_options(unimouse_original_${firmware} PRIVATE ${UNIMOUSE_WARNINGS})
  set_target_properties(unimouse_original_${firmware} PROPERTIES OUTPUT_NAME ${firmware}
    RUNTIME_OUTPUT_DIRECTORY ${ORIGINAL_FIRMWARE_DIR})
  add_dependencies(unimouse_tests unimouse_original_${firmware})
endforeach()

target_sources(unimouse_tests PRIVATE ${ORIGINAL_STYLE_DIR}/original_firmware_test.cc)
target_compile_definitions(unimouse_tests PRIVATE
  ORIGINAL_FIRMWARE_DIR="${ORIGINAL_FIRMWARE_DIR}" ORIGINAL_STYLE_DIR="${ORIGINAL_STYLE_DIR}")
