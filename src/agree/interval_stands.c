/* interval_stands: the stand units of the pooled teacher tables (design.md
 * §6.1): the E1 sweep (mechanism/sweep.tsv, its trees in sweep_trees.tsv)
 * and the E2 tables (irreducibility/<table>_<tag>.tsv, their per-stand rows
 * in <table>_<tag>_stands.tsv or _sectors.tsv). A row of a pooled table pools
 * the stands k = 0..7 of its cell; the unit is the stand index k, whose
 * stands at every spacing (and, in the sweep, every die-back, which share
 * the stand) are drawn together, so a resample keeps the design's stands
 * per cell. Every extractor first recomputes every cell of the pooled table
 * from the rows beside it, in the pipeline's order, and refuses rows that do
 * not give it bit for bit; each statistic is the claim's, recomputed from
 * the drawn stands in draw order (the reduction's resamples sum per-stand
 * miss curves, the same sums in another order: its frozen stands' value is
 * checked in the pipeline's order, iv_data.own_exact). This file: the shared readers, the E2
 * perturbation and the E1 sweep; interval_irred.c: the E2 refinement and
 * reduction. */
#include "interval_stands.h"
#include "estimator.h"
#include "gate.h"
#include "paths.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* <dir>/<base><suffix>.tsv beside the pooled table <dir>/<base>.tsv. */
void iv_rows_path(const char *source, const char *suffix, char *out, size_t n)
{
    size_t l = strlen(source);
    int cut = l > 4 && !strcmp(source + l - 4, ".tsv") ? (int)(l - 4) : (int)l;
    snprintf(out, n, "%.*s%s.tsv", cut, source, suffix);
}

cs_status iv_stands_begin(const claim_row *row, const char *suffix, char *path, size_t np, size_t size, boot_stat fn,
                          void (*cleanup)(void *), iv_data *d, void **ctx)
{
    iv_rows_path(row->source, suffix, path, np);
    *ctx = calloc(1, size);
    if (!*ctx) return cs_err(CS_ENOMEM, "interval: out of memory");
    d->stat = (iv_stat){IV_CALLBACK, 0, 0, fn, *ctx};
    d->cleanup = cleanup;
    return CS_OK;
}

/* The units handed to the bootstrap: x[k] = k, k = 0..ns-1. */
cs_status iv_stand_units(iv_data *d, size_t ns, const char *rows, const char *what)
{
    d->x = calloc(ns ? ns : 1, sizeof *d->x);
    if (!d->x) return cs_err(CS_ENOMEM, "interval: out of memory");
    d->n = ns;
    d->m = 1;
    for (size_t k = 0; k < ns; k++) d->x[k] = (double)k;
    d->unit = "stand";
    d->method = "bootstrap";
    snprintf(d->from, sizeof d->from, "%s (%s; %zu stands, the stands of one index at every spacing drawn together)",
             rows, what, ns);
    return CS_OK;
}

/* A pooled cell that its rows do not give. */
static cs_status not_given(const claim_row *row, const tsv *pooled, size_t r, const char *col, double have, double want,
                           const char *rows)
{
    return cs_err(
        CS_EINVARIANT,
        "%s: %s:%d: field '%s' = %.17g but its per-stand rows %s give %.17g: they are not the data the claim rests on",
        row->macro, tsv_path(pooled), tsv_line(pooled, r), col, have, rows, want);
}

cs_status iv_check_cell(const claim_row *row, const tsv *pooled, size_t r, const char *col, double want,
                        const char *rows)
{
    double have;
    cs_status st = tsv_double(pooled, r, col, &have);
    if (st) return st;
    return have == want ? CS_OK : not_given(row, pooled, r, col, have, want, rows);
}

/* Index of the cell with key `v` among keys[0..n-1] (exact text), or -1. */
long iv_key_index(char (*keys)[48], size_t n, const char *v)
{
    for (size_t i = 0; i < n; i++) if (!strcmp(keys[i], v)) return (long)i;
    return -1;
}

/* Stand index of row r, 0 <= k < maxk. */
cs_status iv_row_stand(const tsv *t, size_t r, size_t maxk, size_t *k)
{
    long s;
    cs_status st = tsv_long(t, r, "stand", &s);
    if (st) return st;
    if (s < 0 || (size_t)s >= maxk)
        return cs_err(CS_EINPUT, "%s:%d: field 'stand': %ld outside 0..%zu", tsv_path(t), tsv_line(t, r), s, maxk - 1);
    *k = (size_t)s;
    return CS_OK;
}

/* Number of stands: one more than the largest stand index of t. */
cs_status iv_count_stands(const tsv *t, size_t *ns)
{
    *ns = 0;
    for (size_t r = 0; r < tsv_nrows(t); r++) {
        long s;
        cs_status st = tsv_long(t, r, "stand", &s);
        if (st) return st;
        if (s < 0 || s > 100000) return cs_err(CS_EINPUT, "%s:%d: field 'stand': %ld", tsv_path(t), tsv_line(t, r), s);
        if ((size_t)s + 1 > *ns) *ns = (size_t)s + 1;
    }
    if (*ns == 0) return cs_err(CS_EINPUT, "%s: no rows", tsv_path(t));
    return CS_OK;
}

/* ---- E2 perturbation: per stand, judged and responding neighbours ---- */

typedef struct { size_t nd, ns; double judged[IV_MAXD * 64], responded[IV_MAXD * 64]; int hi; } perturb_ctx;

/* 100 x the lowest (hi: highest) over the spacings of the response
 * fraction of the drawn stands, as claim_irred_resp_lo/_hi. */
static cs_status perturb_stat(const double *x, size_t n, size_t m, const void *ctx, double *out)
{
    const perturb_ctx *c = ctx;
    double best = c->hi ? -INFINITY : INFINITY;
    for (size_t a = 0; a < c->nd; a++) {
        double j = 0.0, r = 0.0;
        for (size_t b = 0; b < n; b++) {
            size_t k = (size_t)x[b * m];
            j += c->judged[a * c->ns + k];
            r += c->responded[a * c->ns + k];
        }
        double f = r / j;
        if (c->hi ? f > best : f < best) best = f;
    }
    *out = 100.0 * best;
    return CS_OK;
}

cs_status iv_perturb_stands(const claim_row *row, const claim_result *res, const interval_spec *sp, iv_data *d)
{
    (void)res; (void)sp;
    char path[600];
    void *cv;
    cs_status bst = iv_stands_begin(row, "_stands", path, sizeof path, sizeof(perturb_ctx), perturb_stat, free, d, &cv);
    if (bst) return bst;
    perturb_ctx *c = cv;
    c->hi = !strcmp(row->function, "claim_irred_resp_hi");
    tsv *p = NULL, *t = NULL;
    cs_status st = tsv_read(row->source, &p);
    if (!st) st = tsv_read(path, &t);
    char keys[IV_MAXD][48];
    c->nd = p ? tsv_nrows(p) : 0;
    if (!st && (c->nd == 0 || c->nd > IV_MAXD))
        st = cs_err(CS_EINPUT, "%s: %zu spacings (1..%d)", row->source, c->nd, IV_MAXD);
    for (size_t a = 0; a < c->nd && !st; a++) {
        const char *v;
        if (!(st = tsv_text(p, a, "spacing_m", &v))) snprintf(keys[a], sizeof keys[a], "%s", v);
    }
    if (!st) st = iv_count_stands(t, &c->ns);
    if (!st && c->ns > 64) st = cs_err(CS_EINPUT, "%s: %zu stands (at most 64)", path, c->ns);
    unsigned char seen[IV_MAXD * 64] = {0};
    for (size_t r = 0; t && r < tsv_nrows(t) && !st; r++) {
        const char *v;
        size_t k;
        long j, q;
        if ((st = tsv_text(t, r, "spacing_m", &v)) || (st = iv_row_stand(t, r, c->ns, &k)) ||
            (st = tsv_long(t, r, "judged", &j)) || (st = tsv_long(t, r, "responded", &q)))
            break;
        long a = iv_key_index(keys, c->nd, v);
        if (a < 0 || seen[(size_t)a * c->ns + k]) {
            st = cs_err(CS_EINPUT, "%s:%d: spacing %s, stand %zu: %s", path, tsv_line(t, r), v, k,
                        a < 0 ? "no such spacing in the pooled table" : "twice");
            break;
        }
        seen[(size_t)a * c->ns + k] = 1;
        c->judged[(size_t)a * c->ns + k] = (double)j;
        c->responded[(size_t)a * c->ns + k] = (double)q;
    }
    for (size_t i = 0; i < c->nd * c->ns && !st; i++)
        if (!seen[i])
            st = cs_err(CS_EINPUT, "%s: spacing %s has no row for stand %zu", path, keys[i / c->ns], i % c->ns);
    /* every pooled row: its stands, judged and responding neighbours */
    for (size_t a = 0; a < c->nd && !st; a++) {
        double j = 0.0, q = 0.0;
        for (size_t k = 0; k < c->ns; k++) { j += c->judged[a * c->ns + k]; q += c->responded[a * c->ns + k]; }
        if (!(st = iv_check_cell(row, p, a, "stands", (double)c->ns, path)) &&
            !(st = iv_check_cell(row, p, a, "judged", j, path)))
            st = iv_check_cell(row, p, a, "responded", q, path);
    }
    tsv_free(p);
    tsv_free(t);
    if (!st) st = iv_stand_units(d, c->ns, path, "judged and responding neighbours per stand");
    return st;
}

/* ---- E1 sweep: the interior trees of every cell, per stand ---- */

typedef struct {
    size_t nc, ns;
    double thr[4];          /* k1, k2, k3 clearance and cover bars (gates/mechanism.gate) */
    size_t *off, *cnt;      /* per unit u = c ns + k: its trees off .. off + cnt */
    double *kc[3], *cover;  /* per tree; per unit */
    double *buf;
} sweep_ctx;

static const char *const sweep_cols[3] = {"k1_m", "k2_m", "k3_m"};

static void sweep_ctx_free(void *p)
{
    sweep_ctx *c = p;
    if (!c) return;
    free(c->off); free(c->cnt); free(c->cover); free(c->buf);
    for (int j = 0; j < 3; j++) free(c->kc[j]);
    free(c);
}

/* The median as est_median gives it (GSL's median of the sorted values: the
 * middle one, or the mean of the two middle ones), found by selection
 * (Wirth's): order statistics do not depend on how they are found, and a
 * resample needs 48 medians. v (n >= 1, finite) is reordered. */
static double median_select(double *v, size_t n)
{
    const long k = (long)(n / 2);
    long l = 0, r = (long)n - 1;
    while (l < r) {
        double x = v[k];
        long i = l, j = r;
        do {
            while (v[i] < x) i++;
            while (x < v[j]) j--;
            if (i <= j) { double t = v[i]; v[i] = v[j]; v[j] = t; i++; j--; }
        } while (i <= j);
        if (j < k) l = i;
        if (k < i) r = j;
    }
    double hi = v[k];
    if (n % 2) return hi;
    double lo = v[0];
    for (long i = 1; i < k; i++) if (v[i] > lo) lo = v[i];
    return (lo + hi) / 2.0;
}

/* Cell cc over the drawn stands, as exp_mechanism_sweep pools it: the
 * median k-th clearance of the drawn trees (exact: by est_median, else by
 * selection), the mean cover of the stands. */
static cs_status sweep_cell(const sweep_ctx *c, const double *x, size_t n, size_t m, size_t cc, int exact, double k[3],
                            double *cover, size_t *trees)
{
    cs_status st = CS_OK;
    for (int j = 0; j < 3 && !st; j++) {
        size_t t = 0;
        for (size_t b = 0; b < n; b++) {
            size_t u = cc * c->ns + (size_t)x[b * m];
            memcpy(c->buf + t, c->kc[j] + c->off[u], c->cnt[u] * sizeof *c->buf);
            t += c->cnt[u];
        }
        *trees = t;
        if (exact) st = est_median(c->buf, t, &k[j]);
        else if (t) k[j] = median_select(c->buf, t);
        else st = cs_err(CS_EINPUT, "interval: a sweep cell without trees");
    }
    double cs = 0.0;
    for (size_t b = 0; b < n; b++) cs += c->cover[cc * c->ns + (size_t)x[b * m]];
    *cover = cs / (double)n;
    return st;
}

/* The sweep rows that pass (claim_mech_hits). */
static cs_status sweep_stat(const double *x, size_t n, size_t m, const void *ctx, double *out)
{
    const sweep_ctx *c = ctx;
    int hits = 0;
    for (size_t cc = 0; cc < c->nc; cc++) {
        double k[3], cover;
        size_t trees;
        cs_status st = sweep_cell(c, x, n, m, cc, 0, k, &cover, &trees);
        if (st) return st;
        hits += k[0] >= c->thr[0] && k[1] >= c->thr[1] && k[2] >= c->thr[2] && cover >= c->thr[3];
    }
    *out = hits;
    return CS_OK;
}

/* The tree rows of sweep_trees.tsv, cell by cell in the order of
 * sweep.tsv, stand by stand, into c. */
static cs_status sweep_load(sweep_ctx *c, const claim_row *row, const tsv *t, const char *path, char (*keys)[48])
{
    size_t nu = c->nc * c->ns, nr = tsv_nrows(t);
    c->off = calloc(nu, sizeof *c->off);
    c->cnt = calloc(nu, sizeof *c->cnt);
    c->cover = calloc(nu, sizeof *c->cover);
    c->buf = calloc(nr ? nr : 1, sizeof *c->buf);
    for (int j = 0; j < 3; j++) c->kc[j] = calloc(nr ? nr : 1, sizeof *c->kc[j]);
    if (!c->off || !c->cnt || !c->cover || !c->buf || !c->kc[0] || !c->kc[1] || !c->kc[2])
        return cs_err(CS_ENOMEM, "interval: out of memory");
    long last_u = -1;
    cs_status st = CS_OK;
    for (size_t r = 0; r < nr && !st; r++) {
        const char *b, *s;
        size_t k;
        double cov;
        if ((st = tsv_text(t, r, "beta", &b)) || (st = tsv_text(t, r, "spacing_m", &s)) ||
            (st = iv_row_stand(t, r, c->ns, &k)) || (st = tsv_double(t, r, "stand_cover", &cov)))
            break;
        for (int j = 0; j < 3 && !st; j++) st = tsv_double(t, r, sweep_cols[j], &c->kc[j][r]);
        if (st) break;
        char key[48];
        snprintf(key, sizeof key, "%.22s|%.22s", b, s);
        long cc = iv_key_index(keys, c->nc, key);
        if (cc < 0)
            return cs_err(CS_EINPUT, "%s:%d: beta %s at %s m is not a row of %s", path, tsv_line(t, r), b, s,
                          row->source);
        long u = cc * (long)c->ns + (long)k;
        if (u != last_u) {
            if (u < last_u || c->cnt[u])
                return cs_err(CS_EINPUT, "%s:%d: beta %s at %s m, stand %zu: rows out of order", path, tsv_line(t, r),
                              b, s, k);
            c->off[u] = r;
            c->cover[u] = cov;
            last_u = u;
        } else if (cov != c->cover[u]) {
            return cs_err(CS_EINVARIANT,
                          "%s: %s:%d: field 'stand_cover' = %.17g, the stand's other rows %.17g: they are not the data "
                          "the claim rests on",
                          row->macro, path, tsv_line(t, r), cov, c->cover[u]);
        }
        c->cnt[u]++;
    }
    for (size_t u = 0; u < nu && !st; u++)
        if (!c->cnt[u])
            st = cs_err(CS_EINPUT, "%s: row %zu of %s has no trees of stand %zu", path, u / c->ns + 1, row->source,
                        u % c->ns);
    return st;
}

/* Every sweep row recomputed from the frozen stands: its stands, trees, the
 * three clearances (by est_median, and the same by selection) and the cover. */
static cs_status sweep_check(const sweep_ctx *c, const claim_row *row, const tsv *p, const char *path)
{
    double *all = malloc(c->ns * sizeof *all);
    if (!all) return cs_err(CS_ENOMEM, "interval: out of memory");
    for (size_t k = 0; k < c->ns; k++) all[k] = (double)k;
    cs_status st = CS_OK;
    for (size_t cc = 0; cc < c->nc && !st; cc++) {
        double k[3], cover, ks[3], cs;
        size_t trees;
        if ((st = sweep_cell(c, all, c->ns, 1, cc, 1, k, &cover, &trees)) ||
            (st = sweep_cell(c, all, c->ns, 1, cc, 0, ks, &cs, &trees)))
            break;
        for (int j = 0; j < 3 && !st; j++)
            if (ks[j] != k[j])
                st = cs_err(CS_EINVARIANT, "%s: row %zu of %s: the median by selection %.17g, est_median %.17g",
                            row->macro, cc + 1, row->source, ks[j], k[j]);
        if (!st) st = iv_check_cell(row, p, cc, "stands", (double)c->ns, path);
        if (!st) st = iv_check_cell(row, p, cc, "trees", (double)trees, path);
        for (int j = 0; j < 3 && !st; j++) st = iv_check_cell(row, p, cc, sweep_cols[j], k[j], path);
        if (!st) st = iv_check_cell(row, p, cc, "cover", cover, path);
    }
    free(all);
    return st;
}

cs_status iv_sweep_stands(const claim_row *row, const claim_result *res, const interval_spec *sp, iv_data *d)
{
    (void)res; (void)sp;
    char path[600];
    void *cv;
    cs_status bst =
        iv_stands_begin(row, "_trees", path, sizeof path, sizeof(sweep_ctx), sweep_stat, sweep_ctx_free, d, &cv);
    if (bst) return bst;
    sweep_ctx *c = cv;
    const char *gk[4] = {"clearance_k1_min_m", "clearance_k2_min_m", "clearance_k3_min_m", "cover_min"};
    cs_status st = CS_OK;
    for (int i = 0; i < 4 && !st; i++) st = gate_read_value(PATHS_GATE("mechanism"), gk[i], 0, &c->thr[i]);
    tsv *p = NULL, *t = NULL;
    if (!st && !(st = tsv_read(row->source, &p))) st = tsv_read(path, &t);
    enum { MAXC = 256 };
    char keys[MAXC][48];
    c->nc = p ? tsv_nrows(p) : 0;
    if (!st && (c->nc == 0 || c->nc > MAXC)) st = cs_err(CS_EINPUT, "%s: %zu rows (1..%d)", row->source, c->nc, MAXC);
    for (size_t r = 0; r < c->nc && !st; r++) {
        const char *b, *s;
        if (!(st = tsv_text(p, r, "beta", &b)) && !(st = tsv_text(p, r, "spacing_m", &s)))
            snprintf(keys[r], sizeof keys[r], "%.22s|%.22s", b, s);
    }
    if (!st) st = iv_count_stands(t, &c->ns);
    if (!st) st = sweep_load(c, row, t, path, keys);
    if (!st) st = sweep_check(c, row, p, path);
    tsv_free(p);
    tsv_free(t);
    if (!st) st = iv_stand_units(d, c->ns, path, "the interior trees of every row per stand");
    return st;
}
