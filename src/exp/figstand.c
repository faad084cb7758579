/* figstand: the figure stands of E1, E8 and E9 and their numbers on stand k of each family
 * (design.md §7 E1/E8/E9, §6.1); see figstand.h. Stand k of a family uses the figure's seed key
 * (fig/mechanism, fig/pointcloud, fig/hero) with stand index k: seed_derive(key, d, k,
 * stems|crowns). Statistics pool interior trees (exp_common.h). */
#include "figstand.h"
#include "estimator.h"
#include "gate.h"
#include "paths.h"
#include "stand_grow.h"
#include <stdio.h>
#include <stdlib.h>

#define NS CROWN_NSEC

cs_status figstand_stand_stats(const stand *sd, const double *r, dvec g[3], double *cov, double *w, size_t *trees)
{
    cs_status st = exp_stand_metrics(sd, r, g, cov, trees);
    if (!st) st = teacher_worst_overlap(sd->s->x, sd->s->y, r, sd->s->n, w);
    return st;
}

cs_status figstand_cell_close(dvec g[3], double cover, double overlap, size_t trees, cs_status st,
                              figstand_cell *res)
{
    for (int k = 0; k < 3 && !st; k++) st = est_median(g[k].v, g[k].n, &res->k[k]);
    res->cover = cover;
    res->overlap = overlap;
    res->trees = trees;
    for (int k = 0; k < 3; k++) free(g[k].v);
    return st;
}

/* The E1 ablation's arms at the gate's ablation spacing; the table unit, the figure unit and
 * the replicates share them. */
const char *const figstand_ablation_arms[3] = {"coupling_off", "abrasion_off", "both_on"};
const int figstand_ablation_coupled[3] = {0, 1, 1};

cs_status figstand_ablation_gate(double *d, double beta[3])
{
    double btrain;
    cs_status st = gate_read_value(PATHS_GATE("mechanism"), "ablation_spacing_m", 0, d);
    if (!st) st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &btrain);
    if (st) return st;
    beta[0] = btrain;
    beta[1] = 0.0;
    beta[2] = btrain;
    return CS_OK;
}

/* The statistics of one grown stand (a figure stand) as a cell. */
static cs_status stand_cell(const stand *sd, const double *r, figstand_cell *res)
{
    dvec g[3] = {{0}, {0}, {0}};
    double cov = 0.0, w = 0.0;
    size_t trees = 0;
    cs_status st = figstand_stand_stats(sd, r, g, &cov, &w, &trees);
    return figstand_cell_close(g, cov, w, trees, st, res);
}

cs_status figstand_mechanism_grow(const exp_opts *o, unsigned k, double d, const double beta[3], stand **sd,
                                  double **r, double *worst, figstand_cell fres[3])
{
    *r = NULL;
    cs_status st = exp_stand_alloc(&o->rd, sd, stems_hardcore, d, EXP_FIG_L, exp_fig_c(&o->rd), "fig/mechanism", k);
    if (st) return st;
    size_t n = (*sd)->s->n;
    *r = malloc(3 * n * NS * sizeof **r);
    if (!*r) return cs_err(CS_ENOMEM, "experiments: out of memory");
    for (int a = 0; a < 3 && !st; a++) {
        teacher_params p;
        EXP_TEACHER_PARAMS(&o->rd, &p);
        p.coupled = figstand_ablation_coupled[a];
        p.beta = beta[a];
        st = stand_grow(*sd, &p, NULL, *r + (size_t)a * n * NS, NULL, worst);
    }
    for (int a = 0; a < 3 && !st; a++) st = stand_cell(*sd, *r + (size_t)a * n * NS, &fres[a]);
    return st;
}

cs_status figstand_mechanism(const exp_opts *o, unsigned k, figstand_arm out[3])
{
    double d, beta[3], worst = 0.0;
    cs_status st = figstand_ablation_gate(&d, beta);
    if (st) return st;
    stand *sd = NULL;
    double *r = NULL;
    figstand_cell fres[3];
    st = figstand_mechanism_grow(o, k, d, beta, &sd, &r, &worst, fres);
    for (int a = 0; a < 3 && !st; a++) {
        snprintf(out[a].arm, sizeof out[a].arm, "%s", figstand_ablation_arms[a]);
        out[a].d = d;
        for (int q = 0; q < 3; q++) out[a].k[q] = fres[a].k[q];
        out[a].cover = fres[a].cover;
        out[a].overlap = fres[a].overlap;
        out[a].trees = fres[a].trees;
    }
    free(r);
    stand_free(sd);
    return st;
}

cs_status figstand_pointcloud(const exp_opts *o, double d, double beta, unsigned k, figstand_pc_row *row,
                              double *worst)
{
    stand *sd = NULL;
    cs_status st = exp_stand_alloc(&o->rd, &sd, stems_hardcore, d, EXP_FIG_L, exp_fig_c(&o->rd), "fig/pointcloud", k);
    if (st) return st;
    size_t n = sd->s->n;
    double *rc = malloc(n * NS * sizeof *rc), *ru = malloc(n * NS * sizeof *ru);
    unsigned char *fz = malloc(n * NS);
    if (!rc || !ru || !fz) st = cs_err(CS_ENOMEM, "experiments: out of memory");
    teacher_params p;
    EXP_TEACHER_PARAMS(&o->rd, &p);
    p.beta = beta;
    p.frozen_out = fz;
    if (!st) st = stand_grow(sd, &p, NULL, rc, NULL, worst);
    p.coupled = 0;
    p.frozen_out = NULL;
    if (!st) st = stand_grow(sd, &p, NULL, ru, NULL, NULL);
    size_t m = 0, contact = 0, oc = 0, ou = 0;
    for (size_t i = 0; i < n && !st; i++) {
        if (!stems_interior(sd->s, i)) continue;
        m++;
        int any = 0;
        for (int s = 0; s < NS; s++) any |= fz[i * NS + s];
        contact += (size_t)any;
        int c_ov = 0, u_ov = 0;
        for (size_t j = 0; j < n; j++) {
            if (j == i) continue;
            const stems *S = sd->s;
            if (est_clearance(S->x[i], S->y[i], rc + i * NS, S->x[j], S->y[j], rc + j * NS) < 0.0) c_ov = 1;
            if (est_clearance(S->x[i], S->y[i], ru + i * NS, S->x[j], S->y[j], ru + j * NS) < 0.0) u_ov = 1;
        }
        oc += (size_t)c_ov;
        ou += (size_t)u_ov;
    }
    if (!st) {
        row->stems = n;
        row->trees = m;
        row->contact = (double)contact / (double)m;
        row->ovl_c = (double)oc / (double)m;
        row->ovl_u = (double)ou / (double)m;
        row->k1_c = exp_stand_k1(sd, rc);
        row->k1_u = exp_stand_k1(sd, ru);
    }
    free(rc); free(ru); free(fz);
    stand_free(sd);
    return st;
}

cs_status figstand_hero_stems(const exp_opts *o, double d, unsigned k, size_t *stems_n)
{
    stand *sd = NULL;
    cs_status st = exp_stand_alloc(&o->rd, &sd, stems_hardcore, d, EXP_FIG_L, exp_fig_c(&o->rd), "fig/hero", k);
    if (!st) *stems_n = sd->s->n;
    stand_free(sd);
    return st;
}
