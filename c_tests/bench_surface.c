/* Benchmark (not a test): tetrahedralization of closed surfaces by delmesh
 * (delmesh_tetrahedralize_surface) and by TetGen 1.5 (-pY and -pq1.414Y through
 * ref_tetgen_surface), on the five largest closed triangle surfaces of the corpus
 * ($DELMESH_CORPUS/surfaces, those its MANIFEST.tsv describes "closed 2-manifold").
 *
 *   bench_surface                        every file, both settings, 3 repetitions alternating
 *                                        (BENCH_SURFACE_COUNT=k keeps the k largest files)
 *   bench_surface --child TOOL FILE SET  one run (TOOL delmesh|tetgen, SET 0: delmesh default /
 *                                        TetGen -pY, 1: ratio bound 1.414 / -pq1.414Y): prints
 *                                        "<seconds> <Steiner points>"
 *
 * Each run is its own process (bench_util.h): the file is read first, the time is measured around
 * the tetrahedralization call up to the output arrays (destruction excluded; for TetGen, the
 * shim's timing), the memory is the process's peak resident size (the file's arrays included,
 * the same for both). A run longer than 600 s is stopped and reported failed. Reported: medians,
 * ratios TetGen / delmesh (> 1: delmesh is faster, smaller) and the Steiner points of each. */
#define _POSIX_C_SOURCE 200809L

#include "bench_util.h"
#include "ref.h"
#include "surface_io.h"

#include <delmesh.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#define REPETITIONS 3
#define FILES 5
#define TIME_LIMIT 600 /* seconds per run */

enum { DELMESH, TETGEN, TOOLS };
static const char *const tool_names[TOOLS] = {"delmesh", "tetgen"};
static const char *const set_names[2] = {"default / -pY", "q1.414 / -pq1.414Y"};

static int child(int tool, const char *path, int set) {
  alarm(TIME_LIMIT);
  SurfaceFile f;
  char error[512];
  if (!surface_file_read(path, &f, error, sizeof error) || !f.all_triangles) {
    fprintf(stderr, "bench_surface: %s\n", f.all_triangles ? error : "not a triangle surface");
    return 1;
  }
  double seconds = 0;
  size_t steiner = 0;
  if (tool == DELMESH) {
    DelmeshSurfaceOptions options;
    memset(&options, 0, sizeof options);
    options.max_radius_edge_ratio = set ? 1.414 : 0;
    DelmeshMesh *mesh = NULL;
    double t0 = bench_seconds_now();
    DelmeshStatus st = delmesh_tetrahedralize_surface(f.xyz, f.n, f.corners, f.polygon_count, &options, &mesh);
    seconds = bench_seconds_now() - t0;
    if (st != DELMESH_OK) {
      fprintf(stderr, "bench_surface: delmesh failed (status %d): %s\n", (int)st, delmesh_last_error_message());
      return 1;
    }
    steiner = delmesh_mesh_vertex_count(mesh) - f.n;
    /* Nothing is freed: the process ends here. */
  } else {
    RefSurfaceMesh mesh;
    RefTiming timing = {0};
    memset(&mesh, 0, sizeof mesh);
    if (ref_tetgen_surface(f.xyz, f.n, f.corners, f.polygon_count, NULL, 0, NULL, 0, set ? "pq1.414YQ" : "pYQ", &mesh,
                           &timing) != 0) {
      fprintf(stderr, "bench_surface: TetGen failed: %s\n", ref_last_error());
      return 1;
    }
    seconds = timing.seconds;
    steiner = mesh.steiner_count;
  }
  printf("%.6f %zu\n", seconds, steiner);
  return 0;
}

/* ---- The files: the largest closed triangle surfaces of the manifest --------------------------- */

typedef struct File {
  char path[4096];
  char name[64];
  size_t triangles;
} File;

static int by_size(const void *pa, const void *pb) {
  const File *a = pa, *b = pb;
  return (a->triangles < b->triangles) - (a->triangles > b->triangles);
}

/* Fills files[0..*count) with the manifest's closed triangle surfaces, largest first. */
static int largest_files(File *files, size_t capacity, size_t *count) {
  const char *corpus = getenv("DELMESH_CORPUS");
  char path[4096];
  snprintf(path, sizeof path, "%s/MANIFEST.tsv", corpus && corpus[0] ? corpus : ".");
  FILE *manifest = corpus && corpus[0] ? fopen(path, "r") : NULL;
  if (!manifest) return 0;
  char *line = NULL;
  size_t line_capacity = 0, n = 0;
  File *all = NULL;
  size_t all_count = 0, all_capacity = 0;
  while (getline(&line, &line_capacity, manifest) >= 0) {
    char *tab = strchr(line, '\t'), *description = strrchr(line, '\t');
    if (!tab || !description) continue;
    *tab = '\0';
    const char *dot = strrchr(line, '.');
    if (strncmp(line, "surfaces/", 9) != 0 || strchr(line + 9, '/') || !dot || strcmp(dot, ".off") != 0) continue;
    const char *closed = NULL, *faces = strstr(description, " F=");
    for (const char *p = description; *p && !closed; p++)
      if (strncasecmp(p, "closed 2-manifold", 17) == 0) closed = p;
    size_t triangles = 0;
    char kind[8] = "";
    if (!closed || !faces || sscanf(faces, " F=%zu %7[a-z]", &triangles, kind) != 2 || strcmp(kind, "tri") != 0) continue;
    if (all_count == all_capacity) {
      all_capacity = all_capacity ? 2 * all_capacity : 64;
      File *grown = realloc(all, all_capacity * sizeof *all);
      if (!grown) break;
      all = grown;
    }
    File *f = &all[all_count++];
    snprintf(f->path, sizeof f->path, "%s/%s", corpus, line);
    snprintf(f->name, sizeof f->name, "%s", line + 9);
    f->triangles = triangles;
  }
  free(line);
  fclose(manifest);
  if (all) qsort(all, all_count, sizeof *all, by_size);
  for (size_t i = 0; i < all_count && n < capacity; i++) files[n++] = all[i];
  free(all);
  *count = n;
  return n > 0;
}

int main(int argc, char **argv) {
  if (argc == 5 && strcmp(argv[1], "--child") == 0) {
    int tool = strcmp(argv[2], "delmesh") == 0 ? DELMESH : strcmp(argv[2], "tetgen") == 0 ? TETGEN : -1;
    int set = atoi(argv[4]);
    if (tool < 0 || set < 0 || set > 1) return 2;
    return child(tool, argv[3], set);
  }
  if (argc != 1) {
    fprintf(stderr, "usage: %s   (BENCH_SURFACE_COUNT=k keeps the k largest files)\n", argv[0]);
    return 2;
  }
  const char *env = getenv("BENCH_SURFACE_COUNT");
  size_t wanted = env && env[0] ? (size_t)atoi(env) : FILES;
  if (wanted < 1 || wanted > FILES) wanted = FILES;
  File files[FILES];
  size_t count = 0;
  if (!largest_files(files, wanted, &count)) {
    printf("bench_surface: no corpus (set DELMESH_CORPUS to the folder of MANIFEST.tsv): skipped\n");
    return 0;
  }

  printf("delmesh %s vs TetGen 1.5 (tetrahedralize through ref_tetgen_surface), closed surfaces of the corpus\n",
         delmesh_version_string());
  printf("each run in its own process; %d repetitions, alternating; medians; ratios TetGen / delmesh\n\n", REPETITIONS);
  printf("%-16s %7s %-19s | %9s %9s %7s | %9s %9s %7s | %s\n", "surface", "tris", "delmesh / TetGen", "delmesh s",
         "TetGen s", "ratio", "delmesh MB", "TetGen MB", "ratio", "Steiner: delmesh / TetGen");
  int failures = 0;
  for (size_t c = 0; c < count; c++)
    for (int set = 0; set < 2; set++) {
      double times[TOOLS][REPETITIONS], mems[TOOLS][REPETITIONS];
      size_t steiner[TOOLS] = {0, 0};
      int runs[TOOLS] = {0, 0}, failed[TOOLS] = {0, 0};
      char set_arg[4];
      snprintf(set_arg, sizeof set_arg, "%d", set);
      for (int rep = 0; rep < REPETITIONS; rep++)
        for (int k = 0; k < TOOLS; k++) {
          int tool = (k + rep) % TOOLS; /* alternate who goes first */
          if (failed[tool]) continue;
          char *args[] = {argv[0], (char *)"--child", (char *)tool_names[tool], files[c].path, set_arg, NULL};
          BenchRun r = bench_spawn(args);
          if (!r.ok) {
            failed[tool] = 1;
            continue;
          }
          times[tool][runs[tool]] = r.seconds;
          mems[tool][runs[tool]] = r.peak_mb;
          runs[tool]++;
          steiner[tool] = r.count;
        }
      double t[TOOLS], mb[TOOLS];
      char time_cell[TOOLS][16], mem_cell[TOOLS][16], steiner_cell[TOOLS][24], time_ratio[16] = "-", mem_ratio[16] = "-";
      for (int tool = 0; tool < TOOLS; tool++) {
        if (failed[tool] || runs[tool] == 0) {
          snprintf(time_cell[tool], sizeof time_cell[tool], "failed");
          snprintf(mem_cell[tool], sizeof mem_cell[tool], "-");
          snprintf(steiner_cell[tool], sizeof steiner_cell[tool], "-");
          failures++;
          continue;
        }
        t[tool] = bench_median(times[tool], runs[tool]);
        mb[tool] = bench_median(mems[tool], runs[tool]);
        snprintf(time_cell[tool], sizeof time_cell[tool], "%.3f", t[tool]);
        snprintf(mem_cell[tool], sizeof mem_cell[tool], "%.1f", mb[tool]);
        snprintf(steiner_cell[tool], sizeof steiner_cell[tool], "%zu", steiner[tool]);
      }
      if (!failed[DELMESH] && !failed[TETGEN] && runs[DELMESH] && runs[TETGEN]) {
        snprintf(time_ratio, sizeof time_ratio, "%.2f", t[TETGEN] / t[DELMESH]);
        snprintf(mem_ratio, sizeof mem_ratio, "%.2f", mb[TETGEN] / mb[DELMESH]);
      }
      printf("%-16s %7zu %-19s | %9s %9s %7s | %9s %9s %7s | %s / %s\n", files[c].name, files[c].triangles,
             set_names[set], time_cell[DELMESH], time_cell[TETGEN], time_ratio, mem_cell[DELMESH], mem_cell[TETGEN],
             mem_ratio, steiner_cell[DELMESH], steiner_cell[TETGEN]);
      fflush(stdout);
    }
  return failures ? 1 : 0;
}
