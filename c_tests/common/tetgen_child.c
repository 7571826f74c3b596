#define _DEFAULT_SOURCE /* fork, waitpid, alarm */
#include "tetgen_child.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

static int write_all(int fd, const void *data, size_t size) {
  const char *p = data;
  while (size) {
    ssize_t w = write(fd, p, size);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return 0;
    p += w;
    size -= (size_t)w;
  }
  return 1;
}

static int read_all(int fd, void *data, size_t size) {
  char *p = data;
  while (size) {
    ssize_t r = read(fd, p, size);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return 0;
    p += r;
    size -= (size_t)r;
  }
  return 1;
}

/* What goes through the pipe first; the arrays follow on success. */
typedef struct Header {
  int rc;
  size_t vertex_count, steiner_count, boundary_steiner, tet_count; /* or culprit count in tet_count */
  double seconds;
  char message[256];
} Header;

/* The work of one child: fills the header, writes it and the arrays to fd; returns 1 on success. */
typedef int (*ChildWork)(int fd, const void *job);
/* The parent's side: reads the arrays after the header; returns 1 on success. */
typedef int (*ParentRead)(int fd, const Header *h, void *result);

/* Runs `work` in a child process stopped after time_limit seconds (0: none); 0 on success, -1
 * with `error` set otherwise. */
static int in_child(ChildWork work, const void *job, ParentRead collect, void *result, void (*discard)(void *),
                    unsigned time_limit, Header *h, char *error, size_t error_size) {
  int fd[2];
  if (pipe(fd) != 0) {
    snprintf(error, error_size, "pipe: %s", strerror(errno));
    return -1;
  }
  fflush(stdout);
  fflush(stderr);
  pid_t pid = fork();
  if (pid < 0) {
    close(fd[0]);
    close(fd[1]);
    snprintf(error, error_size, "fork: %s", strerror(errno));
    return -1;
  }
  if (pid == 0) {
    close(fd[0]);
    if (time_limit) alarm(time_limit); /* SIGALRM ends the child */
    int ok = work(fd[1], job);
    close(fd[1]);
    _exit(ok ? 0 : 1);
  }
  close(fd[1]);
  memset(h, 0, sizeof *h);
  int got = read_all(fd[0], h, sizeof *h);
  int rc = -1;
  if (got && h->rc == 0) {
    if (collect(fd[0], h, result))
      rc = 0;
    else
      snprintf(error, error_size, "reading TetGen's result from the child failed");
  }
  close(fd[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    if (rc == 0) discard(result);
    if (WTERMSIG(status) == SIGALRM)
      snprintf(error, error_size, "TetGen did not finish within %u s (stopped)", time_limit);
    else
      snprintf(error, error_size, "TetGen aborted (signal %d%s)", WTERMSIG(status),
               WTERMSIG(status) == SIGABRT ? ", a failed assert()" : WTERMSIG(status) == SIGSEGV ? ", a crash" : "");
    return -1;
  }
  if (rc != 0 && got && h->rc != 0) snprintf(error, error_size, "%s", h->message);
  if (rc != 0 && !got)
    snprintf(error, error_size, "TetGen's child ended without a result (exit status %d; under the sanitizers a crash ends it so)",
             WIFEXITED(status) ? WEXITSTATUS(status) : -1);
  return rc;
}

/* ---- Tetrahedralization ------------------------------------------------------------------------ */

typedef struct MeshJob {
  const double *xyz;
  size_t n;
  const uint32_t *corners;
  const size_t *offsets;
  size_t m;
  const double *regions;
  size_t n_regions;
  const double *holes;
  size_t n_holes;
  const char *switches;
} MeshJob;

static int mesh_work(int fd, const void *job) {
  const MeshJob *j = job;
  RefSurfaceMesh mesh;
  RefTiming t = {0};
  memset(&mesh, 0, sizeof mesh);
  Header h;
  memset(&h, 0, sizeof h);
  h.rc = j->offsets ? ref_tetgen_polygons(j->xyz, j->n, j->corners, j->offsets, j->m, j->regions, j->n_regions, j->holes,
                                          j->n_holes, j->switches, &mesh, &t)
                    : ref_tetgen_surface(j->xyz, j->n, j->corners, j->m, j->regions, j->n_regions, j->holes, j->n_holes,
                                         j->switches, &mesh, &t);
  if (h.rc != 0) snprintf(h.message, sizeof h.message, "%s", ref_last_error());
  h.vertex_count = mesh.vertex_count, h.steiner_count = mesh.steiner_count, h.tet_count = mesh.tet_count;
  h.boundary_steiner = mesh.boundary_steiner;
  h.seconds = t.seconds;
  int ok = write_all(fd, &h, sizeof h);
  if (ok && h.rc == 0)
    ok = write_all(fd, mesh.xyz, 3 * mesh.vertex_count * sizeof *mesh.xyz) &&
         write_all(fd, mesh.tets, 4 * mesh.tet_count * sizeof *mesh.tets) &&
         write_all(fd, mesh.labels, mesh.tet_count * sizeof *mesh.labels);
  ref_surface_mesh_free(&mesh);
  return ok;
}

static int mesh_read(int fd, const Header *h, void *result) {
  RefSurfaceMesh *out = result;
  out->xyz = malloc(3 * (h->vertex_count ? h->vertex_count : 1) * sizeof *out->xyz);
  out->tets = malloc(4 * (h->tet_count ? h->tet_count : 1) * sizeof *out->tets);
  out->labels = malloc((h->tet_count ? h->tet_count : 1) * sizeof *out->labels);
  if (!out->xyz || !out->tets || !out->labels || !read_all(fd, out->xyz, 3 * h->vertex_count * sizeof *out->xyz) ||
      !read_all(fd, out->tets, 4 * h->tet_count * sizeof *out->tets) ||
      !read_all(fd, out->labels, h->tet_count * sizeof *out->labels)) {
    ref_surface_mesh_free(out);
    return 0;
  }
  out->vertex_count = h->vertex_count, out->steiner_count = h->steiner_count, out->tet_count = h->tet_count;
  out->boundary_steiner = h->boundary_steiner;
  return 1;
}

static void mesh_discard(void *result) { ref_surface_mesh_free(result); }

int tetgen_child_run(const double *xyz, size_t n, const uint32_t *corners, const size_t *offsets, size_t m,
                     const double *regions, size_t n_regions, const double *holes, size_t n_holes,
                     const char *switches, unsigned time_limit, RefSurfaceMesh *out, RefTiming *timing,
                     char *error, size_t error_size) {
  memset(out, 0, sizeof *out);
  MeshJob job = {xyz, n, corners, offsets, m, regions, n_regions, holes, n_holes, switches};
  Header h;
  int rc = in_child(mesh_work, &job, mesh_read, out, mesh_discard, time_limit, &h, error, error_size);
  if (rc == 0 && timing) timing->seconds = h.seconds;
  return rc;
}

/* ---- Self-intersections -------------------------------------------------------------------------- */

typedef struct Culprits {
  uint32_t *list;
  size_t count;
} Culprits;

static int intersections_work(int fd, const void *job) {
  const MeshJob *j = job;
  Header h;
  memset(&h, 0, sizeof h);
  uint32_t *list = NULL;
  size_t count = 0;
  h.rc = ref_tetgen_intersections(j->xyz, j->n, j->corners, j->m, &list, &count);
  if (h.rc != 0) snprintf(h.message, sizeof h.message, "%s", ref_last_error());
  h.tet_count = count;
  int ok = write_all(fd, &h, sizeof h) && (h.rc != 0 || write_all(fd, list, count * sizeof *list));
  free(list);
  return ok;
}

static int intersections_read(int fd, const Header *h, void *result) {
  Culprits *c = result;
  c->list = malloc((h->tet_count ? h->tet_count : 1) * sizeof *c->list);
  if (!c->list || !read_all(fd, c->list, h->tet_count * sizeof *c->list)) {
    free(c->list);
    c->list = NULL;
    return 0;
  }
  c->count = h->tet_count;
  return 1;
}

static void intersections_discard(void *result) {
  Culprits *c = result;
  free(c->list);
  c->list = NULL;
  c->count = 0;
}

int tetgen_child_intersections(const double *xyz, size_t n, const uint32_t *tris, size_t m, unsigned time_limit,
                               uint32_t **culprits, size_t *count, char *error, size_t error_size) {
  MeshJob job = {xyz, n, tris, NULL, m, NULL, 0, NULL, 0, NULL};
  Culprits c = {NULL, 0};
  Header h;
  int rc = in_child(intersections_work, &job, intersections_read, &c, intersections_discard, time_limit, &h, error,
                    error_size);
  *culprits = c.list;
  *count = c.count;
  return rc;
}
