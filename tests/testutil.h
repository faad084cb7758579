/* Shared helpers for the cmocka tests: comparisons that print observed vs
 * expected with %.17g, and a scratch directory per test binary. */
#ifndef TESTUTIL_H
#define TESTUTIL_H
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define ASSERT_NEAR(obs, exp, tol) do { \
    double o_ = (obs), e_ = (exp), t_ = (tol); \
    if (!(fabs(o_ - e_) <= t_)) { \
        print_error("%s: observed %.17g, expected %.17g (tol %.3g)\n", #obs, o_, e_, t_); \
        fail(); } } while (0)

#define ASSERT_EXACT(obs, exp) do { \
    double o_ = (obs), e_ = (exp); \
    if (!(o_ == e_)) { \
        print_error("%s: observed %.17g, expected exactly %.17g\n", #obs, o_, e_); \
        fail(); } } while (0)

/* Write `text` to `path` (test fixtures). */
static inline void tu_write(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* A fresh scratch directory under build/test-tmp/<name>. Returns a static buffer. */
static inline const char *tu_tmpdir(const char *name)
{
    static char dir[512];
    snprintf(dir, sizeof dir, "build/test-tmp/%s", name);
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s' && mkdir -p '%s'", dir, dir);
    if (system(cmd) != 0) fail_msg("cannot create %s", dir);
    return dir;
}
#endif
