/* args: the "--name value" helpers shared by the experiment commands
 * (crownshy main-*, comp-run, field-*, aniso-*). Only the CLI layer uses
 * them; they print to stdout/stderr and never exit. The typed option tables
 * of train/sample/bench-model stay in cli.c. */
#ifndef ARGS_H
#define ARGS_H

/* 1 after printing `usage` to stdout when argv holds --help or -h; else 0. */
int args_help(int argc, char **argv, const char *usage);
/* The value after the first `name` in argv[1..], or def when absent. */
const char *args_value(int argc, char **argv, const char *name, const char *def);
/* 0 if argv[1..] is a sequence of "name value" pairs with every name in the
 * NULL-terminated `known`; otherwise prints "crownshy CMD: ..." naming the
 * offending option and returns 2 (the usage exit code). */
int args_check(const char *cmd, int argc, char **argv, const char *const *known);

#endif
