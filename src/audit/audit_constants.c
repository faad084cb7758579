/* audit_constants: the design constants the hand-written write-up prints
 * (audit/design_numbers.tsv, design.md §9), each checked at the gate key,
 * header or initialiser that fixes it, and paper/constants.tex generated from
 * them, one macro per phrase (shown, or hidden for the audit's render). */
#include "audit_paper.h"
#include "afile.h"
#include "gate.h"
#include "tsv.h"
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Does a line of a source file give NAME the value x: "#define NAME x" at
 * the line's start (define), or an initialiser "NAME = x" anywhere in it? */
static int source_holds(const char *file, const char *name, int define, double x)
{
    FILE *f = fopen(file, "r");
    char l[512], pat[100];
    snprintf(pat, sizeof pat, define ? "#define %s " : "%s = ", name);
    int ok = 0;
    while (f && !ok && fgets(l, sizeof l, f)) {
        const char *m = define ? (strncmp(l, pat, strlen(pat)) ? NULL : l) : strstr(l, pat);
        ok = m && strtod(m + strlen(pat), NULL) == x;
    }
    if (f) fclose(f);
    return ok;
}

/* audit/design_numbers.tsv: macro, value, source, what. A source is
 * "gate FILE:KEY" (a value of the key, or a hundred times it: a percentage),
 * "count FILE:KEY" (how many values the key has), "excess FILE:KEY" (a hundred
 * times the key's value less one: 30 for 1.30), "log10 FILE:KEY" (minus the
 * decimal exponent of the key's value: 6 for 1e-6), "define FILE:NAME" (a
 * #define of a pinned header), "member FILE:NAME" (an initialiser NAME = value
 * of a source file), or "text" (a number that is no quantity of the
 * study: a count in the reference paper's words, an ordinal; its 'what' says
 * which). Each is checked at its source; each macro prints one phrase of the
 * text (design.md §9). */
const design_const *audit_design_find(const design_const *v, size_t n, const char *name)
{
    for (size_t q = 0; q < n; q++) if (!strcmp(v[q].macro, name)) return &v[q];
    return NULL;
}

size_t audit_design_consts(checklist *cl, design_const **out)
{
    tsv *t;
    *out = NULL;
    if (tsv_read(PATHS_DESIGN_NUMBERS, &t)) {
        checklist_add(cl, VERDICT_FAIL, "design numbers", "%s", cs_errmsg());
        return 0;
    }
    design_const *v = calloc(tsv_nrows(t) + 1, sizeof *v);
    size_t n = 0;
    for (size_t r = 0; v && r < tsv_nrows(t); r++) {
        const char *src = tsv_str(t, r, "source"), *what = tsv_str(t, r, "what"), *mac = tsv_str(t, r, "macro"),
                   *val = tsv_str(t, r, "value");
        double x;
        char kind[16] = "", file[200] = "", key[80] = "";
        int line = tsv_line(t, r), ok = 0;
        if (!mac || !isupper((unsigned char)mac[0]) ||
            strspn(mac, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz") != strlen(mac) || strlen(mac) >= 64 ||
            tsv_double(t, r, "value", &x) || !val || strlen(val) >= 32 || !src || !what || !what[0]) {
            checklist_add(
                cl, VERDICT_FAIL, "design numbers",
                "%s:%d: fields 'macro' (letters, capitalised), 'value' (a number), 'source' and 'what' required",
                PATHS_DESIGN_NUMBERS, line);
            continue;
        }
        if (audit_design_find(v, n, mac)) {
            checklist_add(cl, VERDICT_FAIL, "design numbers", "%s:%d: field 'macro': %s appears twice",
                          PATHS_DESIGN_NUMBERS, line, mac);
            continue;
        }
        if (!strcmp(src, "text")) ok = 1;
        else if (sscanf(src, "%15s %199[^:]:%79s", kind, file, key) == 3) {
            double g[64];
            size_t ng = 0;
            char path[300];
            snprintf(path, sizeof path, PATHS_GATES_DIR "/%s", file);
            if (!strcmp(kind, "gate") && !gate_read_values(path, key, g, 64, &ng))
                for (size_t k = 0; k < ng && !ok; k++)
                    ok = fabs(g[k] - x) <= 1e-9 * fmax(1, fabs(x)) || fabs(100 * g[k] - x) <= 1e-9 * fmax(1, fabs(x));
            else if (!strcmp(kind, "count") && !gate_read_values(path, key, g, 64, &ng)) ok = (double)ng == x;
            else if (!strcmp(kind, "log10") && !gate_read_values(path, key, g, 64, &ng))
                ok = ng == 1 && g[0] > 0 && fabs(-log10(g[0]) - x) <= 1e-9;
            else if (!strcmp(kind, "excess") && !gate_read_values(path, key, g, 64, &ng))
                ok = ng == 1 && fabs(100 * (g[0] - 1) - x) <= 1e-9 * fmax(1, fabs(x));
            else if (!strcmp(kind, "member")) ok = source_holds(file, key, 0, x);
            else if (!strcmp(kind, "define")) ok = source_holds(file, key, 1, x);
        }
        if (!ok) {
            checklist_add(cl, VERDICT_FAIL, "design numbers", "%s:%d: %s = %g is not what its source '%s' holds",
                          PATHS_DESIGN_NUMBERS, line, mac, x, src);
            continue;
        }
        snprintf(v[n].macro, sizeof v[n].macro, "%s", mac);
        snprintf(v[n].value, sizeof v[n].value, "%s", val);
        v[n++].line = line;
    }
    tsv_free(t);
    *out = v;
    return n;
}

cs_status audit_write_constants(const char *path, int hide)
{
    checklist cl = {0};
    design_const *d;
    size_t n = audit_design_consts(&cl, &d);
    cs_status st = CS_OK;
    for (size_t i = 0; i < cl.n && !st; i++)
        if (cl.items[i].v == VERDICT_FAIL) st = cs_err(CS_EINPUT, "%s", cl.items[i].msg);
    checklist_free(&cl);
    afile a;
    if (!st && !d) st = cs_err(CS_ENOMEM, "out of memory");
    if (!st) st = afile_open(&a, path);
    if (st) { free(d); return st; }
    fprintf(a.f, "%% paper/constants.tex: GENERATED by `crownshy numbers` from " PATHS_DESIGN_NUMBERS
                 ", each value checked at its source.\n"
                 "%% The design constants the text prints, one macro per phrase. Never edit by hand.\n");
    for (size_t i = 0; i < n; i++)
        fprintf(a.f, "\\newcommand{\\%s}{%s}\n", d[i].macro, hide ? "\\hiddenvalue{}" : d[i].value);
    free(d);
    return afile_commit(&a);
}
