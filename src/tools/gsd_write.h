/* A minimal writer of GSD files (file layer version 2.0, HOOMD-blue's
 * format, schema "hoomd" 1.4) for the demonstration programs.
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

enum { GSD_UINT8 = 1, GSD_UINT32 = 3, GSD_UINT64 = 4, GSD_INT8 = 5, GSD_FLOAT = 9 };

typedef struct {
  uint64_t frame, n;
  int64_t location;
  uint32_t m;
  uint16_t id;
  uint8_t type, flags;
} gsd_entry;

typedef struct {
  FILE *f;
  gsd_entry *index;
  size_t count, cap;
  uint64_t frame;
  int error;
  char application[64];
} gsd_writer;

/* Creates path and writes the header and the namelist; application is
 * recorded in the header. Returns 0, or -1 (errno set) on failure. */
int gsd_open(gsd_writer *w, const char *path, const char *application);

/* Appends the chunk name (one of the HOOMD names of gsd_write.c) of the
 * current frame: n rows of m values of the given type. Returns 0 or -1. */
int gsd_chunk(gsd_writer *w, const char *name, int type, uint64_t n, uint32_t m,
              const void *data);

/* Closes the current frame: later chunks belong to the next one. */
void gsd_end_frame(gsd_writer *w);

/* Writes the index, rewrites the header, closes the file. Returns 0, or -1
 * if any write failed since gsd_open. */
int gsd_close(gsd_writer *w);

#endif
