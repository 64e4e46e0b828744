/* Minimal GSD 2.0 writer: gsd_write.h. */
#include "gsd_write.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#define GSD_MAGIC 0x65DF65DF65DF65DFULL
#define GSD_VERSION ((2u << 16) | 0u)
#define HOOMD_SCHEMA_VERSION ((1u << 16) | 4u)
#define GSD_NAME_SIZE 64
#define GSD_NAMES 16

/* Chunk names of the HOOMD schema that the demonstration programs write;
 * the id of a chunk is its position here. */
static const char *const gsd_names[] = {
    "configuration/step", "configuration/box", "particles/N",         "particles/types",
    "particles/typeid",   "particles/position", "particles/orientation",
    "particles/type_shapes"};
enum { N_NAMES = sizeof gsd_names / sizeof gsd_names[0] };

static size_t type_size(int type) {
  switch (type) {
    case GSD_UINT8:
    case GSD_INT8: return 1;
    case GSD_UINT32:
    case GSD_FLOAT: return 4;
    case GSD_UINT64: return 8;
    default: return 0;
  }
}

/* Header: magic, index location, index entries, namelist location,
 * namelist entries (uint64 each), schema version, GSD version (uint32),
 * application[64], schema[64], reserved[80]: 256 bytes. */
static int write_header(gsd_writer *w, uint64_t index_location, uint64_t index_entries) {
  unsigned char h[256];
  memset(h, 0, sizeof h);
  uint64_t const u64[5] = {GSD_MAGIC, index_location, index_entries, 256, GSD_NAMES};
  uint32_t const u32[2] = {HOOMD_SCHEMA_VERSION, GSD_VERSION};
  memcpy(h, u64, sizeof u64);
  memcpy(h + 40, u32, sizeof u32);
  memcpy(h + 48, w->application, sizeof w->application);
  strncpy((char *)h + 112, "hoomd", 63);
  if (fseek(w->f, 0, SEEK_SET) != 0 || fwrite(h, 1, sizeof h, w->f) != sizeof h) return -1;
  return 0;
}

int gsd_open(gsd_writer *w, const char *path, const char *application) {
  memset(w, 0, sizeof *w);
  w->f = fopen(path, "wb");
  if (!w->f) return -1;
  strncpy(w->application, application ? application : "", sizeof w->application - 1);
  /* Namelist (version 2.0): the names back to back, each ended by a NUL,
   * in a zero-filled block of GSD_NAMES * 64 bytes. */
  char names[GSD_NAMES * GSD_NAME_SIZE];
  memset(names, 0, sizeof names);
  size_t at = 0;
  for (int k = 0; k < N_NAMES; k++) {
    size_t const len = strlen(gsd_names[k]);
    memcpy(names + at, gsd_names[k], len);
    at += len + 1;
  }
  if (write_header(w, 0, 0) != 0 ||
      fwrite(names, 1, sizeof names, w->f) != sizeof names) {
    fclose(w->f);
    w->f = NULL;
    return -1;
  }
  return 0;
}

int gsd_chunk(gsd_writer *w, const char *name, int type, uint64_t n, uint32_t m,
              const void *data) {
  int id = -1;
  for (int k = 0; k < N_NAMES; k++)
    if (!strcmp(name, gsd_names[k])) id = k;
  size_t const size = type_size(type);
  if (!w->f || id < 0 || size == 0 || m == 0) {
    w->error = 1;
    errno = EINVAL;
    return -1;
  }
  if (w->count == w->cap) {
    size_t const cap = w->cap ? 2 * w->cap : 16;
    gsd_entry *p = realloc(w->index, cap * sizeof *p);
    if (!p) {
      w->error = 1;
      return -1;
    }
    w->index = p, w->cap = cap;
  }
  if (fseek(w->f, 0, SEEK_END) != 0) {
    w->error = 1;
    return -1;
  }
  long const location = ftell(w->f);
  size_t const bytes = (size_t)n * m * size;
  if (location < 0 || fwrite(data, 1, bytes, w->f) != bytes) {
    w->error = 1;
    return -1;
  }
  gsd_entry const e = {w->frame, n, location, m, (uint16_t)id, (uint8_t)type, 0};
  w->index[w->count++] = e;
  return 0;
}

void gsd_end_frame(gsd_writer *w) { w->frame++; }

static int by_frame_then_id(const void *a, const void *b) {
  const gsd_entry *x = a, *y = b;
  if (x->frame != y->frame) return x->frame < y->frame ? -1 : 1;
  return (x->id > y->id) - (x->id < y->id);
}

/* Index entry: frame, N (uint64), location (int64), M (uint32), id
 * (uint16), type, flags (uint8): 32 bytes, no padding. */
int gsd_close(gsd_writer *w) {
  if (!w->f) return -1;
  int rc = w->error ? -1 : 0;
  qsort(w->index, w->count, sizeof *w->index, by_frame_then_id);
  long location = -1;
  if (fseek(w->f, 0, SEEK_END) == 0) location = ftell(w->f);
  unsigned char zero[32] = {0};
  if (location < 0) rc = -1;
  for (size_t k = 0; k < w->count && rc == 0; k++) {
    unsigned char b[32];
    memcpy(b, &w->index[k].frame, 8);
    memcpy(b + 8, &w->index[k].n, 8);
    memcpy(b + 16, &w->index[k].location, 8);
    memcpy(b + 24, &w->index[k].m, 4);
    memcpy(b + 28, &w->index[k].id, 2);
    b[30] = w->index[k].type, b[31] = w->index[k].flags;
    if (fwrite(b, 1, 32, w->f) != 32) rc = -1;
  }
  if (rc == 0 && fwrite(zero, 1, 32, w->f) != 32) rc = -1;
  if (rc == 0) rc = write_header(w, (uint64_t)location, w->count + 1);
  if (fclose(w->f) != 0) rc = -1;
  w->f = NULL;
  free(w->index);
  w->index = NULL;
  return rc;
}
