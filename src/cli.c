/* crownshy: the one command-line entry point. Only this file decides how the
 * process dies; library calls return a cs_status (SPEC §11 exit codes). */
#include "cs.h"
#include "teacher.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef int (*cmd_fn)(int argc, char **argv);
typedef struct { const char *name; cmd_fn fn; const char *help; } cli_cmd;

static int cmd_version(int argc, char **argv)
{
    (void)argc; (void)argv;
    puts("crownshy 0.1");
    return 0;
}

/* Teacher cost (SPEC §10): ms per 144-tree stand at N = 48 and N = 384. */
static int cmd_bench_teacher(int argc, char **argv)
{
    if (argc > 1 && !strcmp(argv[1], "--help")) {
        puts("usage: crownshy bench-teacher [reps]\n"
             "prints teacher ms per 144-tree controlled-lattice stand (d = 3.5 m, beta 0.06) at N = 48 and N = 384");
        return 0;
    }
    int reps = argc > 1 ? atoi(argv[1]) : 10;
    if (reps < 1) { fprintf(stderr, "bench-teacher: reps must be >= 1\n"); return 2; }
    int levels[2] = {48, 384};
    for (int k = 0; k < 2; k++) {
        double ms = 0.0;
        cs_status st = teacher_bench(levels[k], k ? (reps + 3) / 4 : reps, &ms);
        if (st) { fprintf(stderr, "bench-teacher: %s\n", cs_errmsg()); return cs_exit_code(st); }
        printf("teacher_ms_per_stand_N%d\t%.3f\n", levels[k], ms);
    }
    return 0;
}

static const cli_cmd cli_cmds[] = {
    {"bench-teacher", cmd_bench_teacher, "teacher ms per 144-tree stand at N = 48 and 384"},
    {"version", cmd_version, "print the version"},
};
#define NCMDS (sizeof cli_cmds / sizeof cli_cmds[0])

static void usage(FILE *f)
{
    fprintf(f, "usage: crownshy <command> [options]   (crownshy <command> --help)\n\ncommands:\n");
    for (size_t i = 0; i < NCMDS; i++) fprintf(f, "  %-16s %s\n", cli_cmds[i].name, cli_cmds[i].help);
    fprintf(f, "\nexit codes: 0 ok, 1 a gate or claim failed, 2 usage error, 3 bad or missing input\n");
}

int main(int argc, char **argv)
{
    cs_gsl_install();
    if (argc < 2) { usage(stderr); return 2; }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    for (size_t i = 0; i < NCMDS; i++)
        if (!strcmp(argv[1], cli_cmds[i].name)) return cli_cmds[i].fn(argc - 1, argv + 1);
    fprintf(stderr, "crownshy: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
