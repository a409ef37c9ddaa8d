/* SPDX-License-Identifier: MIT */
/* The interface between the simulator and a firmware built as a loadable module (`unimouse run
 * --link inproc:PATH.so`): the module's core reads and writes the simulator's byte queues
 * through these calls and hands control back whenever it waits for input. C, so that the
 * module and the simulator need not share a compiler's C++ ABI. */
#ifndef UNIMOUSE_INPROC_H_
#define UNIMOUSE_INPROC_H_

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define UNIMOUSE_INPROC_VERSION 1
/* the one symbol a firmware module exports */
#define UNIMOUSE_INPROC_ENTRY "unimouse_inproc_main_v1"

/** What the simulator lends the firmware; lives as long as the firmware runs. */
typedef struct unimouse_inproc_host {
  uint32_t size;    /**< sizeof(unimouse_inproc_host) */
  uint32_t version; /**< UNIMOUSE_INPROC_VERSION */
  void* self;
  /** Takes up to `max` bytes the simulator sent; never waits. Returns how many. */
  size_t (*read)(void* self, uint8_t* bytes, size_t max);
  /** Hands bytes to the simulator. */
  void (*write)(void* self, const uint8_t* bytes, size_t size);
  /** Gives control back to the simulator until it has looked at what was written; with
   * `awaiting_step`, the firmware has sent all it owes the step and waits for the next. */
  void (*suspend)(void* self, int awaiting_step);
  /** Ends the firmware: it called exit(code). Never returns. */
  void (*exit)(void* self, int code);
} unimouse_inproc_host;

/** Text the firmware module prints: its log, a line at each newline (the module's core). */
void unimouse_inproc_text(const char* text, size_t size);

/** The module's entry: runs setup() and then loop() for ever on the stack the simulator gave. */
typedef void (*unimouse_inproc_main)(const unimouse_inproc_host* host);

#ifdef __cplusplus
}
#endif

#endif /* UNIMOUSE_INPROC_H_ */
