// The error channel shared by the reference shims (ref.h).
#include "ref.h"
#include "ref_internal.hpp"

#include <cstdio>

namespace {
thread_local char last_error[512] = "";
}

namespace ref {
int fail(const char *message) {
  std::snprintf(last_error, sizeof last_error, "%s", message ? message : "unknown error");
  return -1;
}
}  // namespace ref

extern "C" const char *ref_last_error(void) { return last_error; }
