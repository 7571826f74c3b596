#define _DEFAULT_SOURCE /* wait4, fork, execv, clock_gettime */
#include "bench_util.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

double bench_seconds_now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

BenchRun bench_spawn(char *const args[]) {
  BenchRun r = {0, 0, 0, 0};
  int pipefd[2];
  if (pipe(pipefd) != 0) return r;
  fflush(stdout);
  pid_t pid = fork();
  if (pid < 0) {
    close(pipefd[0]);
    close(pipefd[1]);
    return r;
  }
  if (pid == 0) {
    close(pipefd[0]);
    dup2(pipefd[1], STDOUT_FILENO);
    close(pipefd[1]);
    execv("/proc/self/exe", args);
    _exit(127);
  }
  close(pipefd[1]);
  char line[128] = "";
  FILE *in = fdopen(pipefd[0], "r");
  if (in) {
    if (!fgets(line, sizeof line, in)) line[0] = '\0';
    fclose(in);
  } else {
    close(pipefd[0]);
  }
  int status = 0;
  struct rusage usage;
  memset(&usage, 0, sizeof usage);
  while (wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0 &&
      sscanf(line, "%lf %zu", &r.seconds, &r.count) == 2) {
    r.ok = 1;
    r.peak_mb = (double)usage.ru_maxrss / 1024.0; /* ru_maxrss is in KiB on Linux */
  }
  return r;
}

double bench_median(double *v, int count) {
  for (int i = 1; i < count; i++) /* insertion sort, count is tiny */
    for (int j = i; j > 0 && v[j - 1] > v[j]; j--) {
      double t = v[j];
      v[j] = v[j - 1];
      v[j - 1] = t;
    }
  return count % 2 ? v[count / 2] : 0.5 * (v[count / 2 - 1] + v[count / 2]);
}
