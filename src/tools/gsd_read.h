/* A minimal reader of GSD files (file layer version 2.x, HOOMD-blue's
 * format, schema "hoomd") for the demonstration programs: one frame of
 * ellipsoids (pw85_mc --from). The layout is that of gsd_write.h: a
 * 256-byte header, a namelist of NUL-ended names, the index (32-byte
 * entries: frame, N, location, M, id, type, flags; the first entry of
 * location 0 ends it) and the data chunks. A chunk missing from the frame
 * is taken from frame 0, else given the schema's default (HOOMD's rule).
 * Every size and offset is checked against the file's length before it is
 * read; a malformed file is an error with a message, never a crash.
 * Little-endian hosts only (the byte order of GSD files). */
#ifndef PW85_GSD_READ_H
#define PW85_GSD_READ_H

#include <stddef.h>
#include <stdint.h>

typedef struct {
  uint64_t step;          /* configuration/step (default 0) */
  uint32_t n;             /* particles/N (default 0) */
  double box[6];          /* configuration/box: Lx, Ly, Lz, xy, xz, yz (default 1, 1, 1, 0, 0, 0) */
  double *position;       /* 3n, particles/position (default 0) */
  double *orientation;    /* 4n, particles/orientation (w, x, y, z) (default 1, 0, 0, 0) */
  uint32_t *typeid;       /* n, particles/typeid (default 0) */
  uint32_t n_types;       /* rows of particles/types (default 1) */
  double *semi_axes;      /* 3 n_types: a, b, c of each type's shape {"type": "Ellipsoid", ...}
                             in particles/type_shapes; NaN for a type of another or no shape */
  uint64_t n_frames;      /* frames in the file */
} gsd_hoomd_frame;

/* Reads frame `frame` of path (negative: counted from the end, -1 the
 * last). Returns 0 and *out (free with gsd_hoomd_frame_free), or -1 with a
 * message in message[0 .. size - 1] and *out zeroed. */
int gsd_read_hoomd_frame(const char *path, long long frame, gsd_hoomd_frame *out, char *message,
                         size_t size);

void gsd_hoomd_frame_free(gsd_hoomd_frame *frame);

#endif
