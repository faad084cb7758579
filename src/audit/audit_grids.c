/* audit_grids: every frozen table's rows against its design grid, checked in
 * tier 1 (design.md §9): a sweep that lost, repeated or gained a point fails,
 * naming the table, the point and the claims it feeds. See audit_grids.h.
 *
 * audit/grids.tsv (pinned) has one row per block of a table's design grid:
 *   table    a frozen table, or a glob of them (frozen/extension-pair-16-stands/main/run_s*_*.tsv)
 *   filter   "col=value;col=value" selecting the block's rows, or "-"
 *   columns  comma-separated key columns
 *   values   one source per column, ';'-separated: "gate FILE:KEY" (the
 *            values of a gate key), "seq FILE:KEY" (1..value), "range
 *            FILE:KEY" (lo hi step), or "list a,b,c" (fixed by the design)
 * A table's rows are exactly the union of its blocks, each block the full
 * product of its columns' values, every combination once. A block has at
 * most GRID_MAXC columns of at most GRID_MAXV values each. */
#include "audit_grids.h"
#include "audit_data.h"
#include "gate.h"
#include "paths.h"
#include "tsv.h"
#include <glob.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GRID_MAXV 64
#define GRID_MAXC 4
typedef struct { char v[GRID_MAXV][48]; size_t n; } grid_axis;

/* The values of one source ("gate F:K", "seq F:K", "range F:K", "list a,b"). */
static cs_status grid_source(const char *src, grid_axis *ax, const char *where)
{
    ax->n = 0;
    if (!strncmp(src, "list ", 5)) {
        char buf[1024];
        snprintf(buf, sizeof buf, "%s", src + 5);
        for (char *s = NULL, *t = strtok_r(buf, ",", &s); t; t = strtok_r(NULL, ",", &s)) {
            if (ax->n == GRID_MAXV)
                return cs_err(CS_EINPUT, "%s: field 'values': more than %d values in a list", where, GRID_MAXV);
            snprintf(ax->v[ax->n++], 48, "%s", t);
        }
        return ax->n ? CS_OK : cs_err(CS_EINPUT, "%s: field 'values': empty list", where);
    }
    char kind[8], file[128], key[64];
    if (sscanf(src, "%7s %127[^:]:%63s", kind, file, key) != 3)
        return cs_err(CS_EINPUT, "%s: field 'values': '%s' is not 'gate|seq|range FILE:KEY' or 'list a,b'", where, src);
    char path[300];
    snprintf(path, sizeof path, PATHS_GATES_DIR "/%s", file);
    double v[GRID_MAXV];
    size_t n;
    cs_status st = gate_read_values(path, key, v, GRID_MAXV, &n);
    if (st) return st;
    if (!strcmp(kind, "gate")) for (size_t i = 0; i < n; i++) snprintf(ax->v[ax->n++], 48, "%.17g", v[i]);
    else if (!strcmp(kind, "seq") && n == 1 && v[0] >= 1 && v[0] <= GRID_MAXV)
        for (int i = 1; i <= (int)v[0]; i++) snprintf(ax->v[ax->n++], 48, "%d", i);
    else if (!strcmp(kind, "range") && n == 3 && v[2] > 0) {
        long m = lround((v[1] - v[0]) / v[2]);
        if (m < 0 || m >= GRID_MAXV)
            return cs_err(CS_EINPUT, "%s: field 'values': '%s' spans %ld values (1..%d)", where, src, m + 1, GRID_MAXV);
        for (long i = 0; i <= m; i++) snprintf(ax->v[ax->n++], 48, "%.17g", v[0] + (double)i * v[2]);
    } else return cs_err(CS_EINPUT, "%s: field 'values': '%s' does not fit %s:%s", where, src, file, key);
    return CS_OK;
}

/* Same grid value: numerically when both are numbers, else as text. */
static int grid_same(const char *a, const char *b)
{
    char *ea, *eb;
    double x = strtod(a, &ea), y = strtod(b, &eb);
    if (ea != a && !*ea && eb != b && !*eb) return fabs(x - y) <= 1e-9 * fmax(1.0, fabs(x));
    return !strcmp(a, b);
}

static int grid_filter_keeps(const tsv *t, size_t r, const char *filter)
{
    if (!strcmp(filter, "-")) return 1;
    char f[256];
    snprintf(f, sizeof f, "%s", filter);
    for (char *s = NULL, *tok = strtok_r(f, ";", &s); tok; tok = strtok_r(NULL, ";", &s)) {
        char *eq = strchr(tok, '=');
        if (!eq) return 0;
        *eq = '\0';
        const char *v = tsv_str(t, r, tok);
        if (!v || !grid_same(v, eq + 1)) return 0;
    }
    return 1;
}

/* One block of one table: FAIL items for a missing, repeated or extra row;
 * covered[r] marks the rows the block owns. Returns the failures. */
static size_t grid_block(const claims *c, const tsv *t, const char *filter, const char *cols, const char *vals,
                         int gline, char *covered, checklist *cl)
{
    char where[128], names[GRID_MAXC][64], cbuf[256], vbuf[1024], affected[600];
    snprintf(where, sizeof where, PATHS_GRIDS ":%d", gline);
    audit_feeds(c, tsv_path(t), affected, sizeof affected);
    static grid_axis ax[GRID_MAXC];
    size_t nc = 0;
    snprintf(cbuf, sizeof cbuf, "%s", cols);
    snprintf(vbuf, sizeof vbuf, "%s", vals);
    char *s1 = NULL, *s2 = NULL, *cn = strtok_r(cbuf, ",", &s1), *vs = strtok_r(vbuf, ";", &s2);
    for (; cn && vs && nc < GRID_MAXC; nc++, cn = strtok_r(NULL, ",", &s1), vs = strtok_r(NULL, ";", &s2)) {
        snprintf(names[nc], 64, "%s", cn);
        if (grid_source(vs, &ax[nc], where)) {
            checklist_add(cl, VERDICT_FAIL, "design grids", "%s", cs_errmsg());
            return 1;
        }
    }
    if (!nc || cn || vs) {
        checklist_add(cl, VERDICT_FAIL, "design grids",
                      "%s: fields 'columns'/'values': one source per column (at most %d)", where, GRID_MAXC);
        return 1;
    }
    size_t total = 1, bad = 0;
    for (size_t k = 0; k < nc; k++) total *= ax[k].n;
    int *seen = calloc(total, sizeof *seen), *first = calloc(total, sizeof *first);
    for (size_t r = 0; seen && first && r < tsv_nrows(t); r++) {
        if (!grid_filter_keeps(t, r, filter)) continue;
        size_t idx = 0, k = 0;
        for (; k < nc; k++) {
            const char *v = tsv_str(t, r, names[k]);
            size_t j = 0;
            while (v && j < ax[k].n && !grid_same(v, ax[k].v[j])) j++;
            if (!v || j == ax[k].n) break;
            idx = idx * ax[k].n + j;
        }
        covered[r] = 1;
        if (k < nc) {
            const char *v = tsv_str(t, r, names[k]);
            checklist_add(cl, VERDICT_FAIL, "design grids",
                          "%s:%d: field '%s' = %s is not in its design grid (%s); claims affected: %s", tsv_path(t),
                          tsv_line(t, r), names[k], v ? v : "(missing)", where, affected);
            bad++;
        } else if (seen[idx]++) {
            checklist_add(cl, VERDICT_FAIL, "design grids",
                          "%s:%d repeats the grid point of line %d (%s: one row per point); claims affected: %s",
                          tsv_path(t), tsv_line(t, r), first[idx], where, affected);
            bad++;
        } else first[idx] = tsv_line(t, r);
    }
    for (size_t i = 0; seen && i < total; i++) {
        if (seen[i]) continue;
        char pt[256] = "";
        size_t o = 0, rem = i, div = total;
        for (size_t k = 0; k < nc; k++) {
            div /= ax[k].n;
            o += (size_t)snprintf(pt + o, sizeof pt - o, "%s%s=%s", k ? ", " : "", names[k],
                                  ax[k].v[(rem / div) % ax[k].n]);
        }
        checklist_add(cl, VERDICT_FAIL, "design grids", "%s lacks the grid point %s%s%s (%s); claims affected: %s",
                      tsv_path(t), pt, strcmp(filter, "-") ? " of " : "", strcmp(filter, "-") ? filter : "", where,
                      affected);
        bad++;
    }
    free(seen);
    free(first);
    return bad;
}

/* A FAIL item "FILE:LINE: what; claims affected: ..." naming the claims that
 * read fed (the table at fault, or the pattern no frozen table matched): a
 * broken grid puts those numbers in doubt, whichever file holds the line. */
static void grid_fail_at(const claims *c, checklist *cl, const char *fed, const char *file, int line, const char *fmt,
                         ...) __attribute__((format(printf, 6, 7)));
static void grid_fail_at(const claims *c, checklist *cl, const char *fed, const char *file, int line, const char *fmt,
                         ...)
{
    /* what no longer than an item's message, so the item is cut where one checklist_add would cut it */
    char what[sizeof cl->items[0].msg], affected[600];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    audit_feeds(c, fed, affected, sizeof affected);
    checklist_add(cl, VERDICT_FAIL, "design grids", "%s:%d: %s; claims affected: %s", file, line, what, affected);
}

static size_t grid_table(const claims *c, const char *path, const tsv *spec, const char *pattern, checklist *cl)
{
    tsv *t;
    if (tsv_read(path, &t)) { checklist_add(cl, VERDICT_FAIL, "design grids", "%s", cs_errmsg()); return 1; }
    char *covered = calloc(tsv_nrows(t) + 1, 1);
    size_t bad = 0;
    for (size_t r = 0; covered && r < tsv_nrows(spec); r++) {
        if (strcmp(tsv_str(spec, r, "table"), pattern)) continue;
        bad += grid_block(c, t, tsv_str(spec, r, "filter"), tsv_str(spec, r, "columns"), tsv_str(spec, r, "values"),
                          tsv_line(spec, r), covered, cl);
    }
    for (size_t r = 0; covered && r < tsv_nrows(t); r++)
        if (!covered[r]) {
            grid_fail_at(c, cl, path, path, tsv_line(t, r), "a row outside every block of its design grid (%s)",
                         PATHS_GRIDS);
            bad++;
        }
    free(covered);
    tsv_free(t);
    return bad;
}

void audit_grids(const claims *c, checklist *cl)
{
    tsv *spec;
    if (tsv_read(PATHS_GRIDS, &spec)) { checklist_add(cl, VERDICT_FAIL, "design grids", "%s", cs_errmsg()); return; }
    const char *need[] = {"table", "filter", "columns", "values"};
    for (int k = 0; k < 4; k++)
        if (tsv_col(spec, need[k]) < 0) {
            checklist_add(cl, VERDICT_FAIL, "design grids", "%s: no column '%s'", PATHS_GRIDS, need[k]);
            tsv_free(spec);
            return;
        }
    size_t bad = 0, tables = 0;
    for (size_t r = 0; r < tsv_nrows(spec); r++) {
        const char *pat = tsv_str(spec, r, "table");
        int again = 0;
        for (size_t q = 0; q < r && !again; q++) again = !strcmp(tsv_str(spec, q, "table"), pat);
        if (again) continue;
        glob_t g;
        if (strncmp(pat, PATHS_FROZEN_DIR "/", strlen(PATHS_FROZEN_DIR) + 1) || glob(pat, 0, NULL, &g) != 0) {
            grid_fail_at(c, cl, pat, PATHS_GRIDS, tsv_line(spec, r), "field 'table': no frozen table matches %s", pat);
            bad++;
            continue;
        }
        for (size_t i = 0; i < g.gl_pathc; i++, tables++) bad += grid_table(c, g.gl_pathv[i], spec, pat, cl);
        globfree(&g);
    }
    tsv_free(spec);
    if (!bad)
        checklist_add(cl, VERDICT_PASS, "design grids",
                      "%zu frozen tables hold exactly the rows of their design grids (%s)", tables, PATHS_GRIDS);
}
