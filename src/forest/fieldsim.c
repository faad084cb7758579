/* fieldsim: simulated field statistics per interior tree (design.md §7 E5, E6;
 * reference paper §5.3, §5.4). See fieldsim.h. */
#include "fieldsim.h"
#include "crown.h"
#include "estimator.h"
#include "gate.h"
#include "paths.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void fs_trees_init(fs_trees *t) { memset(t, 0, sizeof *t); }

void fs_trees_free(fs_trees *t)
{
    free(t->coupled); free(t->level); free(t->stand); free(t->tree); free(t->gap); free(t->elong); free(t->elong_card);
    memset(t, 0, sizeof *t);
}

static cs_status fs_reserve(fs_trees *t, size_t want)
{
    if (want <= t->cap) return CS_OK;
    size_t cap = t->cap ? t->cap : 256;
    while (cap < want) cap *= 2;
    int *c = realloc(t->coupled, cap * sizeof *c);
    if (c) t->coupled = c;
    double *l = realloc(t->level, cap * sizeof *l);
    if (l) t->level = l;
    unsigned *s = realloc(t->stand, cap * sizeof *s);
    if (s) t->stand = s;
    unsigned *tr = realloc(t->tree, cap * sizeof *tr);
    if (tr) t->tree = tr;
    double (*g)[4] = realloc(t->gap, cap * sizeof *g);
    if (g) t->gap = g;
    double *e = realloc(t->elong, cap * sizeof *e);
    if (e) t->elong = e;
    double *ec = realloc(t->elong_card, cap * sizeof *ec);
    if (ec) t->elong_card = ec;
    if (!c || !l || !s || !tr || !g || !e || !ec) return cs_err(CS_ENOMEM, "fieldsim: out of memory");
    t->cap = cap;
    return CS_OK;
}

cs_status fs_trees_push(fs_trees *t, int coupled, double level, unsigned stand, unsigned tree, const double gap[4],
                        double elong, double elong_card)
{
    cs_status st = fs_reserve(t, t->n + 1);
    if (st) return st;
    size_t k = t->n++;
    t->coupled[k] = coupled;
    t->level[k] = level;
    t->stand[k] = stand;
    t->tree[k] = tree;
    memcpy(t->gap[k], gap, sizeof t->gap[k]);
    t->elong[k] = elong;
    t->elong_card[k] = elong_card;
    return CS_OK;
}

cs_status fs_group(const fs_trees *t, int coupled, double level, fs_summary *out)
{
    memset(out, 0, sizeof *out);
    size_t n = 0;
    for (size_t k = 0; k < t->n; k++) n += t->coupled[k] == coupled && t->level[k] == level;
    if (n == 0)
        return cs_err(CS_EINPUT, "fieldsim: no trees for arm %s, level %.17g", coupled ? "coupled" : "uncoupled",
                      level);
    double (*g)[4] = malloc(n * sizeof *g);
    double *e = malloc(n * sizeof *e), *ec = malloc(n * sizeof *ec);
    unsigned *st_ids = malloc(n * sizeof *st_ids);
    if (!g || !e || !ec || !st_ids) {
        free(g);
        free(e);
        free(ec);
        free(st_ids);
        return cs_err(CS_ENOMEM, "fieldsim: out of memory");
    }
    size_t m = 0, ns = 0;
    for (size_t k = 0; k < t->n; k++) {
        if (t->coupled[k] != coupled || t->level[k] != level) continue;
        memcpy(g[m], t->gap[k], sizeof g[m]);
        e[m] = t->elong[k];
        ec[m] = t->elong_card[k];
        int seen = 0;
        for (size_t q = 0; q < ns && !seen; q++) seen = st_ids[q] == t->stand[k];
        if (!seen) st_ids[ns++] = t->stand[k];
        m++;
    }
    cs_status st = field_summarize((const double (*)[4])g, n, &out->f);
    if (!st) st = est_median(e, n, &out->elong_median);
    if (!st) st = est_median(ec, n, &out->elong_card_median);
    out->stands = ns;
    free(g); free(e); free(ec); free(st_ids);
    return st;
}

void fs_trees_write(tsv_writer *w, const fs_trees *t)
{
    tsv_writer_columns(w, FS_TREE_COLUMNS);
    for (size_t k = 0; k < t->n; k++) {
        tsv_writer_str(w, t->coupled[k] ? "coupled" : "uncoupled");
        tsv_writer_dbl(w, t->level[k]);
        tsv_writer_long(w, (long)t->stand[k]);
        tsv_writer_long(w, (long)t->tree[k]);
        for (int c = 0; c < 4; c++) tsv_writer_dbl(w, t->gap[k][c]);
        tsv_writer_dbl(w, t->elong[k]);
        tsv_writer_dbl(w, t->elong_card[k]);
        tsv_writer_endrow(w);
    }
}

static cs_status fs_arm(const tsv *t, size_t r, int *coupled)
{
    const char *a = tsv_str(t, r, "arm");
    if (!a) return cs_err(CS_EINPUT, "%s: field 'arm': no such column", tsv_path(t));
    if (!strcmp(a, "coupled")) *coupled = 1;
    else if (!strcmp(a, "uncoupled")) *coupled = 0;
    else return cs_err(CS_EINPUT, "%s:%d: field 'arm': '%s' is not coupled/uncoupled", tsv_path(t), tsv_line(t, r), a);
    return CS_OK;
}

cs_status fs_trees_read(const char *path, fs_trees *out)
{
    fs_trees_init(out);
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    static const char *gcol[4] = {"gap_e", "gap_n", "gap_w", "gap_s"};
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        int coupled;
        double level, g[4], e, ec;
        long s, i;
        if ((st = fs_arm(t, r, &coupled))) break;
        if ((st = tsv_double(t, r, "level", &level))) break;
        if ((st = tsv_long(t, r, "stand", &s))) break;
        if ((st = tsv_long(t, r, "tree", &i))) break;
        for (int c = 0; c < 4 && !st; c++) st = tsv_double(t, r, gcol[c], &g[c]);
        if (!st) st = tsv_double(t, r, "elong", &e);
        if (!st) st = tsv_double(t, r, "elong_card", &ec);
        if (!st && (s < 0 || i < 0))
            st = cs_err(CS_EINPUT, "%s:%d: field 'stand'/'tree': negative", path, tsv_line(t, r));
        if (!st) st = fs_trees_push(out, coupled, level, (unsigned)s, (unsigned)i, g, e, ec);
    }
    tsv_free(t);
    if (st) fs_trees_free(out);
    return st;
}

void fs_summary_write_row(tsv_writer *w, int coupled, double level, double beta, size_t stands_failed,
                          const fs_summary *s)
{
    tsv_writer_str(w, coupled ? "coupled" : "uncoupled");
    tsv_writer_dbl(w, level);
    tsv_writer_dbl(w, beta);
    tsv_writer_long(w, (long)s->stands);
    tsv_writer_long(w, (long)stands_failed);
    tsv_writer_long(w, (long)s->f.trees);
    tsv_writer_dbl(w, s->f.trees ? s->f.tree_mean_median : NAN);
    tsv_writer_dbl(w, s->f.trees ? s->f.spread : NAN);
    tsv_writer_dbl(w, s->f.aniso_trees ? s->f.aniso_median : NAN);
    tsv_writer_long(w, (long)s->f.aniso_trees);
    tsv_writer_long(w, (long)s->f.aniso_excluded);
    tsv_writer_dbl(w, s->f.trees ? s->elong_median : NAN);
    tsv_writer_dbl(w, s->f.trees ? s->elong_card_median : NAN);
    tsv_writer_endrow(w);
}

void fs_trees_path(const char *summary_path, char *out, size_t n)
{
    size_t l = strlen(summary_path);
    if (l > 4 && !strcmp(summary_path + l - 4, ".tsv")) snprintf(out, n, "%.*s_trees.tsv", (int)(l - 4), summary_path);
    else snprintf(out, n, "%s_trees.tsv", summary_path);
}

static cs_status fs_same(const tsv *t, size_t r, const char *col, double want)
{
    double v;
    cs_status st = tsv_double_nf(t, r, col, &v);
    if (st) return st;
    if (!(v == want) && !(isnan(v) && isnan(want)))
        return cs_err(CS_EINPUT,
                      "%s:%d: field '%s': says %.17g but the per-tree table gives %.17g (tampered or inconsistent)",
                      tsv_path(t), tsv_line(t, r), col, v, want);
    return CS_OK;
}

cs_status fs_load_checked(const char *summary_path, tsv **sum, fs_trees *trees)
{
    char tp[600];
    fs_trees_path(summary_path, tp, sizeof tp);
    cs_status st = tsv_read(summary_path, sum);
    if (st) return st;
    if ((st = fs_trees_read(tp, trees))) { tsv_free(*sum); *sum = NULL; return st; }
    for (size_t r = 0; r < tsv_nrows(*sum) && !st; r++) {
        int coupled;
        double level;
        long ntrees;
        if ((st = fs_arm(*sum, r, &coupled))) break;
        if ((st = tsv_double(*sum, r, "level", &level))) break;
        if ((st = tsv_long(*sum, r, "trees", &ntrees))) break;
        if (ntrees == 0) continue;
        fs_summary s;
        if ((st = fs_group(trees, coupled, level, &s))) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'level': %s", summary_path, tsv_line(*sum, r), cs_errmsg());
            break;
        }
        if (!st) st = fs_same(*sum, r, "trees", (double)s.f.trees);
        if (!st) st = fs_same(*sum, r, "stands", (double)s.stands);
        if (!st) st = fs_same(*sum, r, "tree_mean_median", s.f.tree_mean_median);
        if (!st) st = fs_same(*sum, r, "spread", s.f.spread);
        if (!st) st = fs_same(*sum, r, "aniso_median", s.f.aniso_trees ? s.f.aniso_median : NAN);
        if (!st) st = fs_same(*sum, r, "aniso_trees", (double)s.f.aniso_trees);
        if (!st) st = fs_same(*sum, r, "aniso_excluded", (double)s.f.aniso_excluded);
        if (!st) st = fs_same(*sum, r, "elong_median", s.elong_median);
        if (!st) st = fs_same(*sum, r, "elong_card_median", s.elong_card_median);
    }
    if (st) { tsv_free(*sum); *sum = NULL; fs_trees_free(trees); }
    return st;
}

cs_status fs_interp_target(const double *x, const double *y, size_t n, double target, double *xi, int *bracketed)
{
    if (n == 0) return cs_err(CS_EINPUT, "calibration: empty curve");
    for (size_t i = 0; i < n; i++)
        if (!isfinite(x[i]) || !isfinite(y[i])) return cs_err(CS_EINPUT, "calibration: non-finite point %zu", i);
    *bracketed = 0;
    for (size_t i = 0; i < n; i++) {
        if (y[i] == target) { *xi = x[i]; *bracketed = 1; return CS_OK; }
        if (i + 1 < n && (y[i] - target) * (y[i + 1] - target) < 0.0) {
            *xi = x[i] + (target - y[i]) * (x[i + 1] - x[i]) / (y[i + 1] - y[i]);
            *bracketed = 1;
            return CS_OK;
        }
    }
    *xi = fabs(y[0] - target) <= fabs(y[n - 1] - target) ? x[0] : x[n - 1];
    return CS_OK;
}

double fs_round_step(double x, double step)
{
    double k = round(1.0 / step);
    return round(x * k) / k;
}

void fs_fraction_text(double v, char *buf, size_t n)
{
    if (!isfinite(v)) { snprintf(buf, n, "nan"); return; }
    for (long q = 1; q <= 1000; q++) {
        double p = v * (double)q;
        if (fabs(p - round(p)) < 1e-9) {
            long pi = lround(p);
            if (q == 1) snprintf(buf, n, "%ld", pi);
            else snprintf(buf, n, "%ld/%ld", pi, q);
            return;
        }
    }
    snprintf(buf, n, "%.3f", v);
}

static cs_status fs_curve_calibrate(const char *path, const double *x, const double *y, const int *lines, size_t n,
                                    double target, double step, fs_calibration *out)
{
    out->target = target;
    out->step = step;
    out->points = n;
    cs_status st = fs_interp_target(x, y, n, target, &out->interp, &out->bracketed);
    if (st) return cs_err(st, "%s: %s", path, cs_errmsg());
    out->value = fs_round_step(out->interp, step);
    out->line_lo = lines[0];
    for (size_t i = 0; i < n; i++) if (x[i] <= out->interp) out->line_lo = lines[i];
    return CS_OK;
}

cs_status fs_beta_field(const char *calibration_path, fs_calibration *out)
{
    memset(out, 0, sizeof *out);
    double target, step;
    cs_status st = gate_read_value(PATHS_GATE("field"), "calibration_target_m", 0, &target);
    if (!st) st = gate_read_value(PATHS_GATE("field"), "dieback_grid", 2, &step);
    if (st) return st;
    tsv *t;
    fs_trees tr;
    if ((st = fs_load_checked(calibration_path, &t, &tr))) return st;
    size_t n = tsv_nrows(t);
    double *x = malloc((n ? n : 1) * sizeof *x), *y = malloc((n ? n : 1) * sizeof *y);
    int *ln = malloc((n ? n : 1) * sizeof *ln);
    size_t m = 0;
    if (!x || !y || !ln) st = cs_err(CS_ENOMEM, "out of memory");
    for (size_t r = 0; r < n && !st; r++) {
        int coupled;
        if ((st = fs_arm(t, r, &coupled))) break;
        if (!coupled) continue;
        if ((st = tsv_double(t, r, "beta", &x[m]))) break;
        if ((st = tsv_double(t, r, "tree_mean_median", &y[m]))) break;
        if (m && !(x[m] > x[m - 1])) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'beta': grid not ascending", calibration_path, tsv_line(t, r));
            break;
        }
        ln[m++] = tsv_line(t, r);
    }
    if (!st && m < 2) st = cs_err(CS_EINPUT, "%s: fewer than 2 calibration points", calibration_path);
    if (!st) st = fs_curve_calibrate(calibration_path, x, y, ln, m, target, step, out);
    free(x); free(y); free(ln);
    tsv_free(t);
    fs_trees_free(&tr);
    return st;
}

cs_status fs_jitter_star(const char *path, fs_calibration *out)
{
    memset(out, 0, sizeof *out);
    double target;
    cs_status st = gate_read_value(PATHS_GATE("anisotropy"), "field_median", 0, &target);
    if (st) return st;
    tsv *t;
    if ((st = tsv_read(path, &t))) return st;
    size_t n = tsv_nrows(t);
    double *x = malloc((n ? n : 1) * sizeof *x), *y = malloc((n ? n : 1) * sizeof *y);
    int *ln = malloc((n ? n : 1) * sizeof *ln);
    if (!x || !y || !ln) st = cs_err(CS_ENOMEM, "out of memory");
    for (size_t r = 0; r < n && !st; r++) {
        if ((st = tsv_double(t, r, "level", &x[r]))) break;
        if ((st = tsv_double(t, r, "aniso_median", &y[r]))) break;
        if (r && !(x[r] > x[r - 1])) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'level': not ascending", path, tsv_line(t, r));
            break;
        }
        ln[r] = tsv_line(t, r);
    }
    if (!st && n < 2) st = cs_err(CS_EINPUT, "%s: fewer than 2 sweep levels", path);
    if (!st) st = fs_curve_calibrate(path, x, y, ln, n, target, FS_JITTER_STEP, out);
    free(x); free(y); free(ln);
    tsv_free(t);
    return st;
}
