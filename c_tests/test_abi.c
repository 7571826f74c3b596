/* The ABI contract of include/delmesh.h against the loaded library (API.md "Status"):
 * versions, the numeric value of every status, and the last-error channel. */
#define _POSIX_C_SOURCE 200809L

#include "check.h"

#include <delmesh.h>

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Parses "MAJOR.MINOR.PATCH" (decimal, nothing before or after); 1 on success. */
static int parse_version(const char *s, unsigned long part[3]) {
  for (int k = 0; k < 3; k++) {
    if (*s < '0' || *s > '9') return 0;
    char *end;
    part[k] = strtoul(s, &end, 10);
    s = end;
    if (k < 2) {
      if (*s != '.') return 0;
      s++;
    }
  }
  return *s == '\0';
}

static void check_status_values(void) {
  static const struct {
    const char *name;
    long value, expected;
  } statuses[] = {
      {"DELMESH_OK", DELMESH_OK, 0},
      {"DELMESH_ERROR_NULL_ARGUMENT", DELMESH_ERROR_NULL_ARGUMENT, 1},
      {"DELMESH_ERROR_INVALID_ARGUMENT", DELMESH_ERROR_INVALID_ARGUMENT, 2},
      {"DELMESH_ERROR_INVALID_INPUT", DELMESH_ERROR_INVALID_INPUT, 3},
      {"DELMESH_ERROR_CALLBACK", DELMESH_ERROR_CALLBACK, 4},
      {"DELMESH_ERROR_CANCELLED", DELMESH_ERROR_CANCELLED, 5},
      {"DELMESH_ERROR_LIMIT", DELMESH_ERROR_LIMIT, 6},
      {"DELMESH_ERROR_OUT_OF_MEMORY", DELMESH_ERROR_OUT_OF_MEMORY, 7},
      {"DELMESH_ERROR_IO", DELMESH_ERROR_IO, 8},
      {"DELMESH_ERROR_INTERNAL", DELMESH_ERROR_INTERNAL, 9},
  };
  for (size_t k = 0; k < sizeof statuses / sizeof statuses[0]; k++)
    check_case(statuses[k].value == statuses[k].expected, "status %s = %ld (API.md: %ld)",
               statuses[k].name, statuses[k].value, statuses[k].expected);
  /* The status travels as a C enum: its size is that of int on this ABI. */
  check_case(sizeof(DelmeshStatus) == sizeof(int), "sizeof(DelmeshStatus) = %zu (int: %zu)",
             sizeof(DelmeshStatus), sizeof(int));
}

/* A failing call that must name point `index` in its message (NaN coordinate). */
static DelmeshStatus fail_with_nan_at(size_t index) {
  double xyz[3 * 6] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1, 2, 3, 4};
  DelmeshMesh *out = NULL;
  xyz[3 * index + 1] = strtod("nan", NULL);
  DelmeshStatus s = delmesh_delaunay_tetrahedralize(xyz, 6, &out);
  delmesh_mesh_free(out);
  return s;
}

typedef struct ThreadResult {
  DelmeshStatus status;
  char message[512];
} ThreadResult;

static void *other_thread(void *arg) {
  ThreadResult *r = arg;
  const char *before = delmesh_last_error_message();
  /* A fresh thread has no error yet: the message is empty, never NULL. */
  snprintf(r->message, sizeof r->message, "%s", before ? before : "(NULL)");
  if (before == NULL || before[0] != '\0') {
    r->status = DELMESH_OK; /* flags the failure to the main thread */
    return NULL;
  }
  r->status = fail_with_nan_at(1);
  const char *after = delmesh_last_error_message();
  snprintf(r->message, sizeof r->message, "%s", after ? after : "(NULL)");
  return NULL;
}

static void check_last_error(void) {
  const char *m = delmesh_last_error_message();
  check_case(m != NULL, "last_error_message before any failure is not NULL (\"%s\")", m ? m : "");

  DelmeshStatus s = fail_with_nan_at(4);
  m = delmesh_last_error_message();
  check_case(s == DELMESH_ERROR_INVALID_INPUT && m != NULL && m[0] != '\0',
             "after a failure: status %d, message \"%s\"", (int)s, m ? m : "(NULL)");
  char main_message[512];
  snprintf(main_message, sizeof main_message, "%s", m ? m : "");

  /* The message is per thread: another thread's failure does not replace ours. */
  pthread_t thread;
  ThreadResult r;
  memset(&r, 0, sizeof r);
  int created = pthread_create(&thread, NULL, other_thread, &r) == 0;
  if (created) pthread_join(thread, NULL);
  check_case(created && r.status == DELMESH_ERROR_INVALID_INPUT && r.message[0] != '\0' &&
                 strcmp(r.message, main_message) != 0,
             "another thread: empty message at start, then its own (\"%s\")", r.message);
  m = delmesh_last_error_message();
  check_case(m != NULL && strcmp(m, main_message) == 0,
             "this thread's message unchanged by the other thread's failure");

  /* A successful call leaves the message non-NULL (API: never NULL). */
  const double tet[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  DelmeshMesh *mesh = NULL;
  s = delmesh_delaunay_tetrahedralize(tet, 4, &mesh);
  m = delmesh_last_error_message();
  check_case(s == DELMESH_OK && mesh != NULL && m != NULL,
             "after a success: status %d, message not NULL", (int)s);
  delmesh_mesh_free(mesh);
}

int main(void) {
  uint32_t abi = delmesh_abi_version();
  check_case(abi == DELMESH_ABI_VERSION, "delmesh_abi_version() = %lu, header DELMESH_ABI_VERSION = %lu",
             (unsigned long)abi, (unsigned long)DELMESH_ABI_VERSION);

  const char *version = delmesh_version_string();
  unsigned long part[3] = {0, 0, 0};
  int parsed = version != NULL && parse_version(version, part);
  check_case(parsed, "version string \"%s\" is MAJOR.MINOR.PATCH (%lu, %lu, %lu)",
             version ? version : "(NULL)", part[0], part[1], part[2]);
  check_case(version != NULL && version == delmesh_version_string(),
             "version string is static storage (same pointer on every call)");
#if defined(DELMESH_VERSION_MAJOR) && defined(DELMESH_VERSION_MINOR) && defined(DELMESH_VERSION_PATCH)
  check_case(parsed && part[0] == DELMESH_VERSION_MAJOR && part[1] == DELMESH_VERSION_MINOR &&
                 part[2] == DELMESH_VERSION_PATCH,
             "version string matches the header's DELMESH_VERSION_MAJOR/MINOR/PATCH");
#else
  check_note("the header defines no DELMESH_VERSION_MAJOR/MINOR/PATCH macros; not compared");
#endif

  check_status_values();
  check_last_error();
  return check_finish();
}
