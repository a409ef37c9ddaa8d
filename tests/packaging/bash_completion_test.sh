#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The bash completion offers the program's subcommands and options: bash_completion_test.sh
# COMPLETION_FILE PROGRAM
set -euo pipefail
source "$1"
program=$2
# completes the words given, the last one being the word under the cursor
complete_words() {
  COMP_WORDS=("$program" "$@")
  COMP_CWORD=$#
  COMPREPLY=()
  _unimouse
  echo "${COMPREPLY[*]}"
}
check() {
  local expected=$1 got
  shift
  got=$(complete_words "$@")
  if [ "$got" != "$expected" ]; then
    echo "unimouse $* <TAB>: expected '$expected', got '$got'"
    exit 1
  fi
}
check "maze" ma
check "--robot" run --ro
check "--duration" run --robot unimouse --du
check "solve" maze so
check "--strict" maze check --st
check "--set" check --se
check "robot-schema" rob
echo "completion offers subcommands and options"
