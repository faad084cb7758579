/* audit_data: aggregate frozen tables against the per-run tables they are
 * computed from, the lineage "this per-run table feeds these claims", and
 * the git ledger of pinned files (design.md §9).
 *
 * audit/aggregates.tsv (pinned) has one row per aggregate column:
 *   aggregate   frozen table, e.g. frozen/extension-pair-16-stands/main/runs.tsv
 *   value       its column checked, or "-" (lineage only)
 *   reduce      mean | sum | count | min | max | "-" (lineage only)
 *   parts       the per-run table of one aggregate row: a template whose
 *               {col} is that row's cell and {col:0N} the cell as an integer
 *               zero-padded to N digits, e.g. frozen/extension-pair-16-stands/main/run_s{seed:02}_{arm}.tsv
 *   part_value  the per-run column reduced ("-" for count)
 *   filter      "col=template;col=template" selecting the per-run rows, or "-"
 * Sums run in file order, so a mean is compared bit for bit with the
 * aggregate (the pipeline's own order). */
#include "audit_data.h"
#include "tsv.h"
#include <fnmatch.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static cs_status field(const tsv *t, size_t r, const char *col, char *dst, size_t n)
{
    const char *s = tsv_str(t, r, col);
    if (!s) return cs_err(CS_EINPUT, "%s: field '%s': no such column", tsv_path(t), col);
    if (!s[0] || strlen(s) >= n)
        return cs_err(CS_EINPUT, "%s:%d: field '%s': %s", tsv_path(t), tsv_line(t, r), col,
                      s[0] ? "too long" : "empty");
    strcpy(dst, s);
    return CS_OK;
}

/* Braces balanced, no nesting, names non-empty, width "0N" with N 1..9. */
static int template_ok(const char *s)
{
    for (const char *p = s; *p; p++) {
        if (*p == '}') return 0;
        if (*p != '{') continue;
        const char *e = strchr(p + 1, '}'), *o = strchr(p + 1, '{');
        if (!e || (o && o < e) || e == p + 1 || p[1] == ':') return 0;
        const char *colon = memchr(p + 1, ':', (size_t)(e - p - 1));
        if (colon && !(e - colon == 3 && colon[1] == '0' && colon[2] >= '1' && colon[2] <= '9')) return 0;
        p = e;
    }
    return 1;
}

cs_status aggr_load(const char *path, aggr_spec **out, size_t *n)
{
    *out = NULL;
    *n = 0;
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    size_t m = tsv_nrows(t);
    aggr_spec *a = calloc(m ? m : 1, sizeof *a);
    if (!a) { tsv_free(t); return cs_err(CS_ENOMEM, "%s: out of memory", path); }
    for (size_t r = 0; r < m && !st; r++) {
        aggr_spec *w = &a[r];
        w->line = tsv_line(t, r);
        if ((st = field(t, r, "aggregate", w->aggregate, sizeof w->aggregate))) break;
        if ((st = field(t, r, "value", w->value, sizeof w->value))) break;
        if ((st = field(t, r, "reduce", w->reduce, sizeof w->reduce))) break;
        if ((st = field(t, r, "parts", w->parts, sizeof w->parts))) break;
        if ((st = field(t, r, "part_value", w->part_value, sizeof w->part_value))) break;
        if ((st = field(t, r, "filter", w->filter, sizeof w->filter))) break;
        const char *red[] = {"mean", "sum", "count", "min", "max", "-"};
        int ok = 0;
        for (int k = 0; k < 6; k++) ok |= !strcmp(w->reduce, red[k]);
        if (!ok) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'reduce': '%s' (mean, sum, count, min, max or -)", path, w->line,
                        w->reduce);
            break;
        }
        if (strncmp(w->aggregate, PATHS_FROZEN_DIR "/", strlen(PATHS_FROZEN_DIR) + 1) ||
            strncmp(w->parts, PATHS_FROZEN_DIR "/", strlen(PATHS_FROZEN_DIR) + 1)) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'aggregate'/'parts': both must be under %s/", path, w->line,
                        PATHS_FROZEN_DIR);
            break;
        }
        if (!template_ok(w->parts) || (strcmp(w->filter, "-") && !template_ok(w->filter))) {
            st = cs_err(CS_EINPUT, "%s:%d: field '%s': malformed {column} or {column:0N} template", path, w->line,
                        template_ok(w->parts) ? "filter" : "parts");
            break;
        }
        int lineage = !strcmp(w->reduce, "-");
        if (lineage != !strcmp(w->value, "-") ||
            (!lineage && strcmp(w->reduce, "count") && !strcmp(w->part_value, "-"))) {
            st = cs_err(CS_EINPUT,
                        "%s:%d: field 'value': reduce '-' (lineage) goes with value '-'; a reduce other than count "
                        "needs a part_value",
                        path, w->line);
            break;
        }
        if (strcmp(w->filter, "-")) {
            char f[sizeof w->filter];
            strcpy(f, w->filter);
            for (char *save = NULL, *tok = strtok_r(f, ";", &save); tok; tok = strtok_r(NULL, ";", &save))
                if (!strchr(tok, '=') || tok[0] == '=') {
                    st = cs_err(CS_EINPUT, "%s:%d: field 'filter': '%s' is not column=template", path, w->line, tok);
                    break;
                }
        }
    }
    tsv_free(t);
    if (st) { free(a); return st; }
    *out = a;
    *n = m;
    return CS_OK;
}

/* Expand a template with row r of t; 0 on success, else err names the problem. */
static int expand(const char *tpl, const tsv *t, size_t r, char *out, size_t n, char *err, size_t en)
{
    size_t o = 0;
    for (const char *p = tpl; *p; p++) {
        if (*p != '{') { if (o + 1 < n) out[o++] = *p; continue; }
        const char *e = strchr(p, '}');
        char name[64];
        int width = 0;
        snprintf(name, sizeof name, "%.*s", (int)(e - p - 1), p + 1);
        char *colon = strchr(name, ':');
        if (colon) { width = colon[2] - '0'; *colon = '\0'; }
        const char *v = tsv_str(t, r, name);
        if (!v) { snprintf(err, en, "no column '%s'", name); return 1; }
        char buf[128];
        if (width) {
            char *end;
            long x = strtol(v, &end, 10);
            if (end == v || *end) { snprintf(err, en, "field '%s': '%s' is not an integer", name, v); return 1; }
            snprintf(buf, sizeof buf, "%0*ld", width, x);
            v = buf;
        }
        o += (size_t)snprintf(out + o, o < n ? n - o : 0, "%s", v);
        if (o >= n) { snprintf(err, en, "expansion too long"); return 1; }
        p = e;
    }
    out[o < n ? o : n - 1] = '\0';
    return 0;
}

/* Reduce the part rows of one aggregate row; 0 on success. */
static int reduce_part(const aggr_spec *s, const tsv *agg, size_t r, double *out, char *part, size_t pn, char *err,
                       size_t en)
{
    if (expand(s->parts, agg, r, part, pn, err, en)) return 1;
    char filt[512] = "";
    if (strcmp(s->filter, "-") && expand(s->filter, agg, r, filt, sizeof filt, err, en)) return 1;
    tsv *t;
    if (tsv_read(part, &t)) { snprintf(err, en, "%s", cs_errmsg()); return 1; }
    double acc = 0;
    size_t cnt = 0;
    int bad = 0;
    for (size_t q = 0; q < tsv_nrows(t) && !bad; q++) {
        int keep = 1;
        char f[512];
        strcpy(f, filt);
        for (char *save = NULL, *tok = filt[0] ? strtok_r(f, ";", &save) : NULL; tok && keep;
             tok = strtok_r(NULL, ";", &save)) {
            char *eq = strchr(tok, '=');
            *eq = '\0';
            const char *v = tsv_str(t, q, tok);
            if (!v) { snprintf(err, en, "%s: no column '%s'", part, tok); bad = 1; break; }
            keep = !strcmp(v, eq + 1);
        }
        if (bad || !keep) continue;
        double x = 0;
        if (strcmp(s->reduce, "count") && tsv_double_nf(t, q, s->part_value, &x)) {
            snprintf(err, en, "%s", cs_errmsg());
            bad = 1;
            break;
        }
        if (!strcmp(s->reduce, "min")) acc = cnt ? fmin(acc, x) : x;
        else if (!strcmp(s->reduce, "max")) acc = cnt ? fmax(acc, x) : x;
        else acc += x;
        cnt++;
    }
    tsv_free(t);
    if (bad) return 1;
    if (!cnt && strcmp(s->reduce, "count")) { snprintf(err, en, "%s: no row matches '%s'", part, filt); return 1; }
    *out = !strcmp(s->reduce, "count") ? (double)cnt : !strcmp(s->reduce, "mean") ? acc / (double)cnt : acc;
    return 0;
}

void audit_aggregates(const claims *c, checklist *cl)
{
    aggr_spec *s;
    size_t n;
    if (aggr_load(PATHS_AGGREGATES, &s, &n)) {
        checklist_add(cl, VERDICT_FAIL, "aggregates", "%s", cs_errmsg());
        return;
    }
    size_t checked = 0, bad = 0;
    for (size_t i = 0; i < n; i++) {
        char affected[600], name[96];
        audit_feeds(c, s[i].aggregate, affected, sizeof affected);
        snprintf(name, sizeof name, "aggregate %.80s", s[i].aggregate);
        tsv *agg;
        /* a generator reading's summary not made yet (design.md §8): its
         * claims read the per-run tables; once frozen it is checked here */
        if (claims_awaited_source(s[i].aggregate) && access(s[i].aggregate, F_OK) != 0) continue;
        if (tsv_read(s[i].aggregate, &agg)) {
            checklist_add(cl, VERDICT_FAIL, name, "%s (registered in %s:%d); claims affected: %s", cs_errmsg(),
                          PATHS_AGGREGATES, s[i].line, affected);
            bad++;
            continue;
        }
        for (size_t r = 0; r < tsv_nrows(agg); r++) {
            char part[600], err[700];
            double want, have;
            if (!strcmp(s[i].reduce, "-")) {
                /* lineage only: the part must exist */
                struct stat sb;
                if (expand(s[i].parts, agg, r, part, sizeof part, err, sizeof err) == 0 && stat(part, &sb) != 0) {
                    checklist_add(cl, VERDICT_FAIL, name, "%s:%d: its per-run table %s is missing; claims affected: %s",
                                  s[i].aggregate, tsv_line(agg, r), part, affected);
                    bad++;
                }
                continue;
            }
            if (reduce_part(&s[i], agg, r, &want, part, sizeof part, err, sizeof err) ||
                tsv_double_nf(agg, r, s[i].value, &have)) {
                if (!err[0]) snprintf(err, sizeof err, "%s", cs_errmsg());
                checklist_add(cl, VERDICT_FAIL, name,
                              "%s:%d: field '%s' cannot be checked against its per-run table: %s; claims affected: %s",
                              s[i].aggregate, tsv_line(agg, r), s[i].value, err, affected);
                bad++;
                continue;
            }
            checked++;
            if (!(want == have || (isnan(want) && isnan(have)))) {
                checklist_add(cl, VERDICT_FAIL, name,
                              "%s:%d: field '%s' = %.17g but the %s of '%s' over %s%s%s is %.17g (aggregate and "
                              "per-run tables disagree); claims affected: %s",
                              s[i].aggregate, tsv_line(agg, r), s[i].value, have, s[i].reduce, s[i].part_value, part,
                              strcmp(s[i].filter, "-") ? " rows " : "", strcmp(s[i].filter, "-") ? s[i].filter : "",
                              want, affected);
                bad++;
            }
        }
        tsv_free(agg);
    }
    if (!bad)
        checklist_add(cl, VERDICT_PASS, "aggregates",
                      "%zu aggregate cells equal the reduction of their per-run tables (%s, %zu rules)", checked,
                      PATHS_AGGREGATES, n);
    free(s);
}

/* The claims a file feeds: its own (source column) or, for a per-run table,
 * those of the aggregates made from it (audit/aggregates.tsv lineage). */
/* A parts template as a glob: every {col} or {col:0N} cell becomes '*'.
 * glob holds at least strlen(parts) + 1 bytes. */
static void parts_glob(const char *parts, char *glob)
{
    size_t o = 0;
    for (const char *p = parts; *p; p++) {
        if (*p == '{') { glob[o++] = '*'; p = strchr(p, '}'); if (!p) break; }
        else glob[o++] = *p;
    }
    glob[o] = '\0';
}

void audit_feeds(const claims *c, const char *path, char *buf, size_t n)
{
    size_t off = 0, cnt = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < c->n && off < n; i++)
        if (!strcmp(c->rows[i].source, path) ||
            (strchr(c->rows[i].source, '*') && fnmatch(c->rows[i].source, path, FNM_PATHNAME) == 0))
            off += (size_t)snprintf(buf + off, n - off, "%s%s", cnt++ ? ", " : "", c->rows[i].macro);
    if (cnt) return;
    aggr_spec *s;
    size_t m;
    if (!aggr_load(PATHS_AGGREGATES, &s, &m)) {
        for (size_t k = 0; k < m && !cnt; k++) {
            char glob[sizeof s[k].parts];
            parts_glob(s[k].parts, glob);
            if (fnmatch(glob, path, FNM_PATHNAME) != 0 || !strcmp(s[k].aggregate, path)) continue;
            for (size_t i = 0; i < c->n && off < n; i++)
                if (!strcmp(c->rows[i].source, s[k].aggregate))
                    off += (size_t)snprintf(buf + off, n - off, "%s%s", cnt++ ? ", " : "", c->rows[i].macro);
            if (cnt && off < n) snprintf(buf + off, n - off, " (via %s)", s[k].aggregate);
            else if (!strncmp(s[k].aggregate, PATHS_READINGS_DIR "/", strlen(PATHS_READINGS_DIR) + 1)) {
                snprintf(buf, n, "the readings table %s (via %s)", PATHS_READINGS_TEX, s[k].aggregate);
                cnt = 1;
            }
        }
        free(s);
    }
    /* An aggregate the claims do not read (a reading's runs.tsv beside the
     * unit set the claims read) names the claims its parts feed. */
    if (!cnt && !aggr_load(PATHS_AGGREGATES, &s, &m)) {
        for (size_t k = 0; k < m && !cnt; k++) {
            if (strcmp(s[k].aggregate, path)) continue;
            char glob[sizeof s[k].parts];
            parts_glob(s[k].parts, glob);
            for (size_t i = 0; i < c->n && off < n; i++)
                if (!strcmp(c->rows[i].source, glob) || fnmatch(glob, c->rows[i].source, FNM_PATHNAME) == 0)
                    off += (size_t)snprintf(buf + off, n - off, "%s%s", cnt++ ? ", " : "", c->rows[i].macro);
            if (cnt && off < n) snprintf(buf + off, n - off, " (via its parts %s)", glob);
        }
        free(s);
    }
    if (!cnt && !strncmp(path, PATHS_READINGS_DIR "/", strlen(PATHS_READINGS_DIR) + 1)) {
        snprintf(buf, n, "the readings table %s", PATHS_READINGS_TEX);
        cnt = 1;
    }
    if (!cnt && !strncmp(path, PATHS_SENS_DIR "/", strlen(PATHS_SENS_DIR) + 1)) {
        snprintf(buf, n, "the sensitivity table %s", PATHS_SENS_TEX);
        cnt = 1;
    }
    if (!cnt) snprintf(buf, n, "(no claim)");
}

/* ---- the git ledger ---- */
int audit_run_line(const char *cmd, char *out, size_t n)
{
    FILE *p = popen(cmd, "r");
    if (!p) return 1;
    out[0] = '\0';
    char line[512];
    while (fgets(line, sizeof line, p)) { line[strcspn(line, "\n")] = '\0'; if (line[0]) snprintf(out, n, "%s", line); }
    return pclose(p) != 0 || !out[0];
}

/* The preregistration commit pinned in audit/gates_prereg.sha256 (full hex). */
static int pinned_prereg_commit(char *out, size_t n)
{
    FILE *f = fopen(PATHS_GATES_PREREG, "r");
    char line[256], commit[64] = "";
    while (f && fgets(line, sizeof line, f) && line[0] == '#')
        if (sscanf(line, "# preregistration_commit: %63s", commit) == 1) break;
    if (f) fclose(f);
    if (!commit[0] || strspn(commit, "0123456789abcdef") != strlen(commit)) return 1;
    snprintf(out, n, "%s", commit);
    return 0;
}

int audit_prereg_state(char *out, size_t n)
{
    char commit[64], cmd[200];
    out[0] = '\0';
    struct stat sb;
    if (stat(".git", &sb) != 0 || system("git rev-parse --git-dir >/dev/null 2>&1") != 0) return PREREG_NO_GIT;
    if (pinned_prereg_commit(commit, sizeof commit)) return PREREG_UNPINNED;
    snprintf(out, n, "%.12s", commit);
    /* git replace is ignored (GIT_NO_REPLACE_OBJECTS, set by verify) */
    snprintf(cmd, sizeof cmd, "git cat-file -e '%s^{commit}' 2>/dev/null", commit);
    if (system(cmd) != 0) return PREREG_ABSENT;
    snprintf(cmd, sizeof cmd, "git merge-base --is-ancestor '%s' HEAD 2>/dev/null", commit);
    return system(cmd) == 0 ? PREREG_ANCESTOR : PREREG_NOT_ANCESTOR;
}

int audit_prereg_commit(char *out, size_t n)
{
    return audit_prereg_state(out, n) != PREREG_ANCESTOR;
}

void audit_ledger(FILE *o)
{
    struct stat sb;
    char base[64], head[64];
    if (stat(".git", &sb) != 0 || audit_run_line("git rev-parse --short=12 HEAD 2>/dev/null", head, sizeof head)) {
        fprintf(o, "  (no .git here: the ledger of pinned files needs the repository's history)\n");
        return;
    }
    /* the preregistration commit pinned in audit/gates_prereg.sha256, an ancestor of HEAD */
    if (audit_prereg_commit(base, sizeof base)) {
        fprintf(o, "  (the pinned preregistration commit is not an ancestor of HEAD in this history: shallow clone, or "
                   "a rewritten history)\n");
        return;
    }
    tsv *t;
    if (tsv_read(PATHS_PINS, &t)) { fprintf(o, "  (%s unreadable: %s)\n", PATHS_PINS, cs_errmsg()); return; }
    size_t shown = 0, pinned = 0;
    char seen[4096] = "";
    for (size_t r = 0; r < tsv_nrows(t); r++) {
        const char *p = tsv_str(t, r, "path");
        if (!p) continue;
        char path[300];
        snprintf(path, sizeof path, "%.*s", (int)strcspn(p, ":"), p);
        char key[310];
        snprintf(key, sizeof key, "|%s|", path);
        if (strstr(seen, key) || strchr(path, '\'')) continue;
        if (strlen(seen) + strlen(key) < sizeof seen) strcat(seen, key);
        pinned++;
        char cmd[900], n_commits[32], dirty[8];
        snprintf(cmd, sizeof cmd, "git rev-list --count %s..HEAD -- '%s' 2>/dev/null", base, path);
        if (audit_run_line(cmd, n_commits, sizeof n_commits)) snprintf(n_commits, sizeof n_commits, "?");
        snprintf(cmd, sizeof cmd, "git status --porcelain -- '%s' 2>/dev/null | head -c 2", path);
        int uncommitted = !audit_run_line(cmd, dirty, sizeof dirty);
        if (!strcmp(n_commits, "0") && !uncommitted) continue;
        char last[700] = "";
        snprintf(cmd, sizeof cmd,
                 "git log -1 --format='%%h %%ad %%s' --date=short %s..HEAD -- '%s' 2>/dev/null | cut -c1-110", base,
                 path);
        audit_run_line(cmd, last, sizeof last);
        fprintf(o, "  %-34s %s commit(s) since %s%s%s%s\n", path, n_commits, base,
                uncommitted ? ", uncommitted changes" : "", last[0] ? "; last: " : "", last);
        shown++;
    }
    tsv_free(t);
    fprintf(o, "  %zu of %zu pinned paths changed after %s (the commit that added the preregistered gates; HEAD %s)\n",
            shown, pinned, base, head);
}
