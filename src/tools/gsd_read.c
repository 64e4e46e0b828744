/* Minimal GSD 2.x reader: gsd_read.h. */
#include "gsd_read.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gsd_write.h"

typedef struct {
  FILE *f;
  uint64_t length; /* of the file, bytes */
  char **names;    /* the namelist: a chunk's id is its position */
  uint64_t n_names;
  char *name_block;
  gsd_entry *index;
  uint64_t count;
  char *message;
  size_t size;
} reader;

static int fail(reader *r, const char *format, ...) {
  if (r->message && r->size > 0) {
    va_list ap;
    va_start(ap, format);
    vsnprintf(r->message, r->size, format, ap);
    va_end(ap);
  }
  return -1;
}

static int read_at(reader *r, uint64_t location, uint64_t bytes, void *out) {
  if (location > r->length || bytes > r->length - location) return -1;
  if (fseek(r->f, (long)location, SEEK_SET) != 0) return -1;
  return fread(out, 1, (size_t)bytes, r->f) == bytes ? 0 : -1;
}

static size_t size_of(int type) {
  switch (type) {
    case 1: case 5: case 11: return 1; /* uint8, int8, char */
    case 2: case 6: return 2;
    case 3: case 7: case 9: return 4;  /* uint32, int32, float */
    case 4: case 8: case 10: return 8; /* uint64, int64, double */
    default: return 0;
  }
}

/* Header, namelist and index (gsd_write.h). */
static int open_file(reader *r, const char *path) {
  r->f = fopen(path, "rb");
  if (!r->f) return fail(r, "cannot open the file");
  long end = -1;
  if (fseek(r->f, 0, SEEK_END) == 0) end = ftell(r->f);
  if (end < 0) return fail(r, "cannot read the file");
  r->length = (uint64_t)end;
  unsigned char h[256];
  if (read_at(r, 0, sizeof h, h) != 0) return fail(r, "not a GSD file (shorter than its header)");
  uint64_t u64[5];
  uint32_t u32[2];
  memcpy(u64, h, sizeof u64);
  memcpy(u32, h + 40, sizeof u32);
  if (u64[0] != 0x65DF65DF65DF65DFULL) return fail(r, "not a GSD file (magic number)");
  if (u32[1] >> 16 != 2) return fail(r, "GSD file layer version %u.%u (2.x read)", u32[1] >> 16, u32[1] & 0xffffu);
  if (strncmp((const char *)h + 112, "hoomd", 64) != 0) return fail(r, "schema not \"hoomd\"");
  uint64_t const index_location = u64[1], index_entries = u64[2];
  uint64_t const names_location = u64[3], names_entries = u64[4];
  if (names_entries > r->length / 64 || index_entries > r->length / 32)
    return fail(r, "corrupt header (namelist or index larger than the file)");
  uint64_t const name_bytes = names_entries * 64;
  r->name_block = calloc((size_t)name_bytes + 1, 1);
  r->names = calloc((size_t)name_bytes + 1, sizeof(char *));
  r->index = calloc((size_t)index_entries + 1, sizeof(gsd_entry));
  if (!r->name_block || !r->names || !r->index) return fail(r, "out of memory");
  if (read_at(r, names_location, name_bytes, r->name_block) != 0)
    return fail(r, "corrupt namelist (outside the file)");
  for (uint64_t at = 0; at < name_bytes && r->name_block[at]; at += strlen(r->name_block + at) + 1)
    r->names[r->n_names++] = r->name_block + at;
  for (uint64_t k = 0; k < index_entries; k++) {
    unsigned char b[32];
    if (read_at(r, index_location + 32 * k, 32, b) != 0) return fail(r, "corrupt index (outside the file)");
    gsd_entry e;
    memcpy(&e.frame, b, 8);
    memcpy(&e.n, b + 8, 8);
    memcpy(&e.location, b + 16, 8);
    memcpy(&e.m, b + 24, 4);
    memcpy(&e.id, b + 28, 2);
    e.type = b[30], e.flags = b[31];
    if (e.location == 0) break;
    size_t const sz = size_of(e.type);
    if (e.id >= r->n_names || sz == 0 || e.location < 0 || e.m == 0 || (e.n != 0 && (uint64_t)e.m > UINT64_MAX / e.n) ||
        e.n * e.m > r->length / sz || (uint64_t)e.location > r->length - e.n * e.m * sz)
      return fail(r, "corrupt index entry %llu", (unsigned long long)k);
    r->index[r->count++] = e;
  }
  return 0;
}

/* The entry of chunk name in frame, else in frame 0, else NULL. */
static const gsd_entry *find(const reader *r, uint64_t frame, const char *name) {
  const gsd_entry *zero = NULL;
  for (uint64_t k = 0; k < r->count; k++) {
    const gsd_entry *e = &r->index[k];
    if (strcmp(r->names[e->id], name) != 0) continue;
    if (e->frame == frame) return e;
    if (e->frame == 0) zero = e;
  }
  return zero;
}

/* Chunk e as n x m doubles (from a float or double chunk), checked
 * against the expected shape (n rows, m columns). */
static int read_reals(reader *r, const gsd_entry *e, uint64_t n, uint32_t m, double *out, const char *name) {
  if (e->n != n || e->m != m || (e->type != GSD_FLOAT && e->type != GSD_DOUBLE))
    return fail(r, "%s: %llu x %u values of type %u, expected %llu x %u float or double", name,
                (unsigned long long)e->n, e->m, e->type, (unsigned long long)n, m);
  size_t const count = (size_t)(n * m);
  if (e->type == GSD_DOUBLE) return read_at(r, (uint64_t)e->location, count * 8, out) ? fail(r, "%s: read error", name) : 0;
  float *tmp = malloc(count * sizeof(float) + 1);
  if (!tmp) return fail(r, "%s: out of memory", name);
  int const rc = read_at(r, (uint64_t)e->location, count * 4, tmp);
  for (size_t k = 0; k < count && rc == 0; k++) out[k] = tmp[k];
  free(tmp);
  return rc ? fail(r, "%s: read error", name) : 0;
}

/* The value of "key" in a flat JSON object: a string copied to str (size
 * bytes) or a number to *num. Returns 0, or -1 when absent or malformed. */
static int json_value(const char *json, const char *key, char *str, size_t size, double *num) {
  char quoted[32];
  snprintf(quoted, sizeof quoted, "\"%s\"", key);
  const char *p = strstr(json, quoted);
  if (!p) return -1;
  p += strlen(quoted);
  while (*p == ' ') p++;
  if (*p++ != ':') return -1;
  while (*p == ' ') p++;
  if (str) {
    if (*p++ != '"') return -1;
    const char *q = strchr(p, '"');
    if (!q || (size_t)(q - p) >= size) return -1;
    memcpy(str, p, (size_t)(q - p));
    str[q - p] = '\0';
    return 0;
  }
  char *end;
  *num = strtod(p, &end);
  return end == p ? -1 : 0;
}

static int read_frame(reader *r, long long frame, gsd_hoomd_frame *out) {
  uint64_t frames = 0;
  for (uint64_t k = 0; k < r->count; k++)
    if (r->index[k].frame + 1 > frames) frames = r->index[k].frame + 1;
  out->n_frames = frames;
  long long const f = frame < 0 ? (long long)frames + frame : frame;
  if (f < 0 || (uint64_t)f >= frames) return fail(r, "frame %lld: the file has %llu frames", frame, (unsigned long long)frames);
  const gsd_entry *e;
  if ((e = find(r, (uint64_t)f, "configuration/step"))) {
    if (e->type != GSD_UINT64 || e->n * e->m != 1 || read_at(r, (uint64_t)e->location, 8, &out->step))
      return fail(r, "configuration/step: not one uint64");
  }
  double const box_default[6] = {1, 1, 1, 0, 0, 0};
  memcpy(out->box, box_default, sizeof box_default);
  if ((e = find(r, (uint64_t)f, "configuration/box")) && read_reals(r, e, 6, 1, out->box, "configuration/box")) return -1;
  if ((e = find(r, (uint64_t)f, "particles/N"))) {
    if (e->type != GSD_UINT32 || e->n * e->m != 1 || read_at(r, (uint64_t)e->location, 4, &out->n))
      return fail(r, "particles/N: not one uint32");
  }
  if (out->n > 100000000u) return fail(r, "particles/N: %u, more than 10^8", out->n);
  size_t const n = out->n;
  out->position = calloc(3 * n + 1, sizeof(double));
  out->orientation = calloc(4 * n + 1, sizeof(double));
  out->typeid = calloc(n + 1, sizeof(uint32_t));
  if (!out->position || !out->orientation || !out->typeid) return fail(r, "out of memory for %zu particles", n);
  for (size_t i = 0; i < n; i++) out->orientation[4 * i] = 1.0;
  if ((e = find(r, (uint64_t)f, "particles/position")) && read_reals(r, e, n, 3, out->position, "particles/position"))
    return -1;
  if ((e = find(r, (uint64_t)f, "particles/orientation")) &&
      read_reals(r, e, n, 4, out->orientation, "particles/orientation"))
    return -1;
  out->n_types = 1;
  if ((e = find(r, (uint64_t)f, "particles/types"))) {
    if (e->n == 0 || e->n > UINT32_MAX) return fail(r, "particles/types: %llu types", (unsigned long long)e->n);
    out->n_types = (uint32_t)e->n;
  }
  if ((e = find(r, (uint64_t)f, "particles/typeid"))) {
    if (e->type != GSD_UINT32 || e->n != n || e->m != 1 || read_at(r, (uint64_t)e->location, 4 * n, out->typeid))
      return fail(r, "particles/typeid: not %zu uint32", n);
  }
  for (size_t i = 0; i < n; i++)
    if (out->typeid[i] >= out->n_types)
      return fail(r, "particles/typeid: particle %zu of type %u, %u types", i, out->typeid[i], out->n_types);
  out->semi_axes = malloc(3 * (size_t)out->n_types * sizeof(double));
  if (!out->semi_axes) return fail(r, "out of memory");
  for (size_t k = 0; k < 3 * (size_t)out->n_types; k++) out->semi_axes[k] = NAN;
  if ((e = find(r, (uint64_t)f, "particles/type_shapes"))) {
    if (size_of(e->type) != 1 || e->n != out->n_types)
      return fail(r, "particles/type_shapes: %llu rows of type %u for %u types", (unsigned long long)e->n, e->type,
                  out->n_types);
    char *text = malloc((size_t)(e->n * e->m) + 1);
    if (!text) return fail(r, "out of memory");
    if (read_at(r, (uint64_t)e->location, e->n * e->m, text)) {
      free(text);
      return fail(r, "particles/type_shapes: read error");
    }
    for (uint32_t t = 0; t < out->n_types; t++) {
      char row[1024], kind[32];
      size_t const len = e->m < sizeof row ? e->m : sizeof row - 1;
      memcpy(row, text + (size_t)t * e->m, len);
      row[len] = '\0';
      double abc[3];
      if (json_value(row, "type", kind, sizeof kind, NULL) == 0 && !strcmp(kind, "Ellipsoid") &&
          json_value(row, "a", NULL, 0, abc) == 0 && json_value(row, "b", NULL, 0, abc + 1) == 0 &&
          json_value(row, "c", NULL, 0, abc + 2) == 0)
        memcpy(out->semi_axes + 3 * t, abc, sizeof abc);
    }
    free(text);
  }
  return 0;
}

int gsd_read_hoomd_frame(const char *path, long long frame, gsd_hoomd_frame *out, char *message,
                         size_t size) {
  memset(out, 0, sizeof *out);
  reader r = {0};
  r.message = message, r.size = size;
  int rc = open_file(&r, path);
  if (rc == 0) rc = read_frame(&r, frame, out);
  if (r.f) fclose(r.f);
  free(r.names), free(r.name_block), free(r.index);
  if (rc != 0) gsd_hoomd_frame_free(out);
  return rc;
}

void gsd_hoomd_frame_free(gsd_hoomd_frame *frame) {
  free(frame->position), free(frame->orientation), free(frame->typeid), free(frame->semi_axes);
  memset(frame, 0, sizeof *frame);
}
