/* SPDX-License-Identifier: GPL-3.0-or-later */
/* A minimal plugin written in plain C, as an out-of-tree author would. Compiled several times
 * with FAKE_* defines to produce one good library and one for each kind of mismatch. */
#include <stddef.h>

#include "unimouse/plugin_abi.h"

static int token;

static void* Create(const unimouse_config* cfg, const unimouse_host* host, char* err,
                    int err_size) {
  (void)cfg;
  (void)host;
  (void)err;
  (void)err_size;
  return &token;
}

static int Bind(void* self, const unimouse_bind* bind, char* err, int err_size) {
  (void)self;
  (void)bind;
  (void)err;
  (void)err_size;
  return 0;
}

static void Destroy(void* self) { (void)self; }

/* FAKE_OLD_HEADER stands for a plugin built before `start` was appended: its tables say they
 * end at destroy, and what lies beyond (here a start that fails) must never be read */
static int StartMustNotBeCalled(void* self, char* err, int err_size) {
  (void)self;
  if (err_size > 0) err[0] = '\0';
  return 1;
}

#ifdef FAKE_OLD_HEADER
#define FAKE_TYPE_SIZE UNIMOUSE_COMPONENT_TYPE_V1_SIZE
#define FAKE_START StartMustNotBeCalled
#else
#define FAKE_TYPE_SIZE sizeof(unimouse_component_type)
#define FAKE_START NULL
#endif
#ifndef FAKE_TYPE_TABLE_SIZE
#define FAKE_TYPE_TABLE_SIZE FAKE_TYPE_SIZE
#endif

static const unimouse_param kParams[] = {
    {"speed_m_per_s", UNIMOUSE_PARAM_NUMBER, 0, 1.5, NULL, 0, 10, 0, NULL, "how fast"},
};

static const unimouse_component_type kType = {FAKE_TYPE_SIZE,
                                              "fake.widget",
                                              "a widget from a C plugin",
                                              1,
                                              kParams,
                                              0.01,
                                              Create,
                                              Bind,
                                              NULL,
                                              NULL,
                                              NULL,
                                              NULL,
                                              Destroy,
                                              FAKE_START};

static const unimouse_component_type* const kTypes[] = {&kType};

#ifndef FAKE_ABI_VERSION
#define FAKE_ABI_VERSION UNIMOUSE_ABI_VERSION
#endif
#ifndef FAKE_INFO_SIZE
#define FAKE_INFO_SIZE sizeof(unimouse_plugin_info)
#endif
#ifndef FAKE_MUJOCO_VERSION
#define FAKE_MUJOCO_VERSION mjVERSION_HEADER
#endif

static const unimouse_plugin_info kInfo = {
    FAKE_ABI_VERSION, FAKE_INFO_SIZE, FAKE_TYPE_TABLE_SIZE, FAKE_MUJOCO_VERSION, 1, kTypes};

#ifdef FAKE_NO_SYMBOL
UNIMOUSE_EXPORT const unimouse_plugin_info* some_other_symbol(void) { return &kInfo; }
#else
UNIMOUSE_EXPORT const unimouse_plugin_info* unimouse_plugin_v1(void) { return &kInfo; }
#endif
