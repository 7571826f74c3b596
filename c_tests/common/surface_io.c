#define _POSIX_C_SOURCE 200809L /* getline, strcasecmp */
#include "surface_io.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

void surface_file_free(SurfaceFile *f) {
  if (!f) return;
  free(f->xyz);
  free(f->corners);
  free(f->offsets);
  free(f->regions);
  free(f->holes);
  memset(f, 0, sizeof *f);
}

/* ---- A line reader that skips blank lines and '#' comments ------------------------------------ */

typedef struct Reader {
  FILE *file;
  const char *path;
  char *line;
  size_t capacity;
  size_t number; /* of the current line, from 1 */
  char *cursor;  /* next token in the current line */
  char *error;
  size_t error_size;
} Reader;

static int fail(Reader *r, const char *format, ...) {
  char what[200];
  va_list args;
  va_start(args, format);
  vsnprintf(what, sizeof what, format, args);
  va_end(args);
  snprintf(r->error, r->error_size, "%s:%zu: %s", r->path, r->number, what);
  return 0;
}

/* Moves to the next line with content; 0 at the end of the file. */
static int next_line(Reader *r) {
  for (;;) {
    ssize_t len = getline(&r->line, &r->capacity, r->file);
    if (len < 0) return 0;
    r->number++;
    char *hash = strchr(r->line, '#');
    if (hash) *hash = '\0';
    char *p = r->line;
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') p++;
    if (*p) {
      r->cursor = p;
      return 1;
    }
  }
}

/* The next token of the current line as a double / an unsigned integer; 0 when none. */
static int token_double(Reader *r, double *x) {
  char *end;
  errno = 0;
  double v = strtod(r->cursor, &end);
  if (end == r->cursor || errno == ERANGE) return 0;
  r->cursor = end;
  *x = v;
  return 1;
}

static int token_size(Reader *r, size_t *x) {
  char *end;
  while (*r->cursor == ' ' || *r->cursor == '\t') r->cursor++;
  if (*r->cursor == '-') return 0;
  errno = 0;
  unsigned long long v = strtoull(r->cursor, &end, 10);
  if (end == r->cursor || errno == ERANGE || v > UINT32_MAX) return 0;
  r->cursor = end;
  *x = (size_t)v;
  return 1;
}

/* Appends polygon corners, growing the arrays. */
typedef struct Polygons {
  uint32_t *corners;
  size_t corner_count, corner_capacity;
  size_t *offsets;
  size_t count;
} Polygons;

static int polygons_init(Polygons *p, size_t count) {
  memset(p, 0, sizeof *p);
  p->offsets = malloc((count + 1) * sizeof *p->offsets);
  p->corner_capacity = 3 * count + 3;
  p->corners = malloc(p->corner_capacity * sizeof *p->corners);
  if (!p->offsets || !p->corners) return 0;
  p->offsets[0] = 0;
  return 1;
}

static int polygons_push(Polygons *p, uint32_t v) {
  if (p->corner_count == p->corner_capacity) {
    size_t capacity = 2 * p->corner_capacity;
    uint32_t *c = realloc(p->corners, capacity * sizeof *c);
    if (!c) return 0;
    p->corners = c;
    p->corner_capacity = capacity;
  }
  p->corners[p->corner_count++] = v;
  return 1;
}

/* Reads `count` polygons, one a line: "<k> v1 .. vk [anything]"; indices minus `first`. */
static int read_polygons(Reader *r, size_t count, size_t n, size_t first, Polygons *p) {
  if (!polygons_init(p, count)) return fail(r, "out of memory");
  for (size_t f = 0; f < count; f++) {
    size_t k, v;
    if (!next_line(r)) return fail(r, "polygon %zu of %zu missing", f, count);
    if (!token_size(r, &k) || k < 3) return fail(r, "a polygon needs 3 or more corners");
    for (size_t i = 0; i < k; i++) {
      if (!token_size(r, &v)) return fail(r, "polygon %zu: corner %zu missing", f, i);
      if (v < first || v - first >= n) return fail(r, "polygon %zu: vertex %zu out of range", f, v);
      if (!polygons_push(p, (uint32_t)(v - first))) return fail(r, "out of memory");
    }
    p->offsets[++p->count] = p->corner_count;
  }
  return 1;
}

static void take_polygons(SurfaceFile *out, Polygons *p) {
  out->corners = p->corners;
  out->offsets = p->offsets;
  out->polygon_count = p->count;
  out->all_triangles = 1;
  for (size_t f = 0; f < p->count; f++)
    if (p->offsets[f + 1] - p->offsets[f] != 3) out->all_triangles = 0;
  memset(p, 0, sizeof *p);
}

/* ---- OFF ------------------------------------------------------------------------------------------ */

static int read_off(Reader *r, SurfaceFile *out) {
  size_t n, count, edges;
  if (!next_line(r) || strncmp(r->cursor, "OFF", 3) != 0) return fail(r, "no OFF header");
  r->cursor += 3;
  while (*r->cursor == ' ' || *r->cursor == '\t' || *r->cursor == '\r' || *r->cursor == '\n') r->cursor++;
  if (!*r->cursor && !next_line(r)) return fail(r, "no counts");
  if (!token_size(r, &n) || !token_size(r, &count) || !token_size(r, &edges))
    return fail(r, "expected <vertices> <faces> <edges>");
  out->xyz = malloc(3 * (n ? n : 1) * sizeof *out->xyz);
  if (!out->xyz) return fail(r, "out of memory");
  for (size_t i = 0; i < n; i++) {
    if (!next_line(r)) return fail(r, "vertex %zu of %zu missing", i, n);
    for (int k = 0; k < 3; k++)
      if (!token_double(r, &out->xyz[3 * i + (size_t)k])) return fail(r, "vertex %zu: 3 coordinates expected", i);
  }
  out->n = n;
  Polygons p;
  if (!read_polygons(r, count, n, 0, &p)) {
    free(p.corners);
    free(p.offsets);
    return 0;
  }
  take_polygons(out, &p);
  return 1;
}

/* ---- .smesh ------------------------------------------------------------------------------------- */

static int read_smesh(Reader *r, SurfaceFile *out) {
  size_t n, dimension, attributes, markers;
  if (!next_line(r) || !token_size(r, &n) || !token_size(r, &dimension) || !token_size(r, &attributes) ||
      !token_size(r, &markers))
    return fail(r, "expected <points> 3 <attributes> <markers>");
  if (dimension != 3) return fail(r, "dimension %zu, not 3", dimension);
  if (n == 0) return fail(r, "points in a separate .node file are not supported");
  out->xyz = malloc(3 * n * sizeof *out->xyz);
  if (!out->xyz) return fail(r, "out of memory");
  size_t first = 0;
  for (size_t i = 0; i < n; i++) {
    size_t index;
    if (!next_line(r) || !token_size(r, &index)) return fail(r, "point %zu of %zu missing", i, n);
    if (i == 0) first = index; /* TetGen numbers from the first point's index (0 or 1) */
    if (index != first + i) return fail(r, "point %zu numbered %zu", i, index);
    for (int k = 0; k < 3; k++)
      if (!token_double(r, &out->xyz[3 * i + (size_t)k])) return fail(r, "point %zu: 3 coordinates expected", i);
  }
  out->n = n;
  size_t count;
  if (!next_line(r) || !token_size(r, &count) || !token_size(r, &markers))
    return fail(r, "expected <facets> <markers>");
  Polygons p;
  if (!read_polygons(r, count, n, first, &p)) {
    free(p.corners);
    free(p.offsets);
    return 0;
  }
  take_polygons(out, &p);
  /* Holes, then regions (both optional at the end of the file). */
  size_t holes = 0, regions = 0;
  if (next_line(r) && !token_size(r, &holes)) return fail(r, "expected <holes>");
  out->holes = malloc(3 * (holes ? holes : 1) * sizeof *out->holes);
  if (!out->holes) return fail(r, "out of memory");
  for (size_t h = 0; h < holes; h++) {
    size_t index;
    if (!next_line(r) || !token_size(r, &index)) return fail(r, "hole %zu missing", h);
    for (int k = 0; k < 3; k++)
      if (!token_double(r, &out->holes[3 * h + (size_t)k])) return fail(r, "hole %zu: 3 coordinates expected", h);
  }
  out->n_holes = holes;
  if (next_line(r) && !token_size(r, &regions)) return fail(r, "expected <regions>");
  out->regions = malloc(5 * (regions ? regions : 1) * sizeof *out->regions);
  if (!out->regions) return fail(r, "out of memory");
  for (size_t g = 0; g < regions; g++) {
    size_t index;
    if (!next_line(r) || !token_size(r, &index)) return fail(r, "region %zu missing", g);
    for (int k = 0; k < 5; k++)
      if (!token_double(r, &out->regions[5 * g + (size_t)k]))
        return fail(r, "region %zu: x y z label max-volume expected", g);
  }
  out->n_regions = regions;
  return 1;
}

int surface_file_read(const char *path, SurfaceFile *out, char *error, size_t error_size) {
  memset(out, 0, sizeof *out);
  const char *dot = strrchr(path, '.');
  int off = dot && strcasecmp(dot, ".off") == 0, smesh = dot && strcasecmp(dot, ".smesh") == 0;
  if (!off && !smesh) {
    snprintf(error, error_size, "%s: not .off or .smesh", path);
    return 0;
  }
  Reader r = {0};
  r.path = path;
  r.error = error;
  r.error_size = error_size;
  r.file = fopen(path, "r");
  if (!r.file) {
    snprintf(error, error_size, "%s: %s", path, strerror(errno));
    return 0;
  }
  int ok = off ? read_off(&r, out) : read_smesh(&r, out);
  free(r.line);
  fclose(r.file);
  if (!ok) surface_file_free(out);
  return ok;
}
