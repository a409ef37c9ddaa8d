/* SPDX-License-Identifier: MIT */
/* exit() and its kin for a firmware module: the module is linked -Bsymbolic, so the sketch's
 * calls bind to these and end the firmware, not the simulator that loaded it. C, where these
 * carry no exception specification to match. */
_Noreturn void unimouse_inproc_exit(int code);

void exit(int code) { unimouse_inproc_exit(code); }
void _exit(int code) { unimouse_inproc_exit(code); }
void _Exit(int code) { unimouse_inproc_exit(code); }
void quick_exit(int code) { unimouse_inproc_exit(code); }
