/* Minimal GSD 2.0 writer: gsd_write.h. */
#include "gsd_write.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define GSD_MAGIC 0x65DF65DF65DF65DFULL
#define GSD_VERSION ((2u << 16) | 0u)
#define HOOMD_SCHEMA_VERSION ((1u << 16) | 4u)
#define GSD_NAME_SIZE 64

/* Chunk names of the HOOMD schema that the demonstration programs write;
 * the names of their logged scalars (gsd_open) follow. The id of a chunk
 * is its position in the namelist of the file. */
static const char *const particle_names[] = {
    "configuration/step", "configuration/box", "particles/N",         "particles/types",
    "particles/typeid",   "particles/position", "particles/orientation",
    "particles/type_shapes"};
enum { N_PARTICLE_NAMES = sizeof particle_names / sizeof particle_names[0] };

static size_t type_size(int type) {
  switch (type) {
    case GSD_UINT8:
    case GSD_INT8: return 1;
    case GSD_UINT32:
    case GSD_FLOAT: return 4;
    case GSD_UINT64:
    case GSD_DOUBLE: return 8;
    default: return 0;
  }
}

/* Header: magic, index location, index entries, namelist location,
 * namelist entries (uint64 each), schema version, GSD version (uint32),
 * application[64], schema[64], reserved[80]: 256 bytes. */
static int write_header(gsd_writer *w, uint64_t index_location, uint64_t index_entries) {
  unsigned char h[256];
  memset(h, 0, sizeof h);
  uint64_t const u64[5] = {GSD_MAGIC, index_location, index_entries, 256, GSD_MAX_NAMES};
  uint32_t const u32[2] = {HOOMD_SCHEMA_VERSION, GSD_VERSION};
  memcpy(h, u64, sizeof u64);
  memcpy(h + 40, u32, sizeof u32);
  memcpy(h + 48, w->application, sizeof w->application);
  strncpy((char *)h + 112, "hoomd", 63);
  if (fseek(w->f, 0, SEEK_SET) != 0 || fwrite(h, 1, sizeof h, w->f) != sizeof h) return -1;
  return 0;
}

int gsd_open(gsd_writer *w, const char *path, const char *application,
             const char *const *logged_names, int n_logged) {
  memset(w, 0, sizeof *w);
  if (n_logged < 0 || N_PARTICLE_NAMES + n_logged > GSD_MAX_NAMES) {
    errno = EINVAL;
    return -1;
  }
  for (int k = 0; k < N_PARTICLE_NAMES; k++) w->names[w->n_names++] = particle_names[k];
  for (int k = 0; k < n_logged; k++) w->names[w->n_names++] = logged_names[k];
  /* Namelist (version 2.0): the names back to back, each ended by a NUL,
   * in a zero-filled block of GSD_MAX_NAMES * 64 bytes. */
  char names[GSD_MAX_NAMES * GSD_NAME_SIZE];
  memset(names, 0, sizeof names);
  size_t at = 0;
  for (int k = 0; k < w->n_names; k++) {
    size_t const len = strlen(w->names[k]);
    if (at + len + 1 > sizeof names) {
      errno = EINVAL;
      return -1;
    }
    memcpy(names + at, w->names[k], len);
    at += len + 1;
  }
  w->f = fopen(path, "wb");
  if (!w->f) return -1;
  strncpy(w->application, application ? application : "", sizeof w->application - 1);
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
  for (int k = 0; k < w->n_names; k++)
    if (!strcmp(name, w->names[k])) id = k;
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

int gsd_write_frame(gsd_writer *w, const gsd_frame *frame, float *buffer) {
  size_t const n = frame->n;
  double const L = frame->box;
  int rc = gsd_chunk(w, "configuration/step", GSD_UINT64, 1, 1, &frame->step);
  if (w->frame == 0) {
    float const box[6] = {(float)L, (float)L, (float)L, 0.0f, 0.0f, 0.0f};
    const double *s = frame->semi_axes;
    char shape[160];
    int const len = snprintf(shape, sizeof shape,
                             "{\"type\": \"Ellipsoid\", \"a\": %.9g, \"b\": %.9g, \"c\": %.9g}",
                             s[0], s[1], s[2]);
    rc |= gsd_chunk(w, "configuration/box", GSD_FLOAT, 6, 1, box);
    rc |= gsd_chunk(w, "particles/N", GSD_UINT32, 1, 1, &frame->n);
    rc |= gsd_chunk(w, "particles/types", GSD_INT8, 1, 2, "E");
    rc |= gsd_chunk(w, "particles/type_shapes", GSD_INT8, 1, (uint32_t)len + 1, shape);
    uint32_t *typeid = (uint32_t *)buffer; /* all 0 */
    memset(typeid, 0, n * sizeof *typeid);
    rc |= gsd_chunk(w, "particles/typeid", GSD_UINT32, n, 1, typeid);
  }
  float const half = (float)(0.5 * L);
  for (size_t i = 0; i < 3 * n; ++i) {
    double const x = frame->position[i];
    float p = (float)(x - L * floor(x / L) - 0.5 * L);
    if (p >= half) p = -half;
    buffer[i] = p;
  }
  rc |= gsd_chunk(w, "particles/position", GSD_FLOAT, n, 3, buffer);
  for (size_t i = 0; i < 4 * n; ++i) buffer[i] = (float)frame->orientation[i];
  rc |= gsd_chunk(w, "particles/orientation", GSD_FLOAT, n, 4, buffer);
  for (int k = 0; k < frame->n_logged; ++k)
    rc |= gsd_chunk(w, frame->logged_name[k], GSD_DOUBLE, 1, 1, frame->logged_value + k);
  gsd_end_frame(w);
  return rc ? -1 : 0;
}

void gsd_quaternion_of_rotation(const double a[9], double quat[4]) {
  double const a00 = a[0], a01 = a[1], a02 = a[2], a10 = a[3], a11 = a[4], a12 = a[5],
               a20 = a[6], a21 = a[7], a22 = a[8], tr = a00 + a11 + a22;
  double q[4];
  if (tr >= a00 && tr >= a11 && tr >= a22) {
    double const s = 2.0 * sqrt(1.0 + tr);
    q[0] = 0.25 * s, q[1] = (a21 - a12) / s, q[2] = (a02 - a20) / s, q[3] = (a10 - a01) / s;
  } else if (a00 >= a11 && a00 >= a22) {
    double const s = 2.0 * sqrt(1.0 + 2.0 * a00 - tr);
    q[0] = (a21 - a12) / s, q[1] = 0.25 * s, q[2] = (a01 + a10) / s, q[3] = (a02 + a20) / s;
  } else if (a11 >= a22) {
    double const s = 2.0 * sqrt(1.0 + 2.0 * a11 - tr);
    q[0] = (a02 - a20) / s, q[1] = (a01 + a10) / s, q[2] = 0.25 * s, q[3] = (a12 + a21) / s;
  } else {
    double const s = 2.0 * sqrt(1.0 + 2.0 * a22 - tr);
    q[0] = (a10 - a01) / s, q[1] = (a02 + a20) / s, q[2] = (a12 + a21) / s, q[3] = 0.25 * s;
  }
  double const norm = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  double const sign = q[0] < 0.0 ? -1.0 : 1.0;
  for (int k = 0; k < 4; ++k) quat[k] = sign * q[k] / norm;
}
