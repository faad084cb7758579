/* crownshy: the one command-line entry point. Only this file decides how the
 * process dies; library calls return a cs_status (SPEC §11 exit codes). */
#include "cs.h"
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

static const cli_cmd cli_cmds[] = {
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
