/* interval_irred: the stand units of the E2 refinement and reduction
 * tables (design.md §6.1; the shared readers and the design of the units:
 * interval_stands.h). refine_<tag>_sectors.tsv holds |dr| of every judged
 * sector, reduction_<tag>_sectors.tsv every interior sector's radii and
 * territory, each stand's rows in the order the pipeline pooled them. */
#include "interval_stands.h"
#include "gate.h"
#include "paths.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- E2 refinement: |dr| of every judged sector, per level, spacing, stand ---- */

typedef struct {
    size_t nl, nd, ns;
    double level[8];
    size_t *off, *cnt, *judged,
        *resp; /* per unit u = (l nd + a) ns + k: its sectors dr[off .. off + cnt), neighbours */
    double *dr, *step;
    int steps;                          /* 1: the step ratio, 0: the magnitude ratio */
} refine_ctx;

static void refine_ctx_free(void *p)
{
    refine_ctx *c = p;
    if (!c) return;
    free(c->off); free(c->cnt); free(c->judged); free(c->resp); free(c->dr); free(c->step);
    free(c);
}

/* Level l over the drawn stands, at spacing a (a = nd: pooled over the
 * spacings), in the order exp_irreducibility_refine accumulates. */
typedef struct { double mag, step; size_t judged, resp; long stands; } refine_cell;

static refine_cell refine_pool(const refine_ctx *c, const double *x, size_t n, size_t m, size_t l, size_t aonly)
{
    double abs = 0.0, stp = 0.0;
    size_t sec = 0;
    refine_cell o = {0};
    for (size_t a = 0; a < c->nd; a++) {
        if (aonly < c->nd && a != aonly) continue;
        double acc = 0.0, sacc = 0.0;
        for (size_t b = 0; b < n; b++) {
            size_t u = (l * c->nd + a) * c->ns + (size_t)x[b * m];
            for (size_t e = 0; e < c->cnt[u]; e++) acc += c->dr[c->off[u] + e];
            sec += c->cnt[u];
            sacc += c->step[u];
            o.judged += c->judged[u];
            o.resp += c->resp[u];
            o.stands++;
        }
        abs += acc;
        stp += sacc;
    }
    o.mag = abs / (double)sec;
    o.step = stp / (double)o.stands;
    return o;
}

/* The magnitude (or step) at the finest level over the first, pooled over the
 * spacings: claim_irred_resp_shrink (claim_irred_step_shrink). */
static cs_status refine_stat(const double *x, size_t n, size_t m, const void *ctx, double *out)
{
    const refine_ctx *c = ctx;
    refine_cell f = refine_pool(c, x, n, m, c->nl - 1, c->nd), z = refine_pool(c, x, n, m, 0, c->nd);
    *out = c->steps ? f.step / z.step : f.mag / z.mag;
    return CS_OK;
}

/* The sector rows of refine_<tag>_sectors.tsv, in the order written
 * (level, spacing, stand, neighbour, sector), into c. */
static cs_status refine_load(refine_ctx *c, const claim_row *row, const tsv *t, const char *path, const double *ds,
                             double tol)
{
    size_t nu = c->nl * c->nd * c->ns, nr = tsv_nrows(t);
    c->off = calloc(nu, sizeof *c->off);
    c->cnt = calloc(nu, sizeof *c->cnt);
    c->judged = calloc(nu, sizeof *c->judged);
    c->resp = calloc(nu, sizeof *c->resp);
    c->step = calloc(nu, sizeof *c->step);
    c->dr = calloc(nr ? nr : 1, sizeof *c->dr);
    if (!c->off || !c->cnt || !c->judged || !c->resp || !c->step || !c->dr)
        return cs_err(CS_ENOMEM, "interval: out of memory");
    long last_u = -1, last_j = -1;
    int any = 0;
    cs_status st = CS_OK;
    for (size_t r = 0; r < nr && !st; r++) {
        double nres, sd, dr, step;
        long j;
        size_t k;
        if ((st = tsv_double(t, r, "nres", &nres)) || (st = tsv_double(t, r, "spacing_m", &sd)) ||
            (st = iv_row_stand(t, r, c->ns, &k)) || (st = tsv_long(t, r, "neighbour", &j)) ||
            (st = tsv_double(t, r, "dr_m", &dr)) || (st = tsv_double(t, r, "step_m", &step)))
            break;
        size_t l = 0, a = 0;
        while (l < c->nl && c->level[l] != nres) l++;
        while (a < c->nd && ds[a] != sd) a++;
        if (l == c->nl || a == c->nd)
            return cs_err(CS_EINPUT, "%s:%d: N = %g at %g m is not a cell of gates/irreducibility.gate", path,
                          tsv_line(t, r), nres, sd);
        long u = (long)((l * c->nd + a) * c->ns + k);
        if (u != last_u) {
            if (u < last_u || (last_u >= 0 && c->cnt[u]))
                return cs_err(CS_EINPUT, "%s:%d: stand %zu at N = %g, %g m: rows out of order", path, tsv_line(t, r), k,
                              nres, sd);
            c->off[u] = r;
            c->step[u] = step;
            last_u = u;
            last_j = -1;
        } else if (step != c->step[u]) {
            return cs_err(CS_EINVARIANT,
                          "%s: %s:%d: field 'step_m' = %.17g, the stand's other rows %.17g: they are not the data the "
                          "claim rests on",
                          row->macro, path, tsv_line(t, r), step, c->step[u]);
        }
        if (j != last_j) { c->judged[u]++; any = 0; last_j = j; }
        c->dr[r] = dr;
        c->cnt[u]++;
        if (dr > tol && !any) { c->resp[u]++; any = 1; }
    }
    for (size_t u = 0; u < nu && !st; u++)
        if (!c->cnt[u])
            st = cs_err(CS_EINPUT, "%s: no rows for stand %zu at N = %g, %g m", path, u % c->ns,
                        c->level[u / c->ns / c->nd], ds[u / c->ns % c->nd]);
    return st;
}

/* Every row of the pooled table (pooled, spacing_m = 0, or one spacing, at
 * each level) recomputed from the frozen stands. */
static cs_status refine_check(const refine_ctx *c, const claim_row *row, const tsv *p, const char *path,
                              const double *ds)
{
    double *all = malloc(c->ns * sizeof *all);
    if (!all) return cs_err(CS_ENOMEM, "interval: out of memory");
    for (size_t k = 0; k < c->ns; k++) all[k] = (double)k;
    cs_status st = CS_OK;
    for (size_t r = 0; r < tsv_nrows(p) && !st; r++) {
        const char *scope;
        double nres, sd;
        if ((st = tsv_text(p, r, "scope", &scope)) || (st = tsv_double(p, r, "nres", &nres)) ||
            (st = tsv_double(p, r, "spacing_m", &sd)))
            break;
        size_t l = 0, a = 0;
        while (l < c->nl && c->level[l] != nres) l++;
        int pooled = !strcmp(scope, "pooled");
        if (pooled) a = c->nd;
        else while (a < c->nd && ds[a] != sd) a++;
        if (l == c->nl || (!pooled && a == c->nd)) {
            st = cs_err(CS_EINPUT, "%s:%d: N = %g at %g m is not a cell of the design", row->source, tsv_line(p, r),
                        nres, sd);
            break;
        }
        refine_cell o = refine_pool(c, all, c->ns, 1, l, a), z = refine_pool(c, all, c->ns, 1, 0, a);
        if (!(st = iv_check_cell(row, p, r, "stands", (double)o.stands, path)) &&
            !(st = iv_check_cell(row, p, r, "judged", (double)o.judged, path)) &&
            !(st = iv_check_cell(row, p, r, "responded", (double)o.resp, path)) &&
            !(st = iv_check_cell(row, p, r, "magnitude_m", o.mag, path)) &&
            !(st = iv_check_cell(row, p, r, "step_m", o.step, path)) &&
            !(st = iv_check_cell(row, p, r, "step_ratio", o.step / z.step, path)))
            st = iv_check_cell(row, p, r, "magnitude_ratio", o.mag / z.mag, path);
    }
    free(all);
    return st;
}

cs_status iv_refine_stands(const claim_row *row, const claim_result *res, const interval_spec *sp, iv_data *d)
{
    (void)res; (void)sp;
    char path[600];
    void *cv;
    cs_status bst =
        iv_stands_begin(row, "_sectors", path, sizeof path, sizeof(refine_ctx), refine_stat, refine_ctx_free, d, &cv);
    if (bst) return bst;
    refine_ctx *c = cv;
    c->steps = !strcmp(row->function, "claim_irred_step_shrink");
    double tol, ds[IV_MAXD];
    cs_status st = gate_read_values(PATHS_GATE("irreducibility"), "refine_levels", c->level, 8, &c->nl);
    if (!st) st = gate_read_values(PATHS_GATE("irreducibility"), "spacings_m", ds, IV_MAXD, &c->nd);
    if (!st) st = gate_read_value(PATHS_GATE("irreducibility"), "response_tol_m", 0, &tol);
    if (st) return st;
    tsv *p = NULL, *t = NULL;
    if (!(st = tsv_read(row->source, &p))) st = tsv_read(path, &t);
    if (!st) st = iv_count_stands(t, &c->ns);
    if (!st) st = refine_load(c, row, t, path, ds, tol);
    if (!st) st = refine_check(c, row, p, path, ds);
    tsv_free(p);
    tsv_free(t);
    if (!st) st = iv_stand_units(d, c->ns, path, "|dr| of every judged sector per stand");
    return st;
}

/* ---- E2 reduction: every interior sector, per spacing and stand ---- */

typedef struct {
    size_t nd, ns, nq;
    double *curve;   /* ns x nq: summed miss of stand index k's sectors (every spacing) at sigma_q */
    double *stepk;   /* per k: the summed growth steps of its stands */
    double *seck;    /* per k: its sectors */
    double *sum;     /* scratch, nq */
    int steps;       /* 1: miss in steps (claim_irred_steps), 0: miss in m (claim_irred_miss) */
} reduction_ctx;

static void reduction_ctx_free(void *p)
{
    reduction_ctx *c = p;
    if (!c) return;
    free(c->curve); free(c->stepk); free(c->seck); free(c->sum);
    free(c);
}

/* The best single sigma of the drawn stands and its mean miss, in m or in
 * mean growth steps. The curves are per-stand sums: the pooled sums of the
 * pipeline in another order (the frozen stands' own value is checked in the
 * pipeline's order, iv_reduction_stands). */
static cs_status reduction_stat(const double *x, size_t n, size_t m, const void *ctx, double *out)
{
    const reduction_ctx *c = ctx;
    double *s = c->sum, best = INFINITY, sec = 0.0, stp = 0.0;
    for (size_t q = 0; q < c->nq; q++) s[q] = 0.0;
    for (size_t b = 0; b < n; b++) {
        size_t k = (size_t)x[b * m];
        const double *cv = c->curve + k * c->nq;
        for (size_t q = 0; q < c->nq; q++) s[q] += cv[q];
        sec += c->seck[k];
        stp += c->stepk[k];
    }
    for (size_t q = 0; q < c->nq; q++) if (s[q] < best) best = s[q];
    double miss = best / sec, step_mean = stp / (double)(n * c->nd);
    *out = c->steps ? miss / step_mean : miss;
    return CS_OK;
}

/* One sector's miss |r_t - min(r*, b - sigma_q)| at every sigma_q of the
 * grid, added to its spacing's sums and its stand's curve (each q its own
 * sum, in file order). */
static void add_terms(double *restrict sa, double *restrict cv, const double *restrict sig, size_t nq, double rt,
                      double rs, double bb)
{
    for (size_t q = 0; q < nq; q++) {
        double lim = bb - sig[q], term = fabs(rt - (rs < lim ? rs : lim)); /* fmin(rs, lim): no NaN here */
        sa[q] += term;
        cv[q] += term;
    }
}

/* Room for the reduction of nd spacings x ns stands on nq sigmas. */
typedef struct { double *seq, *sig, *stepa, *stepak; size_t *na; unsigned char *seen; } reduction_work;

static void reduction_work_free(reduction_work *w)
{
    free(w->seq); free(w->sig); free(w->stepa); free(w->stepak); free(w->na); free(w->seen);
}

static cs_status reduction_alloc(reduction_ctx *c, reduction_work *w, int q0, int den)
{
    size_t nq = c->nq;
    c->curve = calloc(c->ns * nq, sizeof *c->curve);
    c->stepk = calloc(c->ns, sizeof *c->stepk);
    c->seck = calloc(c->ns, sizeof *c->seck);
    c->sum = calloc(nq, sizeof *c->sum);
    w->seq = calloc(c->nd * nq, sizeof *w->seq);
    w->sig = malloc(nq * sizeof *w->sig);
    w->stepa = calloc(c->nd, sizeof *w->stepa);
    w->stepak = calloc(c->nd * c->ns, sizeof *w->stepak);
    w->na = calloc(c->nd, sizeof *w->na);
    w->seen = calloc(c->nd * c->ns, 1);
    if (!c->curve || !c->stepk || !c->seck || !c->sum || !w->seq || !w->sig || !w->stepa || !w->stepak || !w->na ||
        !w->seen)
        return cs_err(CS_ENOMEM, "interval: out of memory");
    for (size_t q = 0; q < nq; q++) w->sig[q] = (double)((int)q - q0) / (double)den;
    return CS_OK;
}

/* One pass over the sector rows in file order (spacing, stand, tree,
 * sector): the pipeline's sums per spacing (w->seq) and each stand index's
 * curve (c->curve). */
static cs_status reduction_load(reduction_ctx *c, reduction_work *w, const claim_row *row, const tsv *t,
                                const char *path, char (*keys)[48])
{
    long last_a = -1, last_k = -1;
    cs_status st = CS_OK;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        const char *v;
        size_t k;
        double rt, rs, bb, step;
        if ((st = tsv_text(t, r, "spacing_m", &v)) || (st = iv_row_stand(t, r, c->ns, &k)) ||
            (st = tsv_double(t, r, "r_teacher_m", &rt)) || (st = tsv_double(t, r, "r_star_m", &rs)) ||
            (st = tsv_double_nf(t, r, "territory_m", &bb)) || (st = tsv_double(t, r, "step_m", &step)))
            break;
        long a = iv_key_index(keys, c->nd, v);
        if (a < 0)
            return cs_err(CS_EINPUT, "%s:%d: spacing %s is not a spacing row of %s", path, tsv_line(t, r), v,
                          row->source);
        size_t ak = (size_t)a * c->ns + k;
        if (a != last_a || (long)k != last_k) {
            if (a < last_a || (a == last_a && (long)k < last_k) || w->seen[ak])
                return cs_err(CS_EINPUT, "%s:%d: spacing %s, stand %zu: rows out of order", path, tsv_line(t, r), v, k);
            w->seen[ak] = 1;
            w->stepak[ak] = step;
            last_a = a;
            last_k = (long)k;
        } else if (step != w->stepak[ak]) {
            return cs_err(CS_EINVARIANT,
                          "%s: %s:%d: field 'step_m' = %.17g, the stand's other rows %.17g: they are not the data the "
                          "claim rests on",
                          row->macro, path, tsv_line(t, r), step, w->stepak[ak]);
        }
        add_terms(w->seq + (size_t)a * c->nq, c->curve + k * c->nq, w->sig, c->nq, rt, rs, bb);
        w->na[a]++;
        c->seck[k] += 1.0;
    }
    for (size_t i = 0; i < c->nd * c->ns && !st; i++)
        if (!w->seen[i])
            st = cs_err(CS_EINPUT, "%s: spacing %s has no rows for stand %zu", path, keys[i / c->ns], i % c->ns);
    return st;
}

/* The pipeline's reduction of the frozen stands (exp_irreducibility_reduction):
 * every row of the pooled table checked, and the claim's own value. */
static cs_status reduction_own(reduction_ctx *c, reduction_work *w, const claim_row *row, const tsv *p,
                               const char *path, char (*keys)[48], double *own)
{
    size_t ntot = 0, qbest = 0, nq = c->nq;
    double steptot = 0.0, best = INFINITY;
    for (size_t a = 0; a < c->nd; a++) {
        for (size_t k = 0; k < c->ns; k++) {
            w->stepa[a] += w->stepak[a * c->ns + k];
            c->stepk[k] += w->stepak[a * c->ns + k];
        }
        ntot += w->na[a];
        steptot += w->stepa[a];
    }
    for (size_t q = 0; q < nq; q++) {
        double s = 0.0;
        for (size_t a = 0; a < c->nd; a++) s += w->seq[a * nq + q];
        if (s < best) { best = s; qbest = q; }
    }
    double mpool = best / (double)ntot, step_mean = steptot / (double)((int)c->ns * (int)c->nd);
    cs_status st = CS_OK;
    for (size_t r = 0; r < tsv_nrows(p) && !st; r++) {
        const char *scope, *v;
        if ((st = tsv_text(p, r, "scope", &scope)) || (st = tsv_text(p, r, "spacing_m", &v))) break;
        int pooled = !strcmp(scope, "pooled");
        size_t a = pooled ? 0 : (size_t)iv_key_index(keys, c->nd, v), qo = qbest;
        if (!pooled) for (size_t q = 0; q < nq; q++) if (w->seq[a * nq + q] < w->seq[a * nq + qo]) qo = q;
        double mm = pooled ? mpool : w->seq[a * nq + qbest] / (double)w->na[a],
               stp = pooled ? step_mean : w->stepa[a] / (double)c->ns;
        if (!(st = iv_check_cell(row, p, r, "sectors", (double)(pooled ? ntot : w->na[a]), path)) &&
            !(st = iv_check_cell(row, p, r, "sigma_m", w->sig[qbest], path)) &&
            !(st = iv_check_cell(row, p, r, "miss_m", mm, path)) &&
            !(st = iv_check_cell(row, p, r, "step_m", stp, path)) &&
            !(st = iv_check_cell(row, p, r, "miss_steps", mm / stp, path)) &&
            !(st = iv_check_cell(row, p, r, "own_sigma_m", w->sig[qo], path)))
            st = iv_check_cell(row, p, r, "own_miss_m", pooled ? mm : w->seq[a * nq + qo] / (double)w->na[a], path);
    }
    *own = c->steps ? mpool / step_mean : mpool;
    return st;
}

cs_status iv_reduction_stands(const claim_row *row, const claim_result *res, const interval_spec *sp, iv_data *d)
{
    (void)res; (void)sp;
    char path[600];
    void *cv;
    cs_status bst = iv_stands_begin(row, "_sectors", path, sizeof path, sizeof(reduction_ctx), reduction_stat,
                                    reduction_ctx_free, d, &cv);
    if (bst) return bst;
    reduction_ctx *c = cv;
    c->steps = !strcmp(row->function, "claim_irred_steps");
    tsv *p = NULL, *t = NULL;
    cs_status st = tsv_read(row->source, &p);
    if (!st) st = tsv_read(path, &t);
    /* the sigma grid, as the table states it: sigma_q = (q - q0) / den m, q = 0..qmax */
    int q0 = 0, den = 0, qmax = -1;
    const char *g = t ? tsv_meta(t, "sigma_grid") : NULL;
    if (!st && (!g || sscanf(g, "sigma_q = (q - %d) / %d m, q = 0..%d", &q0, &den, &qmax) != 3 || den < 1 || qmax < 0 ||
                qmax > 100000))
        st = cs_err(CS_EINPUT, "%s: header '# sigma_grid:' missing or not 'sigma_q = (q - Q0) / DEN m, q = 0..QMAX'",
                    path);
    c->nq = (size_t)(qmax + 1);
    char keys[IV_MAXD][48];
    /* the spacings: the pooled table's spacing rows, in order */
    for (size_t r = 0; p && r < tsv_nrows(p) && !st; r++) {
        const char *scope, *v;
        if ((st = tsv_text(p, r, "scope", &scope)) || (st = tsv_text(p, r, "spacing_m", &v))) break;
        if (strcmp(scope, "spacing")) continue;
        if (c->nd == IV_MAXD) { st = cs_err(CS_EINPUT, "%s: more than %d spacings", row->source, IV_MAXD); break; }
        snprintf(keys[c->nd++], sizeof keys[0], "%s", v);
    }
    if (!st && c->nd == 0) st = cs_err(CS_EINPUT, "%s: no spacing rows", row->source);
    if (!st) st = iv_count_stands(t, &c->ns);
    reduction_work w = {0};
    if (!st) st = reduction_alloc(c, &w, q0, den);
    if (!st) st = reduction_load(c, &w, row, t, path, keys);
    if (!st) st = reduction_own(c, &w, row, p, path, keys, &d->own_exact);
    d->has_own_exact = !st;
    reduction_work_free(&w);
    tsv_free(p);
    tsv_free(t);
    if (!st)
        st = iv_stand_units(d, c->ns, path, "every interior sector per stand; the sigma refitted on each resample");
    return st;
}
