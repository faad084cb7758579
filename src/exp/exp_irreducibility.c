/* exp_irreducibility: E2 irreducibility (design.md §7 E2; reference paper §3.3, Eq. 4),
 * writing frozen/irreducibility at one die-back (beta_train, or beta_field
 * with --tag field). Choices the spec leaves open:
 *  - focal tree: the interior stem nearest the footprint centre (stems_focal);
 *    judged: its 4 nearest stems (est_knn); the perturbed run keeps the
 *    unperturbed mean height; magnitude = mean |dr| over the judged trees' 96
 *    sectors, pooled over stands;
 *  - reduction: sigma on a grid -1.000:0.001:3.000 m, one sigma for all
 *    interior sectors of all spacings pooled; miss in steps = pooled mean
 *    miss / pooled mean Delta at N = 48.
 * Outputs:
 *  irreducibility/perturb_<tag>.tsv  spacing_m beta nres stands judged responded
 *                          response_fraction magnitude_m step_m   (5 rows)
 *  irreducibility/refine_<tag>.tsv   scope(pooled|spacing) spacing_m nres stands
 *                          judged responded magnitude_m step_m step_ratio
 *                          magnitude_ratio   (pooled rows first; gate on pooled N=384)
 *  irreducibility/reduction_<tag>.tsv scope spacing_m sectors sigma_m miss_m step_m
 *                          miss_steps own_sigma_m own_miss_m (pooled row first)
 * With --stand-rows (the make units; design.md §6.1), the rows the pooled
 * tables are made of, in the order they were pooled, written before them:
 *  irreducibility/perturb_<tag>_stands.tsv  spacing_m stand judged responded
 *                          magnitude_m step_m   (one row per stand)
 *  irreducibility/refine_<tag>_sectors.tsv  nres spacing_m stand neighbour
 *                          sector dr_m step_m   (one row per judged sector)
 *  irreducibility/reduction_<tag>_sectors.tsv spacing_m stand tree sector
 *                          r_teacher_m r_star_m territory_m step_m
 *                          (one row per interior sector) */
#include "exp_irreducibility.h"
#include "exp_common.h"
#include "unit_out.h"
#include "estimator.h"
#include "gate.h"
#include "paths.h"
#include "stand_grow.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NS CROWN_NSEC
#define MAXJUDGE 16

typedef struct { size_t judged, responded, sectors; double abs_sum, step_sum; int stands; } perturb_acc;

/* One stand's own numbers beside the pooled accumulation (--stand-rows):
 * its judged and responding neighbours, |dr| of every judged sector
 * (neighbour-major) and their sum, its growth step. */
typedef struct { size_t judged, responded; double abs_sum, step, dr[MAXJUDGE * NS]; } stand_own;

/* One stand at resolution nres: baseline and perturbed growth, accumulated
 * into acc (and, when own is not NULL, the stand's own numbers into own). */
static cs_status perturb_stand(const stand *sd, const exp_reading *rd, double beta, int nres, double hfac, double tol,
                               int njudge, perturb_acc *acc, stand_own *own, double *worst)
{
    if (own) memset(own, 0, sizeof *own);
    size_t n = sd->s->n;
    double *ra = malloc(n * NS * sizeof *ra), *rb = malloc(n * NS * sizeof *rb), *h2 = malloc(n * sizeof *h2);
    cs_status st = (!ra || !rb || !h2) ? cs_err(CS_ENOMEM, "experiments: out of memory") : CS_OK;
    teacher_params p;
    EXP_TEACHER_PARAMS(rd, &p);
    p.beta = beta;
    p.nres = nres;
    teacher_info ia;
    if (!st) st = stand_grow(sd, &p, NULL, ra, &ia, worst);
    if (!st) {
        size_t f = 0;
        st = stems_focal(sd->s, &f);
        memcpy(h2, sd->h, n * sizeof *h2);
        h2[f] *= hfac;
        p.hbar = ia.hbar; /* the perturbation keeps the unperturbed mean height */
        if (!st) st = stand_grow(sd, &p, h2, rb, NULL, worst);
        for (int k = 1; k <= njudge && !st; k++) {
            long j = est_knn(sd->s->x, sd->s->y, n, f, k);
            if (j < 0) {
                st = cs_err(CS_EINPUT, "experiments: focal tree has fewer than %d neighbours", njudge);
                break;
            }
            int resp = 0;
            for (int s = 0; s < NS; s++) {
                double dr = fabs(rb[(size_t)j * NS + s] - ra[(size_t)j * NS + s]);
                if (dr > tol) resp = 1;
                acc->abs_sum += dr;
                acc->sectors++;
                if (own) { own->dr[(k - 1) * NS + s] = dr; own->abs_sum += dr; }
            }
            acc->judged++;
            acc->responded += (size_t)resp;
            if (own) { own->judged++; own->responded += (size_t)resp; }
        }
        acc->step_sum += ia.step;
        acc->stands++;
        if (own) own->step = ia.step;
    }
    free(ra); free(rb); free(h2);
    return st;
}

typedef struct { double ds[8]; size_t nd; double hfac, tol; int njudge; double levels[8]; size_t nlev; } irred_cfg;

static cs_status irred_cfg_load(irred_cfg *c)
{
    double v;
    cs_status st = gate_read_values(PATHS_GATE("irreducibility"), "spacings_m", c->ds, 8, &c->nd);
    if (!st) st = gate_read_value(PATHS_GATE("irreducibility"), "height_factor", 0, &c->hfac);
    if (!st) st = gate_read_value(PATHS_GATE("irreducibility"), "response_tol_m", 0, &c->tol);
    if (!st) st = gate_read_value(PATHS_GATE("irreducibility"), "neighbours_judged", 0, &v);
    if (!st) c->njudge = (int)v;
    if (!st) st = gate_read_values(PATHS_GATE("irreducibility"), "refine_levels", c->levels, 8, &c->nlev);
    if (!st && (c->njudge < 1 || c->njudge > MAXJUDGE))
        st = cs_err(CS_EINPUT, "%s: neighbours_judged %d outside 1..%d", PATHS_GATE("irreducibility"), c->njudge,
                    MAXJUDGE);
    return st;
}

static void irred_meta(tsv_writer *w, const exp_opts *o, double beta)
{
    unit_out_meta(w, o);
    tsv_writer_meta(w, "dieback", "%.17g (%s)", beta, o->tag);
    tsv_writer_meta(w, "stems", "controlled lattice a = 0.04, L = 12 d");
    tsv_writer_meta(w, "focal", "interior stem nearest the footprint centre, height x 1.30, stand mean height kept");
    tsv_writer_meta(w, "judged", "the focal tree's 4 nearest stems; responds when any sector moves by > 1e-6 m");
}

/* Stand k of the E2 design at spacing d: controlled lattice, a = 0.04, L = 12 d. */
static cs_status irred_stand(const exp_reading *rd, stand **sd, double d, int k)
{
    return exp_stand_alloc(rd, sd, stems_lattice, d, 12.0 * d, 0.04, "irreducibility", (unsigned)k);
}

/* Open irreducibility/<prefix>_<tag><rows>.tsv (rows: "" for the pooled
 * table, "_stands" or "_sectors" for its per-stand rows) and write the
 * provenance block and the shared metadata; on failure nothing is left open. */
static cs_status irred_open(const exp_opts *o, const char *prefix, const char *rows, double beta, prov *pv,
                            double worst, tsv_writer **w, char *path, size_t pathsz)
{
    char file[64];
    snprintf(file, sizeof file, "%s_%s%s.tsv", prefix, o->tag, rows);
    cs_status st = unit_out_open(o, "irreducibility", file, w, path, pathsz);
    if (st) return st;
    pv->worst_overlap_m = worst;
    snprintf(pv->seeds, sizeof pv->seeds, "seed_derive(irreducibility,d,k,stems|crowns) k=0..%d", o->stands - 1);
    st = prov_write(*w, pv);
    if (st) { tsv_writer_abort(*w); return st; }
    irred_meta(*w, o, beta);
    if (rows[0])
        tsv_writer_meta(*w, "rows", "the per-stand rows of %s_%s.tsv, in the order they were pooled (design.md §6.1)",
                        prefix, o->tag);
    return CS_OK;
}

/* Room for n stand_own records (--stand-rows), or NULL without the rows. */
static cs_status owns_alloc(const exp_opts *o, size_t n, stand_own **out)
{
    *out = NULL;
    if (!o->stand_rows) return CS_OK;
    *out = calloc(n ? n : 1, sizeof **out);
    return *out ? CS_OK : cs_err(CS_ENOMEM, "experiments: out of memory");
}

/* irreducibility/perturb_<tag>_stands.tsv: one row per stand (spacing-major). */
static cs_status write_perturb_stands(const exp_opts *o, double beta, const prov *pv, double worst, const irred_cfg *c,
                                      const stand_own *own)
{
    prov rp = *pv;
    tsv_writer *w = NULL;
    char path[512];
    const size_t ns = (size_t)o->stands;
    cs_status st = irred_open(o, "perturb", "_stands", beta, &rp, worst, &w, path, sizeof path);
    if (st) return st;
    tsv_writer_columns(w, "spacing_m\tstand\tjudged\tresponded\tmagnitude_m\tstep_m");
    for (size_t a = 0; a < c->nd; a++)
        for (size_t k = 0; k < ns; k++) {
            const stand_own *x = &own[a * ns + k];
            tsv_writer_dbl(w, c->ds[a]);
            tsv_writer_long(w, (long)k);
            tsv_writer_long(w, (long)x->judged);
            tsv_writer_long(w, (long)x->responded);
            tsv_writer_dbl(w, x->abs_sum / (double)(x->judged * NS));
            tsv_writer_dbl(w, x->step);
            tsv_writer_endrow(w);
        }
    return unit_out_finish(w, &rp, path);
}

/* irreducibility/refine_<tag>_sectors.tsv: one row per judged sector (level,
 * spacing, stand, neighbour, sector). */
static cs_status write_refine_sectors(const exp_opts *o, double beta, const prov *pv, double worst, const irred_cfg *c,
                                      const stand_own *own)
{
    prov rp = *pv;
    tsv_writer *w = NULL;
    char path[512];
    const size_t ns = (size_t)o->stands;
    cs_status st = irred_open(o, "refine", "_sectors", beta, &rp, worst, &w, path, sizeof path);
    if (st) return st;
    tsv_writer_meta(w, "sectors",
                    "|dr| of each sector of each judged neighbour (1..%d by distance to the focal tree); step_m is the "
                    "stand's growth step",
                    c->njudge);
    tsv_writer_columns(w, "nres\tspacing_m\tstand\tneighbour\tsector\tdr_m\tstep_m");
    for (size_t l = 0; l < c->nlev; l++)
        for (size_t a = 0; a < c->nd; a++)
            for (size_t k = 0; k < ns; k++) {
                const stand_own *x = &own[(l * c->nd + a) * ns + k];
                for (size_t j = 0; j < x->judged; j++)
                    for (int q = 0; q < NS; q++) {
                        tsv_writer_long(w, (long)c->levels[l]);
                        tsv_writer_dbl(w, c->ds[a]);
                        tsv_writer_long(w, (long)k);
                        tsv_writer_long(w, (long)j + 1);
                        tsv_writer_long(w, q);
                        tsv_writer_dbl(w, x->dr[j * NS + (size_t)q]);
                        tsv_writer_dbl(w, x->step);
                        tsv_writer_endrow(w);
                    }
            }
    return unit_out_finish(w, &rp, path);
}

cs_status exp_irreducibility_perturb(const exp_opts *o, double beta)
{
    prov pv;
    exp_prov_begin(&pv, "irreducibility", &o->rd, o->argc, o->argv);
    irred_cfg c;
    cs_status st = irred_cfg_load(&c);
    if (st) return st;
    perturb_acc acc[8];
    memset(acc, 0, sizeof acc);
    double worst = 0.0;
    stand_own *own = NULL;
    const size_t ns = (size_t)o->stands;
    st = owns_alloc(o, c.nd * ns, &own);
    for (size_t a = 0; a < c.nd && !st; a++) {
        for (int k = 0; k < o->stands && !st; k++) {
            stand *sd = NULL;
            st = irred_stand(&o->rd, &sd, c.ds[a], k);
            if (!st) st = perturb_stand(sd, &o->rd, beta, exp_nres(&o->rd), c.hfac, c.tol, c.njudge, &acc[a],
                                        own ? &own[a * ns + (size_t)k] : NULL, &worst);
            stand_free(sd);
        }
        if (!st) fprintf(stderr, "irreducibility perturb (%s): d=%.1f responded %zu/%zu\n", o->tag, c.ds[a],
                         acc[a].responded, acc[a].judged);
    }
    tsv_writer *w = NULL;
    char path[512];
    if (!st && own) st = write_perturb_stands(o, beta, &pv, worst, &c, own);
    free(own);
    if (!st) st = irred_open(o, "perturb", "", beta, &pv, worst, &w, path, sizeof path);
    if (st) return st;
    tsv_writer_columns(w, "spacing_m\tbeta\tnres\tstands\tjudged\tresponded\tresponse_fraction\tmagnitude_m\tstep_m");
    for (size_t a = 0; a < c.nd; a++) {
        tsv_writer_dbl(w, c.ds[a]);
        tsv_writer_dbl(w, beta);
        tsv_writer_long(w, exp_nres(&o->rd));
        tsv_writer_long(w, acc[a].stands);
        tsv_writer_long(w, (long)acc[a].judged);
        tsv_writer_long(w, (long)acc[a].responded);
        tsv_writer_dbl(w, (double)acc[a].responded / (double)acc[a].judged);
        tsv_writer_dbl(w, acc[a].abs_sum / (double)acc[a].sectors);
        tsv_writer_dbl(w, acc[a].step_sum / (double)acc[a].stands);
        tsv_writer_endrow(w);
    }
    return unit_out_finish(w, &pv, path);
}

cs_status exp_irreducibility_refine(const exp_opts *o, double beta)
{
    prov pv;
    exp_prov_begin(&pv, "irreducibility", &o->rd, o->argc, o->argv);
    irred_cfg c;
    cs_status st = irred_cfg_load(&c);
    if (st) return st;
    perturb_acc acc[8][8], pool[8];
    memset(acc, 0, sizeof acc);
    memset(pool, 0, sizeof pool);
    double worst = 0.0;
    stand_own *own = NULL;
    const size_t ns = (size_t)o->stands;
    st = owns_alloc(o, c.nlev * c.nd * ns, &own);
    for (size_t l = 0; l < c.nlev && !st; l++) {
        for (size_t a = 0; a < c.nd && !st; a++)
            for (int k = 0; k < o->stands && !st; k++) {
                stand *sd = NULL;
                st = irred_stand(&o->rd, &sd, c.ds[a], k);
                if (!st) st = perturb_stand(sd, &o->rd, beta, (int)c.levels[l], c.hfac, c.tol, c.njudge, &acc[l][a],
                                            own ? &own[(l * c.nd + a) * ns + (size_t)k] : NULL, &worst);
                stand_free(sd);
                if (!st && k == o->stands - 1)
                    fprintf(stderr, "irreducibility refine (%s): %3.0f%% (N=%.0f d=%.1f done, %.1f s)\n", o->tag,
                            100.0 * (double)(l * c.nd + a + 1) / (double)(c.nlev * c.nd), c.levels[l], c.ds[a],
                            prov_now() - pv.t0);
            }
        for (size_t a = 0; a < c.nd; a++) {
            pool[l].abs_sum += acc[l][a].abs_sum;
            pool[l].sectors += acc[l][a].sectors;
            pool[l].judged += acc[l][a].judged;
            pool[l].responded += acc[l][a].responded;
            pool[l].step_sum += acc[l][a].step_sum;
            pool[l].stands += acc[l][a].stands;
        }
        if (!st) fprintf(stderr, "irreducibility refine (%s): N=%.0f magnitude %.6f m\n", o->tag, c.levels[l],
                         pool[l].abs_sum / (double)pool[l].sectors);
    }
    tsv_writer *w = NULL;
    char path[512];
    if (!st && own) st = write_refine_sectors(o, beta, &pv, worst, &c, own);
    free(own);
    if (!st) st = irred_open(o, "refine", "", beta, &pv, worst, &w, path, sizeof path);
    if (st) return st;
    tsv_writer_meta(w, "scope",
                    "pooled rows (spacing_m = 0) pool every judged sector of every spacing; gate on pooled");
    tsv_writer_columns(
        w, "scope\tspacing_m\tnres\tstands\tjudged\tresponded\tmagnitude_m\tstep_m\tstep_ratio\tmagnitude_ratio");
    for (int pooled = 1; pooled >= 0; pooled--)
        for (size_t a = 0; a < (pooled ? 1 : c.nd); a++)
            for (size_t l = 0; l < c.nlev; l++) {
                const perturb_acc *x = pooled ? &pool[l] : &acc[l][a];
                const perturb_acc *x0 = pooled ? &pool[0] : &acc[0][a];
                double mag = x->abs_sum / (double)x->sectors, mag0 = x0->abs_sum / (double)x0->sectors;
                double step = x->step_sum / (double)x->stands, step0 = x0->step_sum / (double)x0->stands;
                tsv_writer_str(w, pooled ? "pooled" : "spacing");
                tsv_writer_dbl(w, pooled ? 0.0 : c.ds[a]);
                tsv_writer_long(w, (long)c.levels[l]);
                tsv_writer_long(w, x->stands);
                tsv_writer_long(w, (long)x->judged);
                tsv_writer_long(w, (long)x->responded);
                tsv_writer_dbl(w, mag);
                tsv_writer_dbl(w, step);
                tsv_writer_dbl(w, step / step0);
                tsv_writer_dbl(w, mag / mag0);
                tsv_writer_endrow(w);
            }
    return unit_out_finish(w, &pv, path);
}

/* Voronoi territory distance b_i(theta): along theta to the nearest
 * perpendicular bisector with any other stem (paper Eq. 4). */
static double territory(const stems *s, size_t i, double th)
{
    double ux = cos(th), uy = sin(th), b = INFINITY;
    for (size_t j = 0; j < s->n; j++) {
        if (j == i) continue;
        double vx = s->x[j] - s->x[i], vy = s->y[j] - s->y[i];
        double proj = ux * vx + uy * vy; /* nu cos(angle) */
        if (proj <= 0.0) continue;
        double t = 0.5 * (vx * vx + vy * vy) / proj;
        if (t < b) b = t;
    }
    return b;
}

/* sigma_q = (q - 1000) / 1000 m, q = 0..4000: -1.000 .. 3.000 m by 1 mm
 * (an exact division, so the reported sigma is the nearest double to q mm). */
#define SIG_LO (-1.0)
#define SIG_STEP 0.001
#define SIG_N 4001
#define SIG_Q0 1000
#define SIG_DEN 1000
#define SIGMA(q) ((double)((q) - SIG_Q0) / (double)SIG_DEN)

/* Where each sector of the reduction comes from (--stand-rows): per
 * spacing, each sector's stand and tree; per stand (spacing-major), its
 * growth step. */
typedef struct { dvec stand[8], tree[8]; double *step; } reduction_rows;

/* The reduction's inputs: per spacing a, the teacher radius, the target and
 * the Voronoi territory of every interior sector of every stand, and the
 * summed growth steps; rows (may be NULL) receives where each came from. */
static cs_status reduction_gather(const exp_opts *o, double beta, const irred_cfg *c, dvec rt[8], dvec rs[8],
                                  dvec bb[8], double step_sum[8], reduction_rows *rows, double *worst)
{
    cs_status st = CS_OK;
    for (size_t a = 0; a < c->nd && !st; a++)
        for (int k = 0; k < o->stands && !st; k++) {
            stand *sd = NULL;
            st = irred_stand(&o->rd, &sd, c->ds[a], k);
            if (st) break;
            double *r = malloc(sd->s->n * NS * sizeof *r);
            teacher_params p;
            EXP_TEACHER_PARAMS(&o->rd, &p);
            p.beta = beta;
            teacher_info inf;
            st = r ? stand_grow(sd, &p, NULL, r, &inf, worst) : cs_err(CS_ENOMEM, "experiments: out of memory");
            if (!st) step_sum[a] += inf.step;
            if (!st && rows) rows->step[a * (size_t)o->stands + (size_t)k] = inf.step;
            for (size_t i = 0; i < sd->s->n && !st; i++) {
                if (!stems_interior(sd->s, i)) continue;
                for (int s = 0; s < NS && !st; s++) {
                    st = dvec_push(&rt[a], r[i * NS + s]);
                    if (!st) st = dvec_push(&rs[a], sd->rstar[i * NS + s]);
                    if (!st) st = dvec_push(&bb[a], territory(sd->s, i, crown_theta(s)));
                    if (!st && rows) st = dvec_push(&rows->stand[a], (double)k);
                    if (!st && rows) st = dvec_push(&rows->tree[a], (double)i);
                }
            }
            free(r);
            stand_free(sd);
        }
    return st;
}

/* irreducibility/reduction_<tag>_sectors.tsv: one row per interior sector
 * (spacing, stand, tree, sector), with the sigma grid it is searched on. */
static cs_status write_reduction_sectors(const exp_opts *o, double beta, const prov *pv, double worst,
                                         const irred_cfg *c, const dvec rt[8], const dvec rs[8], const dvec bb[8],
                                         const reduction_rows *rows)
{
    prov rp = *pv;
    tsv_writer *w = NULL;
    char path[512];
    cs_status st = irred_open(o, "reduction", "_sectors", beta, &rp, worst, &w, path, sizeof path);
    if (st) return st;
    tsv_writer_meta(w, "sectors",
                    "every interior sector: the teacher's radius, the target r* and the territory b (Eq. 4); step_m is "
                    "the stand's growth step");
    tsv_writer_meta(w, "sigma_grid", "sigma_q = (q - %d) / %d m, q = 0..%d", SIG_Q0, SIG_DEN, SIG_N - 1);
    tsv_writer_columns(w, "spacing_m\tstand\ttree\tsector\tr_teacher_m\tr_star_m\tterritory_m\tstep_m");
    for (size_t a = 0; a < c->nd; a++)
        for (size_t e = 0; e < rt[a].n; e++) {
            size_t k = (size_t)rows->stand[a].v[e];
            tsv_writer_dbl(w, c->ds[a]);
            tsv_writer_long(w, (long)k);
            tsv_writer_long(w, (long)rows->tree[a].v[e]);
            tsv_writer_long(w, (long)(e % NS));
            tsv_writer_dbl(w, rt[a].v[e]);
            tsv_writer_dbl(w, rs[a].v[e]);
            tsv_writer_dbl(w, bb[a].v[e]);
            tsv_writer_dbl(w, rows->step[a * (size_t)o->stands + k]);
            tsv_writer_endrow(w);
        }
    return unit_out_finish(w, &rp, path);
}

/* miss[a][q]: summed |r_t - min(r*, b - sigma_q)| over the sectors of spacing a. */
static void reduction_miss(size_t nd, const dvec *rt, const dvec *rs, const dvec *bb, double *miss)
{
    for (size_t a = 0; a < nd; a++)
        for (int q = 0; q < SIG_N; q++) {
            double sig = SIGMA(q), sum = 0.0;
            for (size_t e = 0; e < rt[a].n; e++) sum += fabs(rt[a].v[e] - fmin(rs[a].v[e], bb[a].v[e] - sig));
            miss[a * SIG_N + q] = sum;
        }
}

cs_status exp_irreducibility_reduction(const exp_opts *o, double beta)
{
    prov pv;
    exp_prov_begin(&pv, "irreducibility", &o->rd, o->argc, o->argv);
    irred_cfg c;
    cs_status st = irred_cfg_load(&c);
    if (st) return st;
    /* Per spacing: triples (r_teacher, r*, b) of every interior sector. */
    dvec rt[8], rs[8], bb[8];
    memset(rt, 0, sizeof rt); memset(rs, 0, sizeof rs); memset(bb, 0, sizeof bb);
    double step_sum[8] = {0}, worst = 0.0;
    reduction_rows rows;
    memset(&rows, 0, sizeof rows);
    if (o->stand_rows) {
        rows.step = calloc(c.nd * (size_t)o->stands, sizeof *rows.step);
        if (!rows.step) st = cs_err(CS_ENOMEM, "experiments: out of memory");
    }
    if (!st) st = reduction_gather(o, beta, &c, rt, rs, bb, step_sum, o->stand_rows ? &rows : NULL, &worst);
    double *miss = st ? NULL : calloc(c.nd * SIG_N, sizeof *miss);
    if (!st && !miss) st = cs_err(CS_ENOMEM, "experiments: out of memory");
    size_t ntot = 0;
    double steptot = 0.0;
    for (size_t a = 0; a < c.nd; a++) { ntot += rt[a].n; steptot += step_sum[a]; }
    if (!st) reduction_miss(c.nd, rt, rs, bb, miss);
    tsv_writer *w = NULL;
    char path[512];
    if (!st && o->stand_rows) st = write_reduction_sectors(o, beta, &pv, worst, &c, rt, rs, bb, &rows);
    if (!st) st = irred_open(o, "reduction", "", beta, &pv, worst, &w, path, sizeof path);
    if (!st) {
        int qbest = 0;
        double best = INFINITY;
        for (int q = 0; q < SIG_N; q++) {
            double sum = 0.0;
            for (size_t a = 0; a < c.nd; a++) sum += miss[a * SIG_N + q];
            if (sum < best) { best = sum; qbest = q; }
        }
        double sig = SIGMA(qbest);
        double step_mean = steptot / (double)(o->stands * (int)c.nd);
        tsv_writer_meta(w, "reduction", "r = min(r*, b - sigma) at sector centres (Eq. 4); sigma grid %.3f:%.3f:%.3f m",
                        SIG_LO, SIG_STEP, SIG_LO + SIG_STEP * (SIG_N - 1));
        tsv_writer_meta(w, "scope",
                        "pooled row (spacing_m = 0): one sigma for all spacings; spacing rows use that sigma, own_* "
                        "their own best");
        tsv_writer_columns(w,
                           "scope\tspacing_m\tsectors\tsigma_m\tmiss_m\tstep_m\tmiss_steps\town_sigma_m\town_miss_m");
        for (int pooled = 1; pooled >= 0; pooled--)
            for (size_t a = 0; a < (pooled ? 1 : c.nd); a++) {
                size_t nsec = pooled ? ntot : rt[a].n;
                double m = pooled ? best / (double)ntot : miss[a * SIG_N + qbest] / (double)rt[a].n;
                double stp = pooled ? step_mean : step_sum[a] / (double)o->stands;
                int qo = qbest;
                if (!pooled)
                    for (int q = 0; q < SIG_N; q++) if (miss[a * SIG_N + q] < miss[a * SIG_N + qo]) qo = q;
                tsv_writer_str(w, pooled ? "pooled" : "spacing");
                tsv_writer_dbl(w, pooled ? 0.0 : c.ds[a]);
                tsv_writer_long(w, (long)nsec);
                tsv_writer_dbl(w, sig);
                tsv_writer_dbl(w, m);
                tsv_writer_dbl(w, stp);
                tsv_writer_dbl(w, m / stp);
                tsv_writer_dbl(w, SIGMA(qo));
                tsv_writer_dbl(w, pooled ? m : miss[a * SIG_N + qo] / (double)rt[a].n);
                tsv_writer_endrow(w);
            }
        fprintf(stderr, "irreducibility reduction (%s): sigma=%.3f miss=%.4f m = %.2f steps\n", o->tag, sig,
                best / (double)ntot, best / (double)ntot / step_mean);
        st = unit_out_finish(w, &pv, path);
    }
    free(miss);
    free(rows.step);
    for (size_t a = 0; a < 8; a++) {
        free(rt[a].v), free(rs[a].v), free(bb[a].v);
        free(rows.stand[a].v), free(rows.tree[a].v);
    }
    return st;
}

