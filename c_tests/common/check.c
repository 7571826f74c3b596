#include "check.h"

#include <stdarg.h>
#include <stdio.h>

static unsigned long passed_count;
static unsigned long failed_count;

int check_case(int ok, const char *format, ...) {
  va_list args;
  ok = ok != 0;
  if (ok)
    passed_count++;
  else
    failed_count++;
  fputs(ok ? "PASS  " : "FAIL  ", stdout);
  va_start(args, format);
  vprintf(format, args);
  va_end(args);
  fputc('\n', stdout);
  fflush(stdout);
  return ok;
}

void check_note(const char *format, ...) {
  va_list args;
  fputs("      ", stdout);
  va_start(args, format);
  vprintf(format, args);
  va_end(args);
  fputc('\n', stdout);
  fflush(stdout);
}

int check_finish(void) {
  printf("%lu passed, %lu failed\n", passed_count, failed_count);
  fflush(stdout);
  return failed_count == 0 && passed_count > 0 ? 0 : 1;
}
