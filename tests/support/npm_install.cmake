# SPDX-License-Identifier: GPL-3.0-or-later
# Installs the npm packages a test runs into DIR/node_modules, at the versions PACKAGE_DIR's
# package-lock.json pins (npm ci). Without npm, or without the registry, the build goes on and
# DIR/failure.txt says why, for the tests that need the packages to skip with that reason.
file(MAKE_DIRECTORY ${DIR})
file(REMOVE ${DIR}/failure.txt)
if(NOT NPM)
  file(WRITE ${DIR}/failure.txt "no npm: ./setup.sh installs nodejs and npm")
  return()
endif()
configure_file(${PACKAGE_DIR}/package.json ${DIR}/package.json COPYONLY)
configure_file(${PACKAGE_DIR}/package-lock.json ${DIR}/package-lock.json COPYONLY)
# no install scripts: the packages are data for node, nothing of theirs runs at build time
execute_process(COMMAND ${NPM} ci --no-audit --no-fund --ignore-scripts --loglevel=error
  WORKING_DIRECTORY ${DIR} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  string(REGEX REPLACE "\n.*" "" first_line "${output}")
  file(WRITE ${DIR}/failure.txt "npm ci failed (${result}): ${first_line}")
  message(WARNING "npm ci in ${DIR} failed; the tests that read recordings with @mcap/core will skip")
  return()
endif()
file(WRITE ${DIR}/installed.stamp "")
