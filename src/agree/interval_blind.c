/* interval_blind: the stand units of the direction-blind level (MainIso and
 * its readings; design.md §6.1). The level is the mean over the unseen
 * spacings of W1(circular crowns, the teacher's) over every patch of the
 * evaluation stands; baselines_stands.tsv beside baselines.tsv says how many
 * consecutive patches of samples_baselines.tsv each stand gave. The unit is
 * the stand index k (its stands at every spacing drawn together); a resample
 * pools the patches of the drawn stands, in draw order, at each spacing, and
 * takes the W1 and their mean as the claim does. The frozen stands in their
 * own order must give the claim's value bit for bit. The W1 reads each pool
 * in ascending order: each spacing's pools are put in order once, with the
 * stand of every value, and a resample's pool in order is that order with
 * each value repeated as often as its stand was drawn: the values and order
 * a sort of the gathered pool gives, without a sort per resample. */
#include "interval_stands.h"
#include "estimator.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BL_MAXSTAND 4096

typedef struct {
    size_t nd, ns;
    size_t *off[IV_MAXD], *cnt[IV_MAXD]; /* per spacing, per stand: first patch, patches */
    double *teach[IV_MAXD], *blind[IV_MAXD];
    double *ga, *gb;                     /* gather buffers: ns x the largest stand */
    size_t cap;                          /* the largest stand's patches */
    /* per spacing, each pool's values in ascending order with their stands:
     * a resample's pooled values in order are these, each as many times as
     * its stand was drawn (what sorting the gathered values gives) */
    double *sblind[IV_MAXD], *steach[IV_MAXD];
    size_t *kblind[IV_MAXD], *kteach[IV_MAXD];
    size_t *mult;                        /* draws of each stand in one resample */
    int sorted;                          /* every value finite: the ordered pools are used */
} blind_ctx;

static void blind_free(void *p)
{
    blind_ctx *c = p;
    if (!c) return;
    for (size_t i = 0; i < IV_MAXD; i++) {
        free(c->off[i]); free(c->cnt[i]); free(c->teach[i]); free(c->blind[i]);
        free(c->sblind[i]); free(c->steach[i]); free(c->kblind[i]); free(c->kteach[i]);
    }
    free(c->mult);
    free(c->ga);
    free(c->gb);
    free(c);
}

/* The values of the drawn stands in ascending order: each value of the
 * ordered pool as many times as its stand was drawn. */
static size_t expand(const double *v, const size_t *k, size_t tot, const size_t *mult, double *out)
{
    size_t g = 0;
    for (size_t j = 0; j < tot; j++)
        for (size_t t = mult[k[j]]; t; t--) out[g++] = v[j];
    return g;
}

static cs_status blind_stat(const double *x, size_t n, size_t m, const void *ctxp, double *out)
{
    (void)m;
    const blind_ctx *c = ctxp;
    double sum = 0;
    if (c->sorted) {
        memset(c->mult, 0, c->ns * sizeof *c->mult);
        for (size_t r = 0; r < n; r++) c->mult[(size_t)x[r]]++;
        for (size_t i = 0; i < c->nd; i++) {
            const size_t tot = c->off[i][c->ns - 1] + c->cnt[i][c->ns - 1];
            const size_t ga = expand(c->sblind[i], c->kblind[i], tot, c->mult, c->ga);
            const size_t gb = expand(c->steach[i], c->kteach[i], tot, c->mult, c->gb);
            if (!ga || ga != gb) return cs_err(CS_EINPUT, "estimator: empty sample");
            sum += est_w1_sorted(c->ga, ga, c->gb, gb);
        }
        *out = sum / (double)c->nd;
        return CS_OK;
    }
    for (size_t i = 0; i < c->nd; i++) {
        size_t g = 0;
        for (size_t r = 0; r < n; r++) {
            const size_t k = (size_t)x[r];
            memcpy(c->ga + g, c->blind[i] + c->off[i][k], c->cnt[i][k] * sizeof *c->ga);
            memcpy(c->gb + g, c->teach[i] + c->off[i][k], c->cnt[i][k] * sizeof *c->gb);
            g += c->cnt[i][k];
        }
        double w;
        cs_status st = est_w1(c->ga, g, c->gb, g, &w);
        if (st) return st;
        sum += w;
    }
    *out = sum / (double)c->nd;
    return CS_OK;
}

/* Index of spacing d among the first *nd of dd (added when new). */
static long spacing_index(double *dd, size_t *nd, double d)
{
    for (size_t i = 0; i < *nd; i++) if (dd[i] == d) return (long)i;
    if (*nd == IV_MAXD) return -1;
    dd[*nd] = d;
    return (long)(*nd)++;
}

/* The stands table: per unseen spacing (file order), the patches of each stand. */
static cs_status read_stands(const char *path, blind_ctx *c, double *dd)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        const char *sp = tsv_str(t, r, "split");
        double d;
        long k, p;
        if (!sp) { st = cs_err(CS_EINPUT, "%s:%d: field 'split' missing", path, tsv_line(t, r)); break; }
        if (strcmp(sp, "unseen")) continue;
        if ((st = tsv_double(t, r, "spacing", &d)) || (st = tsv_long(t, r, "stand", &k)) ||
            (st = tsv_long(t, r, "patches", &p)))
            break;
        long i = spacing_index(dd, &c->nd, d);
        if (i < 0) { st = cs_err(CS_EINPUT, "%s:%d: more than %d spacings", path, tsv_line(t, r), IV_MAXD); break; }
        if (!c->cnt[i] && !(c->cnt[i] = calloc(BL_MAXSTAND, sizeof *c->cnt[i]))) {
            st = cs_err(CS_ENOMEM, "interval: out of memory");
            break;
        }
        size_t have = 0;
        while (have < BL_MAXSTAND && c->cnt[i][have]) have++;
        if (k != (long)have || p < 0 || k >= BL_MAXSTAND) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'stand': %ld out of order (expected %zu) or field 'patches' negative",
                        path, tsv_line(t, r), k, have);
            break;
        }
        c->cnt[i][k] = (size_t)p;
    }
    tsv_free(t);
    if (st) return st;
    if (!c->nd) return cs_err(CS_EINPUT, "%s: no unseen rows", path);
    for (size_t i = 0; i < c->nd; i++) {
        size_t ns = 0;
        while (ns < BL_MAXSTAND && c->cnt[i][ns]) ns++;
        if (i == 0) c->ns = ns;
        else if (ns != c->ns)
            return cs_err(CS_EINPUT, "%s: %zu stands at %g m, %zu at %g m", path, ns, dd[i], c->ns, dd[0]);
        if (!(c->off[i] = malloc(ns * sizeof *c->off[i]))) return cs_err(CS_ENOMEM, "interval: out of memory");
        for (size_t k = 0, o = 0; k < ns; o += c->cnt[i][k], k++) c->off[i][k] = o;
    }
    return CS_OK;
}

/* The teacher's and the circular crowns' values of each unseen spacing, in patch order. */
static cs_status read_samples(const char *path, blind_ctx *c, const double *dd)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    size_t nv[IV_MAXD][2] = {{0}};
    for (size_t i = 0; i < c->nd && !st; i++) {
        size_t tot = c->off[i][c->ns - 1] + c->cnt[i][c->ns - 1];
        if (!(c->teach[i] = malloc(tot * sizeof *c->teach[i])) || !(c->blind[i] = malloc(tot * sizeof *c->blind[i])))
            st = cs_err(CS_ENOMEM, "interval: out of memory");
        for (size_t k = 0; k < c->ns; k++) if (c->cnt[i][k] > c->cap) c->cap = c->cnt[i][k];
    }
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        const char *sp = tsv_str(t, r, "split"), *pr = tsv_str(t, r, "probe"), *wh = tsv_str(t, r, "which");
        if (!sp || !pr || !wh) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'split'/'probe'/'which' missing", path, tsv_line(t, r));
            break;
        }
        if (strcmp(sp, "unseen") || strcmp(pr, "none")) continue;
        const int b = !strcmp(wh, "blind");
        if (!b && strcmp(wh, "teacher")) continue;
        double d, v;
        if ((st = tsv_double(t, r, "spacing", &d)) || (st = tsv_double(t, r, "value", &v))) break;
        size_t i = 0;
        while (i < c->nd && dd[i] != d) i++;
        const size_t tot = i < c->nd ? c->off[i][c->ns - 1] + c->cnt[i][c->ns - 1] : 0;
        if (i == c->nd || nv[i][b] == tot) {
            st = cs_err(CS_EINPUT, "%s:%d: more %s values at %g m than the stands' patches", path, tsv_line(t, r), wh,
                        d);
            break;
        }
        (b ? c->blind[i] : c->teach[i])[nv[i][b]++] = v;
    }
    tsv_free(t);
    for (size_t i = 0; i < c->nd && !st; i++)
        if (nv[i][0] != c->off[i][c->ns - 1] + c->cnt[i][c->ns - 1] || nv[i][1] != nv[i][0])
            st = cs_err(CS_EINPUT, "%s: %zu teacher and %zu blind values at %g m, the stands give %zu patches", path,
                        nv[i][0], nv[i][1], dd[i], c->off[i][c->ns - 1] + c->cnt[i][c->ns - 1]);
    if (!st && (!(c->ga = malloc(c->cap * c->ns * sizeof *c->ga)) || !(c->gb = malloc(c->cap * c->ns * sizeof *c->gb))))
        st = cs_err(CS_ENOMEM, "interval: out of memory");
    return st;
}

static const double *order_vals;
static int order_cmp(const void *a, const void *b)
{
    const double x = order_vals[*(const size_t *)a], y = order_vals[*(const size_t *)b];
    return x < y ? -1 : x > y;
}

/* One pool of one spacing in ascending order, with the stand of each value. */
static cs_status order_pool(const blind_ctx *c, size_t i, const double *v, double **sv, size_t **sk)
{
    const size_t tot = c->off[i][c->ns - 1] + c->cnt[i][c->ns - 1];
    size_t *idx = malloc((tot ? tot : 1) * sizeof *idx), *stand = malloc((tot ? tot : 1) * sizeof *stand);
    *sv = malloc((tot ? tot : 1) * sizeof **sv);
    *sk = malloc((tot ? tot : 1) * sizeof **sk);
    if (!idx || !stand || !*sv || !*sk) { free(idx); free(stand); return cs_err(CS_ENOMEM, "interval: out of memory"); }
    for (size_t k = 0; k < c->ns; k++)
        for (size_t p = 0; p < c->cnt[i][k]; p++) stand[c->off[i][k] + p] = k;
    for (size_t j = 0; j < tot; j++) idx[j] = j;
    order_vals = v;
    qsort(idx, tot, sizeof *idx, order_cmp);
    for (size_t j = 0; j < tot; j++) { (*sv)[j] = v[idx[j]]; (*sk)[j] = stand[idx[j]]; }
    free(idx);
    free(stand);
    return CS_OK;
}

/* The ordered pools, when every value is finite (otherwise each resample
 * sorts its gathered values and the estimator names the value it refuses). */
static cs_status order_pools(blind_ctx *c)
{
    for (size_t i = 0; i < c->nd; i++) {
        const size_t tot = c->off[i][c->ns - 1] + c->cnt[i][c->ns - 1];
        for (size_t j = 0; j < tot; j++)
            if (!isfinite(c->teach[i][j]) || !isfinite(c->blind[i][j])) return CS_OK;
    }
    if (!(c->mult = calloc(c->ns ? c->ns : 1, sizeof *c->mult))) return cs_err(CS_ENOMEM, "interval: out of memory");
    for (size_t i = 0; i < c->nd; i++) {
        cs_status st = order_pool(c, i, c->blind[i], &c->sblind[i], &c->kblind[i]);
        if (!st) st = order_pool(c, i, c->teach[i], &c->steach[i], &c->kteach[i]);
        if (st) return st;
    }
    c->sorted = 1;
    return CS_OK;
}

cs_status iv_blind_stands(const claim_row *row, const claim_result *res, const interval_spec *spec, iv_data *d)
{
    (void)res; (void)spec;
    char rows[520], samples[520];
    const char *slash = strrchr(row->source, '/');
    const int dl = slash ? (int)(slash - row->source + 1) : 0;
    snprintf(samples, sizeof samples, "%.*ssamples_baselines.tsv", dl, row->source);
    void *ctx; /* rows: baselines_stands.tsv beside baselines.tsv */
    cs_status st =
        iv_stands_begin(row, "_stands", rows, sizeof rows, sizeof(blind_ctx), blind_stat, blind_free, d, &ctx);
    blind_ctx *c = ctx;
    double dd[IV_MAXD];
    if (!st) st = read_stands(rows, c, dd);
    if (!st) st = read_samples(samples, c, dd);
    if (!st) st = order_pools(c);
    if (!st)
        st = iv_stand_units(d, c->ns, rows,
                            "the patches of each evaluation stand, their values in samples_baselines.tsv");
    return st;
}
