/* opts: see opts.h. getopt_long does the scanning (permuting positional
 * arguments to the end, "--name=value", "--" ends options); the strict value
 * checks and the messages are ours, one printer for every command. */
#include "opts.h"
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define OPTS_MAX 64

void opts_usage_error(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "crownshy %s: ", cmd);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, " (see crownshy %s --help)\n", cmd);
}

int opts_exit_code(int r) { return r == OPTS_USAGE ? 2 : 0; }

static const char *metavar(opt_type t)
{
    return t == OPT_LONG ? "N" : t == OPT_DOUBLE ? "X" : t == OPT_STR ? "VALUE" : "";
}

/* "a|b|c" for a choice's metavar, "alias = word" pairs for its help. */
static void choice_words(const opt_spec *o, char *words, size_t wn, char *aliases, size_t an)
{
    size_t w = 0, a = 0;
    words[0] = aliases[0] = 0;
    for (const char *const *c = o->choices; c && *c; c++) {
        const char *eq = strchr(*c, '=');
        if (!eq) w += (size_t)snprintf(words + w, w < wn ? wn - w : 0, "%s%s", w ? "|" : "", *c);
        else
            a += (size_t)snprintf(aliases + a, a < an ? an - a : 0, "%s%.*s = %s", a ? ", " : "", (int)(eq - *c), *c,
                                  eq + 1);
    }
}

void opts_help(const opts_cmd *c)
{
    printf("usage: crownshy %s %s\n", c->cmd, c->synopsis ? c->synopsis : "");
    if (c->about && c->about[0]) {
        fputs("\n", stdout);
        fputs(c->about, stdout);
        if (c->about[strlen(c->about) - 1] != '\n') fputc('\n', stdout);
    }
    fputs("\noptions:\n", stdout);
    for (size_t i = 0; i < c->nopts; i++) {
        const opt_spec *o = &c->opts[i];
        char lhs[160], words[128], aliases[128];
        choice_words(o, words, sizeof words, aliases, sizeof aliases);
        snprintf(lhs, sizeof lhs, "--%s%s%s", o->name, o->type == OPT_FLAG ? "" : " ",
                 o->type == OPT_CHOICE ? words : metavar(o->type));
        printf("  %-24s %s", lhs, o->help ? o->help : "");
        if (o->type == OPT_LONG) printf(" [%.0f..%.0f]", o->min, o->max);
        else if (o->type == OPT_DOUBLE) printf(" [%g..%g]", o->min, o->max);
        if (aliases[0]) printf(" (also: %s)", aliases);
        if (o->required) printf(" (required)");
        fputc('\n', stdout);
    }
    printf("  %-24s %s\n", "-h, --help", "print this help");
    printf(
        "\nexit codes: 0 ok, 1 a check failed, 2 usage error, 3 bad or missing input, 4 environment (I/O, memory)\n");
}

/* Strict number parsing: whole string, finite, in range. 0 or OPTS_USAGE. */
static int set_value(const opts_cmd *c, const opt_spec *o, const char *v)
{
    char *end;
    if (o->type == OPT_STR) { *(const char **)o->dst = v; return OPTS_OK; }
    if (o->type == OPT_CHOICE) {
        for (const char *const *c = o->choices; c && *c; c++) {
            const char *eq = strchr(*c, '=');
            size_t k = eq ? (size_t)(eq - *c) : strlen(*c);
            if (strlen(v) != k || strncmp(v, *c, k)) continue;
            if (!eq) { *(const char **)o->dst = *c; return OPTS_OK; }
            for (const char *const *d = o->choices; *d; d++)
                if (!strcmp(*d, eq + 1)) { *(const char **)o->dst = *d; return OPTS_OK; }
        }
        char words[128], aliases[128];
        choice_words(o, words, sizeof words, aliases, sizeof aliases);
        opts_usage_error(c->cmd, "--%s: must be %s, not '%s'", o->name, words, v);
        return OPTS_USAGE;
    }
    if (!v[0]) { opts_usage_error(c->cmd, "--%s: empty value", o->name); return OPTS_USAGE; }
    errno = 0;
    if (o->type == OPT_LONG) {
        long x = strtol(v, &end, 10);
        if (*end || end == v) { opts_usage_error(c->cmd, "--%s: not an integer: '%s'", o->name, v); return OPTS_USAGE; }
        if (errno == ERANGE || (double)x < o->min || (double)x > o->max) {
            opts_usage_error(c->cmd, "--%s: %s is out of range [%.0f, %.0f]", o->name, v, o->min, o->max);
            return OPTS_USAGE;
        }
        *(long *)o->dst = x;
        return OPTS_OK;
    }
    double x = strtod(v, &end);
    if (*end || end == v) { opts_usage_error(c->cmd, "--%s: not a number: '%s'", o->name, v); return OPTS_USAGE; }
    if (errno == ERANGE || !isfinite(x) || x < o->min || x > o->max) {
        opts_usage_error(c->cmd, "--%s: %s is out of range [%g, %g]", o->name, v, o->min, o->max);
        return OPTS_USAGE;
    }
    *(double *)o->dst = x;
    return OPTS_OK;
}

static int scan(const opts_cmd *c, int argc, char **argv, char **pos, int *npos_out)
{
    struct option lo[OPTS_MAX + 2];
    size_t n = c->nopts < OPTS_MAX ? c->nopts : OPTS_MAX;
    for (size_t i = 0; i < n; i++)
        lo[i] = (struct option){c->opts[i].name, c->opts[i].type == OPT_FLAG ? no_argument : required_argument, NULL,
                                (int)(256 + i)};
    lo[n] = (struct option){"help", no_argument, NULL, 'h'};
    lo[n + 1] = (struct option){NULL, 0, NULL, 0};
    /* the scan is global state in the C library: reset it (0 = full reinit in glibc) */
    optind = 0;
    opterr = 0;
    int r = OPTS_OK, ch;
    unsigned char seen[OPTS_MAX] = {0};
    while (r == OPTS_OK && (ch = getopt_long(argc, argv, ":h", lo, NULL)) != -1) {
        if (ch == 'h') { opts_help(c); return OPTS_HELP; }
        if (ch == ':') {
            const char *a = argv[optind - 1];
            opts_usage_error(c->cmd, "option '%s' needs a value", a);
            return OPTS_USAGE;
        }
        if (ch == '?') {
            const char *a = argv[optind - 1];
            if (optopt && optopt < 256) opts_usage_error(c->cmd, "unknown option '-%c'", optopt);
            else opts_usage_error(c->cmd, "unknown option '%s'", a);
            return OPTS_USAGE;
        }
        const opt_spec *o = &c->opts[ch - 256];
        seen[ch - 256] = 1;
        if (o->type == OPT_FLAG) *(int *)o->dst = 1;
        else r = set_value(c, o, optarg);
    }
    if (r) return r;
    for (size_t i = 0; i < n; i++)
        if (c->opts[i].required && !seen[i]) {
            opts_usage_error(c->cmd, "--%s is required", c->opts[i].name);
            return OPTS_USAGE;
        }
    int npos = argc - optind;
    if (npos < c->min_pos || (c->max_pos >= 0 && npos > c->max_pos)) {
        if (npos > 0 && c->max_pos >= 0 && npos > c->max_pos)
            opts_usage_error(c->cmd, "unexpected argument '%s'", argv[optind + c->max_pos]);
        else opts_usage_error(c->cmd, "needs %d argument%s", c->min_pos, c->min_pos == 1 ? "" : "s");
        return OPTS_USAGE;
    }
    for (int i = 0; i < npos && pos; i++) pos[i] = argv[optind + i];
    if (npos_out) *npos_out = npos;
    return OPTS_OK;
}

int opts_parse(const opts_cmd *c, int argc, char **argv, char **pos, int *npos_out)
{
    /* getopt_long permutes what it scans: give it a copy of the pointers */
    char **av = malloc(((size_t)argc + 1) * sizeof *av);
    if (!av) { opts_usage_error(c->cmd, "out of memory"); return OPTS_USAGE; }
    memcpy(av, argv, (size_t)argc * sizeof *av);
    av[argc] = NULL;
    int r = scan(c, argc, av, pos, npos_out);
    free(av);
    return r;
}
