/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The plugin ABI: the only contract a component library and the kernel must agree on.
 *
 * A plugin library exports one symbol, unimouse_plugin_v1, returning a table of component types.
 * The loader checks the ABI version, the struct sizes and the MuJoCo version before it uses
 * anything else. Within ABI version 1, structs only grow at the end, and every struct says its
 * size: the kernel accepts a plugin built against an older, smaller header (the fields it lacks
 * read as 0 and its missing hooks as NULL), and a plugin reads a kernel-made struct's newer
 * fields only when its size covers them (UNIMOUSE_HAS_FIELD). A NULL optional hook means "not
 * implemented". No C++ exception may cross this boundary. C99. */
#ifndef UNIMOUSE_PLUGIN_ABI_H_
#define UNIMOUSE_PLUGIN_ABI_H_

#include <mujoco/mujoco.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define UNIMOUSE_ABI_VERSION 1
#define UNIMOUSE_EXPORT __attribute__((visibility("default")))

/* whether a struct whose size field says `s->size` includes `field` */
#define UNIMOUSE_HAS_FIELD(s, type, field) \
  ((s)->size >= offsetof(type, field) + sizeof(((type*)0)->field))

/* kinds of component parameters */
typedef enum unimouse_param_kind {
  UNIMOUSE_PARAM_NUMBER = 1,  /* finite double */
  UNIMOUSE_PARAM_INTEGER = 2, /* whole number, stored as double */
  UNIMOUSE_PARAM_BOOL = 3,    /* true/false, stored as 0 or 1 */
  UNIMOUSE_PARAM_STRING = 4
} unimouse_param_kind;

/* One declared parameter of a component type. The kernel validates YAML against these before a
 * component is created, so create() only ever sees complete, in-range values. */
typedef struct unimouse_param {
  const char* name;           /* snake_case with a unit suffix where it has a unit: "gear_ratio" */
  int kind;                   /* unimouse_param_kind */
  int required;               /* 1: no default, the YAML must give it */
  double default_number;      /* NUMBER, INTEGER, BOOL */
  const char* default_string; /* STRING */
  double min, max;            /* inclusive bounds for NUMBER and INTEGER; +-inf when unbounded */
  int min_exclusive;          /* 1: value must be strictly greater than min */
  const char* choices;        /* STRING: '|'-separated allowed values, NULL for any */
  const char* doc;            /* one line: what it means */
} unimouse_param;

/* validated parameter values of one component instance; opaque, read through unimouse_host */
typedef struct unimouse_config unimouse_config;

/* log levels; an error stops the run with exit code 3 once the hook returns */
enum {
  UNIMOUSE_LOG_INFO = 0,
  UNIMOUSE_LOG_WARNING = 1,
  UNIMOUSE_LOG_ERROR = 2,
  UNIMOUSE_LOG_FIRMWARE = 3, /* a line of the firmware's own log (link frame 8) */
  UNIMOUSE_LOG_DETAIL = 4    /* appended in 0.7: chatter (a report per cell) for the run's log and
                                recording; the console shows it only when asked (-v) */
};

/* Services the kernel offers while a component is being created. */
typedef struct unimouse_host {
  uint32_t size; /* sizeof(unimouse_host) as the kernel saw it */
  void* ctx;
  double (*config_number)(const unimouse_config* cfg, const char* name);
  const char* (*config_string)(const unimouse_config* cfg, const char* name);
  int (*config_given)(const unimouse_config* cfg, const char* name); /* 0: the default applies */
  void (*log)(void* ctx, int level, const char* message);
  /* appended in 0.2: 1 when a data file (the robot file) gave the value, 0 when the command line
   * or a default did; a value from a data file may not start a program or make a path */
  int (*config_from_data_file)(const unimouse_config* cfg, const char* name);
} unimouse_host;

/* Name resolution at bind time. Every lookup returns an id >= 0, or -1 after the kernel has
 * recorded an error naming the component and its YAML line; bind then returns non-zero. */
typedef struct unimouse_bind {
  uint32_t size; /* sizeof(unimouse_bind) as the kernel saw it */
  void* ctx;
  const mjModel* model;
  double timestep_s;
  const char* component_name; /* the instance's name in the robot file */
  double period_s;            /* how often its hooks run: a whole number of steps */
  const char* output_dir;     /* where the run writes its files */
  int (*joint)(void* ctx, const char* name);
  int (*actuator)(void* ctx, const char* name);
  int (*site)(void* ctx, const char* name);
  int (*body)(void* ctx, const char* name);
  int (*signal_read)(void* ctx, const char* name);  /* a signal another component writes */
  int (*signal_write)(void* ctx, const char* name); /* a signal this component alone writes */
  int (*rng_stream)(void* ctx, const char* name);   /* named, seeded stream: "tof.front" */
  void (*set_state_size)(void* ctx, int nstate);    /* doubles of evolving state it needs */
  /* appended in 0.2: a beam the host draws, from a site along its x axis, as long as the value of
   * a signal (metres); a value of range_max_m or more is a miss */
  void (*declare_beam)(void* ctx, int site, int length_signal, double range_max_m);
  /* appended in 0.4: the maze the world was built from, for a firmware that asks for it; width
   * and height 0 on an open floor. The goal is the smallest rectangle holding every goal cell,
   * maze_goal_is_rectangle 0 when it holds other cells too. */
  int maze_width_cells, maze_height_cells;
  double maze_cell_m;
  int maze_goal_x0, maze_goal_y0, maze_goal_x1, maze_goal_y1;
  int maze_goal_is_rectangle;
  /* appended in 0.5: what the component is to the run, declared once: a bitwise or of
   * UNIMOUSE_TRAIT_*. The host decides pacing, warnings and pictures from these, never from where
   * a component came from (a robot file or the command line). */
  void (*declare_traits)(void* ctx, int traits);
} unimouse_bind;

/* what a component can declare about itself at bind (appended in 0.5) */
enum {
  UNIMOUSE_TRAIT_FIRMWARE = 1,  /* a firmware drives the robot through it and reports to it */
  UNIMOUSE_TRAIT_WALL_CLOCK = 2 /* its peer lives in real time (a board): the run keeps to the
                                   wall clock while the firmware does not set the pace */
};

/* A text line a component logged (a firmware's log channel, for one), with when and who. */
typedef struct unimouse_message {
  double time_s;
  int level;
  const char* source; /* component name */
  const char* text;
} unimouse_message;

/* What a component reports to the host on a typed path (appended in 0.2): what a firmware
 * believes about the maze, sent on the link's debug channels (docs/protocol.md). */
enum {
  UNIMOUSE_REPORT_WALLS = 1,   /* cell x, y: walls and known, side bits N 1, E 2, S 4, W 8 */
  UNIMOUSE_REPORT_VISITED = 2, /* cell x, y */
  UNIMOUSE_REPORT_PATH = 3,    /* cells, the path it plans: ncells pairs x, y */
  UNIMOUSE_REPORT_VALUE = 4,   /* a named number */
  /* a number the component measured over the run, for the run's record (result.json's
   * "measurements"): name, with its unit in it, and value; sent from finish (appended in 0.3) */
  UNIMOUSE_REPORT_MEASURE = 5,
  /* the firmware started over inside the run (docs/protocol.md, "Restarts"); value: how many
   * times so far; sent from sense (appended in 0.6) */
  UNIMOUSE_REPORT_RESTART = 6
};

typedef struct unimouse_report {
  uint32_t size; /* sizeof(unimouse_report) as the component saw it */
  int kind;      /* UNIMOUSE_REPORT_* */
  int x, y;
  int walls, known;
  const int* cells; /* PATH: x0, y0, x1, y1, ... */
  int ncells;
  const char* name; /* VALUE */
  double value;     /* VALUE */
} unimouse_report;

/* Everything a hook may touch during one tick. In sense, data is read-only by contract. */
typedef struct unimouse_tick {
  uint32_t size; /* sizeof(unimouse_tick) as the kernel saw it */
  void* ctx;
  const mjModel* model;
  mjData* data;
  double* state;                                /* this component's slice */
  int nstate;                                   /* doubles in state */
  double* signals;                              /* every signal, indexed by the ids from bind */
  int64_t step;                                 /* physics steps taken before this tick */
  double time_s;                                /* simulated time at the start of this tick */
  double (*rng_uniform)(void* ctx, int stream); /* [0, 1) */
  double (*rng_normal)(void* ctx, int stream);  /* standard normal */
  /* distance along a unit direction to the first wall, obstacle or floor within max_m that is not
   * part of a robot; -1 when nothing is hit */
  double (*ray_cast)(void* ctx, const double origin[3], const double direction[3], double max_m);
  void (*log)(void* ctx, int level, const char* message);
  /* messages logged since this component's previous hook call, oldest first */
  const unimouse_message* messages;
  int nmessages;
  /* appended in 0.2 */
  void (*report)(void* ctx, const unimouse_report* report); /* see unimouse_report */
  /* 1: the firmware sets the pace (lock-step), so the run does not pace to the wall clock */
  void (*set_firmware_paced)(void* ctx, int paced);
} unimouse_tick;

/* One component type. create, bind and destroy are required; the hooks are optional. finish
 * runs once at the end of a run, however it ends, so a component can write out what it holds.
 * The first published layout ends at destroy (UNIMOUSE_COMPONENT_TYPE_V1_SIZE). */
typedef struct unimouse_component_type {
  uint32_t size;       /* sizeof(unimouse_component_type) as the plugin saw it */
  const char* name;    /* dotted, globally unique: "unimouse.dc_motor" */
  const char* summary; /* one line for `unimouse plugins` */
  int nparam;
  const unimouse_param* params;
  double default_period_s; /* 0: every physics step */
  /* returns the instance, or NULL after writing a reason into err */
  void* (*create)(const unimouse_config* cfg, const unimouse_host* host, char* err, int err_size);
  int (*bind)(void* self, const unimouse_bind* bind, char* err, int err_size); /* 0 on success */
  void (*reset)(const void* self, const unimouse_tick* tick);   /* writes initial state */
  void (*sense)(const void* self, const unimouse_tick* tick);   /* after mj_step1 */
  void (*actuate)(const void* self, const unimouse_tick* tick); /* before mj_step2 */
  void (*finish)(const void* self, const unimouse_tick* tick);  /* once, when the run ends */
  void (*destroy)(void* self);
  /* appended in 0.2: opens what the instance needs outside the process (a port, a child
   * process, a file) before the run's first reset; `unimouse check` never calls it. Returns 0,
   * or non-zero after writing a reason into err. */
  int (*start)(void* self, char* err, int err_size);
} unimouse_component_type;

/* the size of unimouse_component_type as ABI version 1 first published it */
#define UNIMOUSE_COMPONENT_TYPE_V1_SIZE (offsetof(unimouse_component_type, destroy) + sizeof(void*))

/* What a plugin library hands the loader. */
typedef struct unimouse_plugin_info {
  uint32_t abi_version;         /* UNIMOUSE_ABI_VERSION the plugin was built against */
  uint32_t size;                /* sizeof(unimouse_plugin_info) as the plugin saw it */
  uint32_t component_type_size; /* sizeof(unimouse_component_type) as the plugin saw it */
  int mujoco_version;           /* mjVERSION_HEADER the plugin was built against */
  int ntype;
  const unimouse_component_type* const* types;
} unimouse_plugin_info;

typedef const unimouse_plugin_info* (*unimouse_plugin_entry)(void);

/* the one symbol a plugin library exports */
#define UNIMOUSE_PLUGIN_SYMBOL "unimouse_plugin_v1"

#ifdef __cplusplus
}
#endif

#endif /* UNIMOUSE_PLUGIN_ABI_H_ */
