/* Every command of `crownshy` parses its options with opts (src/base/opts.h):
 * for each command of the table in src/cli/cli.c, --help exits 0 and prints
 * "usage: crownshy <cmd>", an unknown option exits 2 naming it, and every
 * numeric option refuses a non-numeric, an empty and an out-of-range value
 * with exit 2 naming the option. A new command is one line of CMDS; the
 * tests fail while a command of `crownshy --help`, or a numeric option of a
 * command's --help, is missing from it.
 * Runs build/crownshy from a scratch directory (no gates/, frozen/ or src/),
 * so a command that wrongly ran past its parser could not touch the tree. */
#include "testutil.h"
#include <limits.h>
#include <unistd.h>

#define MAXNUM 12

typedef struct {
    const char *opt;  /* numeric option without "--" */
    const char *out;  /* a value outside its range */
} num_opt;

typedef struct {
    const char *cmd;
    const char *pos;  /* a dummy positional argument when the command requires one, else "" */
    num_opt num[MAXNUM];
} cmd_case;

static const cmd_case CMDS[] = {
    {"figures", "", {{0}}},
    {"main-run", "", {{"seed", "0"}, {"epochs", "0"}, {"train-stands", "10001"}, {"pair", "2"}}},
    {"main-baselines", "", {{0}}},
    {"main-summary", "", {{"seeds", "65"}}},
    {"main-redraw", "", {{"seed", "0"}}},
    {"main-train", "", {{"seed", "0"}, {"epochs", "0"}, {"train-stands", "10001"}, {"pair", "2"}}},
    {"main-eval", "", {{"seed", "4294967296"}}},
    {"comp-run", "", {{0}}},
    {"comp-dist", "", {{"patches", "0"}}},
    {"bench-teacher", "", {{"reps", "0"}}},
    {"readings-summary", "", {{0}}},
    {"model-readings", "", {{0}}},
    {"run", "irreducibility-perturb", {{"stands", "0"}, {"beta", "1"}}},
    {"gates", "", {{0}}},
    {"check-tsv", "no-such.tsv", {{0}}},
    {"verify", "", {{0}}},
    {"numbers", "", {{0}}},
    {"audit", "", {{0}}},
    {"trace", "NoSuchMacro", {{0}}},
    {"pin", "", {{0}}},
    {"hash-frozen", "", {{0}}},
    {"field-summary", "", {{0}}},
    {"field-calibrate", "", {{0}}},
    {"field-beta", "no-such.tsv", {{0}}},
    {"field-heldout", "", {{"stands", "0"}}},
    {"aniso-lattice", "", {{"stands", "10001"}}},
    {"aniso-hardcore", "", {{"stands", "0"}}},
    {"aniso-jitter", "", {{"stands", "-3"}}},
    {"aniso-jitter-calibrate", "", {{0}}},
    {"aniso-heldout", "", {{"stands", "0"}}},
    {"field-diagnose", "", {{"stands", "0"}}},
    {"version", "", {{0}}},
    {"train", "", {{"steps", "0"}, {"batch", "4097"}, {"lr", "0"}, {"width", "0"}, {"depth", "65"}, {"heads", "0"},
                   {"mlp", "16385"}, {"seed", "-1"}, {"stands", "0"}, {"spacing", "0.05"}, {"ckpt-every", "-1"}, {"pair", "2"}}},
    {"sample", "", {{"n", "0"}, {"euler", "100001"}, {"seed", "4294967296"}, {"spacing", "1e3"}}},
    {"bench-model", "", {{"repeats", "16"}, {"steps", "0"}, {"batch", "0"}}},
};
#define NCMDS (sizeof CMDS / sizeof *CMDS)

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

static const cmd_case *find(const char *name)
{
    for (size_t i = 0; i < NCMDS; i++)
        if (!strcmp(CMDS[i].cmd, name)) return &CMDS[i];
    return NULL;
}

static void test_every_command_is_in_the_table(void **s)
{
    (void)s;
    assert_int_equal(run("--help"), 0);
    const char *p = strstr(out, "\ncommands:\n");
    assert_non_null(p);
    p += strlen("\ncommands:\n");
    size_t listed = 0;
    while (p[0] == ' ' && p[1] == ' ') {
        char name[64];
        if (sscanf(p, " %63s", name) != 1) break;
        if (!find(name)) fail_msg("command '%s' of crownshy --help has no row in CMDS", name);
        listed++;
        p = strchr(p, '\n');
        if (!p) break;
        p++;
    }
    if (listed != NCMDS) fail_msg("crownshy --help lists %zu commands, CMDS has %zu rows", listed, NCMDS);
}

static void test_help_exits_zero_and_prints_usage(void **s)
{
    (void)s;
    for (size_t i = 0; i < NCMDS; i++) {
        const char *c = CMDS[i].cmd;
        char want[96];
        int n = snprintf(want, sizeof want, "usage: crownshy %s", c);
        int rc = run("%s --help", c);
        const char *u = strstr(out, want);
        if (rc != 0 || !u || (u[n] != ' ' && u[n] != '\n')) fail_msg("crownshy %s --help: exit %d, output:\n%s", c, rc, out);
    }
}

/* The numeric options a command's --help lists ("  --name N" or "  --name X"). */
static void test_every_numeric_option_is_in_the_table(void **s)
{
    (void)s;
    for (size_t i = 0; i < NCMDS; i++) {
        const cmd_case *c = &CMDS[i];
        assert_int_equal(run("%s --help", c->cmd), 0);
        size_t listed = 0, have = 0;
        while (have < MAXNUM && c->num[have].opt) have++;
        for (const char *p = out; (p = strstr(p, "\n  --")); p++) {
            char name[64], meta[16];
            if (sscanf(p + 5, "%63s %15s", name, meta) != 2 || (strcmp(meta, "N") && strcmp(meta, "X"))) continue;
            listed++;
            size_t k = 0;
            while (k < have && strcmp(c->num[k].opt, name)) k++;
            if (k == have) fail_msg("crownshy %s: numeric option --%s has no entry in CMDS", c->cmd, name);
        }
        if (listed != have) fail_msg("crownshy %s --help lists %zu numeric options, CMDS has %zu", c->cmd, listed, have);
    }
}

static void test_unknown_option_exits_2_naming_it(void **s)
{
    (void)s;
    for (size_t i = 0; i < NCMDS; i++) {
        const cmd_case *c = &CMDS[i];
        int rc = run("%s %s --no-such-option 1", c->cmd, c->pos);
        if (rc != 2 || !strstr(out, "--no-such-option")) fail_msg("crownshy %s --no-such-option: exit %d, output:\n%s", c->cmd, rc, out);
    }
}

static void expect_refused(const cmd_case *c, const char *opt, const char *value)
{
    char name[80];
    snprintf(name, sizeof name, "--%s", opt);
    int rc = run("%s %s %s '%s'", c->cmd, c->pos, name, value);
    if (rc != 2 || !strstr(out, name)) fail_msg("crownshy %s %s '%s': exit %d (want 2 naming %s), output:\n%s", c->cmd, name, value, rc, name, out);
}

static void test_bad_numbers_exit_2_naming_the_option(void **s)
{
    (void)s;
    size_t checked = 0;
    for (size_t i = 0; i < NCMDS; i++)
        for (size_t k = 0; k < MAXNUM && CMDS[i].num[k].opt; k++) {
            expect_refused(&CMDS[i], CMDS[i].num[k].opt, "abc");
            expect_refused(&CMDS[i], CMDS[i].num[k].opt, "");
            expect_refused(&CMDS[i], CMDS[i].num[k].opt, CMDS[i].num[k].out);
            checked++;
        }
    assert_true(checked >= 30);
}

/* The bug of issue 12: `run irreducibility-perturb --beta abc` exited 0 and
 * wrote a table with beta = 0. */
static void test_run_beta_abc_is_a_usage_error(void **s)
{
    (void)s;
    assert_int_equal(run("run irreducibility-perturb --beta abc"), 2);
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
        {"comp-run --joint a --indep b", "--out"},
        {"field-calibrate", "--out"},
        {"field-heldout --out x.tsv", "--calibration"},
        {"aniso-jitter-calibrate --out x.tsv", "--sweep"},
        {"aniso-heldout --calibration c.tsv --out x.tsv", "--jitter-calibration"},
        {"run irreducibility-perturb --tag other", "--tag"},
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
        cmocka_unit_test(test_every_command_is_in_the_table),
        cmocka_unit_test(test_help_exits_zero_and_prints_usage),
        cmocka_unit_test(test_every_numeric_option_is_in_the_table),
        cmocka_unit_test(test_unknown_option_exits_2_naming_it),
        cmocka_unit_test(test_bad_numbers_exit_2_naming_the_option),
        cmocka_unit_test(test_run_beta_abc_is_a_usage_error),
        cmocka_unit_test(test_choices_and_required_options),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
