/* A minimal writer of GSD files (file layer version 2.0, HOOMD-blue's
 * format, schema "hoomd" 1.4) for the demonstration programs pw85_mc,
 * pw85_md and pw85_edmd: the file layer (gsd_open, gsd_chunk,
 * gsd_end_frame, gsd_close) and one frame of identical ellipsoids in a
 * cubic periodic box (gsd_write_frame).
 *
 * Layout written: a 256-byte header, a namelist block of 16 x 64 bytes (the
 * chunk names back to back, each ended by a NUL; a chunk's id is the
 * position of its name), the data chunks
 * in the order written, then at gsd_close the index (one 32-byte entry per
 * chunk: frame, N, location, M, id, type, flags; sorted by frame then id,
 * closed by a zero entry) whose location the header is rewritten with.
 * Little-endian hosts only (the byte order of GSD files). */
#ifndef PW85_GSD_WRITE_H
#define PW85_GSD_WRITE_H

#include <stdint.h>
#include <stdio.h>

enum { GSD_UINT8 = 1, GSD_UINT32 = 3, GSD_UINT64 = 4, GSD_INT8 = 5, GSD_FLOAT = 9, GSD_DOUBLE = 10 };

typedef struct {
  uint64_t frame, n;
  int64_t location;
  uint32_t m;
  uint16_t id;
  uint8_t type, flags;
} gsd_entry;

enum { GSD_MAX_NAMES = 16 };

typedef struct {
  FILE *f;
  const char *names[GSD_MAX_NAMES]; /* the namelist: a chunk's id is its position */
  int n_names;
  gsd_entry *index;
  size_t count, cap;
  uint64_t frame;
  int error;
  char application[64];
} gsd_writer;

/* Creates path and writes the header and the namelist: the HOOMD names of
 * gsd_write.c, then the n_logged names of logged_names ("log/...", kept
 * by pointer until gsd_close; at most 8). application is recorded in the
 * header. Returns 0, or -1 (errno set) on failure. */
int gsd_open(gsd_writer *w, const char *path, const char *application,
             const char *const *logged_names, int n_logged);

/* Appends the chunk name (one of the names of the namelist) of the
 * current frame: n rows of m values of the given type. Returns 0 or -1. */
int gsd_chunk(gsd_writer *w, const char *name, int type, uint64_t n, uint32_t m,
              const void *data);

/* Closes the current frame: later chunks belong to the next one. */
void gsd_end_frame(gsd_writer *w);

/* Writes the index, rewrites the header, closes the file. Returns 0, or -1
 * if any write failed since gsd_open. */
int gsd_close(gsd_writer *w);

/* One frame of n identical ellipsoids (HOOMD type "E") in a periodic cubic
 * box of side box. */
typedef struct {
  uint64_t step;              /* configuration/step */
  uint32_t n;
  double box;
  double semi_axes[3];        /* along the body axes x, y, z */
  const double *position;     /* 3n centres, any periodic image */
  const double *orientation;  /* 4n quaternions (w, x, y, z), body to lab frame */
  int n_logged;               /* scalars logged with the frame: */
  const char *const *logged_name; /* names given to gsd_open */
  const double *logged_value;
} gsd_frame;

/* Appends the frame and ends it: step, positions (float32, wrapped into
 * [-box/2, box/2)^3), orientations (float32) and the logged scalars
 * (float64, read back as frame.log["pw85/..."]); the first frame of the
 * file also holds the box, N, the type "E", its typeid and its shape
 * {"type": "Ellipsoid", "a", "b", "c"} (the semi-axes), which HOOMD readers
 * carry over to the later frames. buffer: 4n floats of scratch. Returns 0
 * or -1. */
int gsd_write_frame(gsd_writer *w, const gsd_frame *frame, float *buffer);

/* Unit quaternion (w, x, y, z), w >= 0, of the rotation matrix a (row
 * major, orthonormal; its columns the body axes in the lab frame), by the
 * largest of 1 + tr a, 1 + 2 a_kk - tr a (Shepperd, J. Guidance and Control
 * 1(3), 223, 1978). */
void gsd_quaternion_of_rotation(const double a[9], double quat[4]);

#endif
