#define _DEFAULT_SOURCE /* fork, waitpid */
#include "tetgen_child.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

typedef struct Header {
  int rc;
  size_t vertex_count, steiner_count, boundary_steiner, tet_count;
  double seconds;
  char message[256];
} Header;

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

int tetgen_child_run(const double *xyz, size_t n, const uint32_t *corners, const size_t *offsets, size_t m,
                     const double *regions, size_t n_regions, const double *holes, size_t n_holes,
                     const char *switches, unsigned time_limit, RefSurfaceMesh *out, RefTiming *timing,
                     char *error, size_t error_size) {
  memset(out, 0, sizeof *out);
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
    RefSurfaceMesh mesh;
    RefTiming t = {0};
    memset(&mesh, 0, sizeof mesh);
    Header h;
    memset(&h, 0, sizeof h);
    h.rc = offsets ? ref_tetgen_polygons(xyz, n, corners, offsets, m, regions, n_regions, holes, n_holes, switches, &mesh, &t)
                   : ref_tetgen_surface(xyz, n, corners, m, regions, n_regions, holes, n_holes, switches, &mesh, &t);
    if (h.rc != 0) snprintf(h.message, sizeof h.message, "%s", ref_last_error());
    h.vertex_count = mesh.vertex_count, h.steiner_count = mesh.steiner_count, h.tet_count = mesh.tet_count;
    h.boundary_steiner = mesh.boundary_steiner;
    h.seconds = t.seconds;
    int ok = write_all(fd[1], &h, sizeof h);
    if (ok && h.rc == 0)
      ok = write_all(fd[1], mesh.xyz, 3 * mesh.vertex_count * sizeof *mesh.xyz) &&
           write_all(fd[1], mesh.tets, 4 * mesh.tet_count * sizeof *mesh.tets) &&
           write_all(fd[1], mesh.labels, mesh.tet_count * sizeof *mesh.labels);
    ref_surface_mesh_free(&mesh);
    close(fd[1]);
    _exit(ok ? 0 : 1);
  }
  close(fd[1]);
  Header h;
  memset(&h, 0, sizeof h);
  int got = read_all(fd[0], &h, sizeof h);
  int rc = -1;
  if (got && h.rc == 0) {
    out->xyz = malloc(3 * (h.vertex_count ? h.vertex_count : 1) * sizeof *out->xyz);
    out->tets = malloc(4 * (h.tet_count ? h.tet_count : 1) * sizeof *out->tets);
    out->labels = malloc((h.tet_count ? h.tet_count : 1) * sizeof *out->labels);
    if (out->xyz && out->tets && out->labels && read_all(fd[0], out->xyz, 3 * h.vertex_count * sizeof *out->xyz) &&
        read_all(fd[0], out->tets, 4 * h.tet_count * sizeof *out->tets) &&
        read_all(fd[0], out->labels, h.tet_count * sizeof *out->labels)) {
      out->vertex_count = h.vertex_count, out->steiner_count = h.steiner_count, out->tet_count = h.tet_count;
      out->boundary_steiner = h.boundary_steiner;
      if (timing) timing->seconds = h.seconds;
      rc = 0;
    } else {
      ref_surface_mesh_free(out);
      snprintf(error, error_size, "reading TetGen's result from the child failed");
    }
  }
  close(fd[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    ref_surface_mesh_free(out);
    if (WTERMSIG(status) == SIGALRM)
      snprintf(error, error_size, "TetGen did not finish within %u s (stopped)", time_limit);
    else
      snprintf(error, error_size, "TetGen aborted (signal %d%s)", WTERMSIG(status),
               WTERMSIG(status) == SIGABRT ? ", a failed assert()" : "");
    return -1;
  }
  if (rc != 0 && got && h.rc != 0) snprintf(error, error_size, "%s", h.message);
  if (rc != 0 && !got) snprintf(error, error_size, "TetGen's child ended without a result (status %d)", status);
  return rc;
}
