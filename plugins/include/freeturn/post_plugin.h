/* The post-processor plugin ABI (docs/writing-a-post.md).
 *
 * A post-processor is a shared library that exports one C function,
 * `freeturn_post_entry`, returning a table of function pointers. Only plain C types cross
 * the boundary: no C++ types, no exceptions, no memory freed on the other side. The host
 * checks `abi_version` when it loads the library and refuses any other version.
 *
 * The host does the geometry and the machine's standard settings (axis layout, signs,
 * offsets, wrap, limits); the plugin turns axis values into the dialect's text through
 * the writer the host gives it. Errors are return values (non-zero) with a message
 * written into the caller's buffer. */
#ifndef FREETURN_POST_PLUGIN_H
#define FREETURN_POST_PLUGIN_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define FREETURN_POST_ABI_VERSION 3
#define FREETURN_POST_ENTRY "freeturn_post_entry"

/* One block in machine units: mm for X and Z, degrees for C and B (C already wrapped if
 * the machine wraps it), and the block's duration in seconds (0 for the first block). */
typedef struct ft_block {
  double x, z, c, b;
  double time;
} ft_block;

typedef struct ft_axis_layout {
  int count;          /* 2 to 4 */
  char letters[4];    /* 'X', 'Z', 'C', 'B' in program order */
  int decimals[4];    /* digits after the point, per axis */
} ft_axis_layout;

typedef struct ft_program_info {
  const char* program_name;      /* the job's name */
  const char* machine_name;
  const char* dialect_settings;  /* YAML text under the machine's dialect key ("" if none) */
  ft_axis_layout layout;
  int c_wrapped;                 /* 1: C in [0, 360); 0: accumulating */
  int interpolation;             /* 0: linear, 1: PVT */
  double spindle_rpm;            /* 0 in X-Z profile mode */
  double feed;                   /* mm/min in profile mode */
  int feed_per_minute;           /* 1: program feed per minute (X-Z only); 0: inverse time */
  long long block_count;         /* blocks the program will receive */
  /* The clearance base: no block's Z goes past top_z on the side away from the part
   * (the host checks it), so a move at top_z + z_away * retract clears the part whatever
   * X, C and B do. Approach and retract there, never relative to one block (version 3). */
  double top_z;                  /* machine Z (mm) */
  int z_away;                    /* +1: a larger machine Z is away from the part; -1: smaller */
} ft_program_info;

/* The host's output. `write` appends to the current file; `open_file` starts another one
 * beside the main program (a child point file) and makes it current; `select_main` makes
 * the main program current again. Each returns 0 on success. */
typedef struct ft_writer {
  void* context;
  int (*write)(void* context, const char* data, size_t size);
  int (*open_file)(void* context, const char* name);
  int (*select_main)(void* context);
} ft_writer;

typedef struct ft_post {
  int abi_version; /* FREETURN_POST_ABI_VERSION */
  const char* name;
  /* NULL on failure, with a message in `error`. `info` and `writer` outlive the handle. */
  void* (*create)(const ft_program_info* info, const ft_writer* writer, char* error,
                  size_t error_size);
  int (*begin)(void* post, char* error, size_t error_size);
  int (*blocks)(void* post, const ft_block* blocks, size_t count, char* error, size_t error_size);
  int (*end)(void* post, char* error, size_t error_size);
  void (*destroy)(void* post);
} ft_post;

typedef const ft_post* (*ft_post_entry_fn)(void);

#ifdef __cplusplus
}
#endif

#endif
