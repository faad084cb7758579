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
#include <sys/wait.h>

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

/* Write `text` to the fixture <dir>/<name>, its path into path[n]: a test
 * names its inputs by that path, so a cut one would test another file. */
static inline void tu_write_in(char *path, size_t n, const char *dir, const char *name, const char *text)
{
    if (snprintf(path, n, "%s/%s", dir, name) >= (int)n) fail_msg("tu_write_in: path %s/%s too long", dir, name);
    tu_write(path, text);
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
/* Run "<env>build/crownshy <args>" (env: a prefix such as
 * "OPENBLAS_NUM_THREADS=1 ", or "") with stderr joined to stdout into out[n].
 * Returns the exit code, or -1 if the command did not exit normally. */
static inline int tu_run_cli(const char *env, const char *args, char *out, size_t n)
{
    char cmd[4352];
    if (snprintf(cmd, sizeof cmd, "%sbuild/crownshy %s 2>&1", env, args) >= (int)sizeof cmd)
        fail_msg("tu_run_cli: command line too long");
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    size_t got = fread(out, 1, n - 1, p);
    out[got] = '\0';
    int st = pclose(p);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* tu_run_cli of "<command> <path>" on a fixture file holding text, written as
 * <file> into the scratch folder build/test-tmp/<scratch>. */
static inline int tu_run_cli_on(const char *env, const char *command, const char *scratch, const char *file,
                                const char *text, char *out, size_t n)
{
    char p[600], a[700];
    tu_write_in(p, sizeof p, tu_tmpdir(scratch), file, text);
    if (snprintf(a, sizeof a, "%s %s", command, p) >= (int)sizeof a)
        fail_msg("tu_run_cli_on: '%s %s' too long", command, p);
    return tu_run_cli(env, a, out, n);
}
#endif
