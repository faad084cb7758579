/* Every command of `crownshy` parses its options with opts (src/base/opts.h):
 * for each command `crownshy --help` lists (the experiments' commands come
 * from src/base/manifest.h, so a new command is tested without a new line
 * here), --help exits 0 and prints "usage: crownshy <cmd>", an unknown
 * option exits 2 naming it, and every numeric option its --help lists
 * ("--name N [min..max]" or "--name X [min..max]") refuses a non-numeric, an
 * empty and an out-of-range value (one past an end of its printed range)
 * with exit 2 naming the option.
 * Runs build/crownshy from a scratch directory (no gates/, frozen/ or src/),
 * so a command that wrongly ran past its parser could not touch the tree. */
#include "testutil.h"
#include <limits.h>
#include <unistd.h>

#define MAXCMDS 96
#define MAXNUM 16

typedef struct {
    char opt[48];     /* numeric option without "--" */
    char out[48];     /* a value outside its range */
} num_opt;

typedef struct {
    char cmd[48];
    num_opt num[MAXNUM];
    size_t nnum;
} cmd_case;

static cmd_case CMDS[MAXCMDS];
static size_t NCMDS;

static char out[65536];
static char env[PATH_MAX + 64];

/* A scratch directory holding only build/crownshy (a link to ours). */
static int setup(void **s)
{
    (void)s;
    char self[PATH_MAX], link[PATH_MAX + 64], cmd[2 * PATH_MAX + 200];
    if (!realpath("build/crownshy", self)) return -1;
    const char *dir = tu_tmpdir("cli_opts");
    snprintf(cmd, sizeof cmd, "mkdir -p '%s/build'", dir);
    if (system(cmd) != 0) return -1;
    snprintf(link, sizeof link, "%s/build/crownshy", dir);
    if (symlink(self, link) != 0) return -1;
    snprintf(env, sizeof env, "cd '%s' && env -u FIELD_TABLE ", dir);
    return 0;
}

static int run(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static int run(const char *fmt, ...)
{
    char args[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    return tu_run_cli(env, args, out, sizeof out);
}

/* The commands of `crownshy --help` (indented lines under each group) and,
 * from each command's --help, its numeric options with a value past the
 * range it prints. */
static void discover(void)
{
    static char help[65536];
    NCMDS = 0;
    if (run("--help") != 0) fail_msg("crownshy --help failed:\n%s", out);
    snprintf(help, sizeof help, "%s", out);
    for (const char *p = help; (p = strstr(p, "\n  ")) && NCMDS < MAXCMDS; p++) {
        cmd_case *c = &CMDS[NCMDS];
        memset(c, 0, sizeof *c);
        if (sscanf(p + 3, "%47s", c->cmd) != 1 || c->cmd[0] == '-') continue;
        NCMDS++;
        if (run("%s --help", c->cmd) != 0) fail_msg("crownshy %s --help failed:\n%s", c->cmd, out);
        for (const char *q = out; (q = strstr(q, "\n  --")) && c->nnum < MAXNUM; q++) {
            char meta[8];
            num_opt *o = &c->num[c->nnum];
            if (sscanf(q + 5, "%47s %7s", o->opt, meta) != 2 || (strcmp(meta, "N") && strcmp(meta, "X"))) continue;
            /* the range is the last "[min..max]" of the option's line */
            const char *eol = strchr(q + 1, '\n'), *rg = NULL, *dd = NULL;
            for (const char *b = q + 1; (b = strchr(b, '[')) && eol && b < eol; b++)
                if ((dd = strstr(b, "..")) && dd < eol) rg = b;
            if (!rg) fail_msg("crownshy %s --help: --%s prints no [min..max] range", c->cmd, o->opt);
            dd = strstr(rg, "..");
            double hi = strtod(dd + 2, NULL);
            if (!strcmp(meta, "N")) snprintf(o->out, sizeof o->out, "%.0f", hi + 1);
            else snprintf(o->out, sizeof o->out, "%.17g", hi + (hi > 1 ? hi : 1));
            c->nnum++;
        }
    }
    if (NCMDS < 20) fail_msg("crownshy --help lists only %zu commands:\n%s", NCMDS, help);
}

static void test_every_command_is_listed_by_group(void **s)
{
    (void)s;
    if (!NCMDS) discover();
    assert_int_equal(run("--help"), 0);
    assert_non_null(strstr(out, "\nreviewing the package"));
    assert_non_null(strstr(out, "\nrunning the study"));
    assert_non_null(strstr(out, "\nmaintaining the package"));
    assert_non_null(strstr(out, "start with `crownshy verify`"));
}

static void test_help_exits_zero_and_prints_usage(void **s)
{
    (void)s;
    if (!NCMDS) discover();
    for (size_t i = 0; i < NCMDS; i++) {
        const char *c = CMDS[i].cmd;
        char want[96];
        int n = snprintf(want, sizeof want, "usage: crownshy %s", c);
        int rc = run("%s --help", c);
        const char *u = strstr(out, want);
        if (rc != 0 || !u || (u[n] != ' ' && u[n] != '\n'))
            fail_msg("crownshy %s --help: exit %d, output:\n%s", c, rc, out);
    }
}

static void test_unknown_option_exits_2_naming_it(void **s)
{
    (void)s;
    if (!NCMDS) discover();
    for (size_t i = 0; i < NCMDS; i++) {
        const cmd_case *c = &CMDS[i];
        int rc = run("%s --no-such-option 1", c->cmd);
        if (rc != 2 || !strstr(out, "--no-such-option"))
            fail_msg("crownshy %s --no-such-option: exit %d, output:\n%s", c->cmd, rc, out);
    }
}

static void expect_refused(const cmd_case *c, const char *opt, const char *value)
{
    char name[80];
    snprintf(name, sizeof name, "--%s", opt);
    int rc = run("%s %s '%s'", c->cmd, name, value);
    if (rc != 2 || !strstr(out, name))
        fail_msg("crownshy %s %s '%s': exit %d (want 2 naming %s), output:\n%s", c->cmd, name, value, rc, name, out);
}

static void test_bad_numbers_exit_2_naming_the_option(void **s)
{
    (void)s;
    if (!NCMDS) discover();
    size_t checked = 0;
    for (size_t i = 0; i < NCMDS; i++)
        for (size_t k = 0; k < CMDS[i].nnum; k++) {
            expect_refused(&CMDS[i], CMDS[i].num[k].opt, "abc");
            expect_refused(&CMDS[i], CMDS[i].num[k].opt, "");
            expect_refused(&CMDS[i], CMDS[i].num[k].opt, CMDS[i].num[k].out);
            checked++;
        }
    assert_true(checked >= 30);
    assert_true(NCMDS > 0);
}

/* A die-back that does not parse is refused, never read as 0. */
static void test_beta_abc_is_a_usage_error(void **s)
{
    (void)s;
    assert_int_equal(run("irreducibility-perturb --beta abc"), 2);
    assert_non_null(strstr(out, "--beta"));
}

/* Other usage errors name the option; valid values still parse. */
static void test_choices_and_required_options(void **s)
{
    (void)s;
    static const struct { const char *args, *named; } usage[] = {
        {"main-run --seed 1 --arm both --out x.tsv", "--arm"},
        {"main-run --seed 1 --arm joint --out x.tsv --scale tiny", "--scale"},
        {"main-baselines --out x.tsv --scale tiny", "--scale"},
        {"main-run --arm joint --out x.tsv", "--seed"},
        {"main-run --seed 1 --out x.tsv", "--arm"},
        {"main-run --seed 1 --arm joint", "--out"},
        {"main-summary --seeds 2", "--dir"},
        {"main-summary --dir x", "--seeds"},
        {"comparison-run --joint a --indep b", "--out"},
        {"field-calibrate", "--out"},
        {"field-heldout --out x.tsv", "--calibration"},
        {"anisotropy-jitter-calibrate --out x.tsv", "--sweep"},
        {"anisotropy-heldout --calibration c.tsv --out x.tsv", "--jitter-calibration"},
        {"irreducibility-perturb --tag other", "--tag"},
        {"train --arm both", "--arm"},
        {"sample", "--ckpt"},
    };
    for (size_t i = 0; i < sizeof usage / sizeof *usage; i++) {
        int rc = run("%s", usage[i].args);
        if (rc != 2 || !strstr(out, usage[i].named) || !strstr(out, "--help)"))
            fail_msg("crownshy %s: exit %d (want 2 naming %s), output:\n%s", usage[i].args, rc, usage[i].named, out);
    }
    /* a zero-padded seed (experiments.mk: --seed 01) parses; without gates/ the run stops at its inputs (3) */
    assert_int_equal(run("main-run --seed 01 --arm joint --scale smoke --out x.tsv"), 3);
    assert_null(strstr(out, "usage"));
    /* field-beta takes its table as a positional argument (experiments.mk) */
    assert_int_equal(run("field-beta no-such-calibration.tsv"), 3);
    assert_null(strstr(out, "usage"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_command_is_listed_by_group),
        cmocka_unit_test(test_help_exits_zero_and_prints_usage),
        cmocka_unit_test(test_unknown_option_exits_2_naming_it),
        cmocka_unit_test(test_bad_numbers_exit_2_naming_the_option),
        cmocka_unit_test(test_beta_abc_is_a_usage_error),
        cmocka_unit_test(test_choices_and_required_options),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
