/* The reporting harness of the C test programs: one line per case, a final
 * "N passed, M failed" line, and the exit status (0 only when nothing failed). */
#ifndef DELMESH_C_TESTS_CHECK_H
#define DELMESH_C_TESTS_CHECK_H

#if defined(__GNUC__)
#define CHECK_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define CHECK_PRINTF(f, a)
#endif

/* Records one case: prints "PASS  <text>" or "FAIL  <text>"; returns `ok` (0 or 1). */
int check_case(int ok, const char *format, ...) CHECK_PRINTF(2, 3);

/* An informational line (a figure, a comparison that is reported but not asserted). */
void check_note(const char *format, ...) CHECK_PRINTF(1, 2);

/* Prints "N passed, M failed" and returns the process exit status. */
int check_finish(void);

#endif
