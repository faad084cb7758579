/* args: see args.h. */
#include "args.h"
#include <stdio.h>
#include <string.h>

int args_help(int argc, char **argv, const char *usage)
{
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(usage, stdout);
            if (usage[0] && usage[strlen(usage) - 1] != '\n') fputc('\n', stdout);
            return 1;
        }
    return 0;
}

const char *args_value(int argc, char **argv, const char *name, const char *def)
{
    for (int i = 1; i + 1 < argc; i++)
        if (!strcmp(argv[i], name)) return argv[i + 1];
    return def;
}

int args_check(const char *cmd, int argc, char **argv, const char *const *known)
{
    for (int i = 1; i < argc; i += 2) {
        int ok = 0;
        for (int k = 0; known[k] && !ok; k++) ok = !strcmp(argv[i], known[k]);
        if (!ok) { fprintf(stderr, "crownshy %s: unknown option '%s'\n", cmd, argv[i]); return 2; }
        if (i + 1 >= argc) { fprintf(stderr, "crownshy %s: option '%s' needs a value\n", cmd, argv[i]); return 2; }
    }
    return 0;
}
