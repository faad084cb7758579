/* opts: the one option parser of every crownshy command (design.md §11), built on
 * the C library's getopt_long. A command describes its options in a table;
 * the same table parses argv, checks every value strictly and prints --help.
 *  - numbers parse in full (strtol / strtod): an empty, unparsable,
 *    non-finite or out-of-range value is a usage error naming the option;
 *  - unknown options, missing values, a required option left out and a
 *    choice outside its list are usage errors;
 *  - long options only ("--name value" or "--name=value"), plus -h.
 * Library code: prints the help to stdout and errors to stderr, never exits;
 * the caller returns the exit code (0 after --help, 2 on a usage error). */
#ifndef OPTS_H
#define OPTS_H
#include <stddef.h>

typedef enum { OPT_STR, OPT_LONG, OPT_DOUBLE, OPT_FLAG, OPT_CHOICE } opt_type;

typedef struct {
    const char *name;  /* long name without "--" */
    opt_type type;
    void *dst;         /* const char ** (string, choice), long *, double *, or int * (flag: set to 1) */
    double min, max;   /* inclusive range of a number (ignored for strings, flags) */
    const char *help;  /* one line: what it is, its default */
    int required;      /* a usage error when absent; --help says "(required)" */
    /* OPT_CHOICE: the accepted words, NULL-terminated; "alias=word" accepts
     * alias and stores word (the entry "word" of the same list). --help
     * prints the words and their aliases. */
    const char *const *choices;
} opt_spec;

typedef struct {
    const char *cmd;       /* "main-run" */
    const char *synopsis;  /* after "usage: crownshy CMD ", e.g. "--seed S --arm joint|indep [options]" */
    const char *about;     /* paragraph printed under the usage line (may be NULL) */
    const opt_spec *opts;
    size_t nopts;
    int min_pos, max_pos;  /* positional arguments allowed (max_pos < 0: any number) */
} opts_cmd;

#define OPTS_OK 0
#define OPTS_HELP 1
#define OPTS_USAGE 2

/* Parse argv (argv[0] is the command name; argv itself is left in its order,
 * so a provenance line can still quote it). The positional arguments are
 * stored in pos[0 .. *npos-1]: pos must hold argc entries, or be NULL when the
 * command takes none (max_pos 0; npos may then be NULL too).
 * Returns OPTS_OK, OPTS_HELP (help printed) or OPTS_USAGE (error printed). */
int opts_parse(const opts_cmd *c, int argc, char **argv, char **pos, int *npos);
/* Exit code for a parse result: OPTS_HELP -> 0, OPTS_USAGE -> 2. */
int opts_exit_code(int parse_result);
/* The one usage-error printer: "crownshy CMD: message (see crownshy CMD --help)". */
void opts_usage_error(const char *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Print the help generated from the table to stdout. */
void opts_help(const opts_cmd *c);

#endif
