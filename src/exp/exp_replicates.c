/* exp_replicates: the replicate stands of the numbers that rest on one figure stand
 * (design.md §6.1): the E1 figure stand (hard-core, 3.5 m, L = 36 m; its ablation arms), the
 * E8 point-cloud stands (5, 4, 3 m; coupled and uncoupled) and the E9 hero stems (3.0 and
 * 6.5 m). Stand k of a family is the figure's own key with stand index k (seed_derive(key, d,
 * k, stems|crowns)): the same stems process and crown-draw distribution, seeds disjoint from
 * the figure's (k = 0, included so that the claims can check that this code gives the
 * figure's numbers bit for bit). Each number is computed by the function the figure unit
 * uses (figstand.c: figstand_mechanism, figstand_pointcloud, figstand_hero_stems).
 * Output replicates/figure_stands.tsv, one row per (family, arm, spacing, stand): family arm
 * spacing_m stand stems trees k1_m k2_m k3_m cover overlap_m contact_pct (nan where the
 * family does not define a column). */
#include "exp_replicates.h"
#include "exp_common.h"
#include "figstand.h"
#include "gate.h"
#include "paths.h"
#include "unit_out.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct {
    const char *family;
    char arm[16];
    double d, stems, trees, k[3], cover, overlap, contact_pct;
    unsigned stand;
} rep_row;

#define ROWS_PER_STAND 11 /* 3 E1 arms, 3 x 2 E8 stands, 2 E9 spacings */

static void put(rep_row *r, const char *family, const char *arm, double d, unsigned k, double stems, double trees,
                const double kk[3], double cover, double overlap, double contact_pct)
{
    r->family = family;
    snprintf(r->arm, sizeof r->arm, "%.15s", arm);
    r->d = d;
    r->stand = k;
    r->stems = stems;
    r->trees = trees;
    for (int q = 0; q < 3; q++) r->k[q] = kk ? kk[q] : NAN;
    r->cover = cover;
    r->overlap = overlap;
    r->contact_pct = contact_pct;
}

/* The ROWS_PER_STAND rows of stand k; *worst: the coupled growths' worst overlap. */
static cs_status stand_rows(const exp_opts *o, unsigned k, double btrain, rep_row *out, double *worst)
{
    figstand_arm fa[3];
    size_t n = 0;
    cs_status st = figstand_mechanism(o, k, fa);
    for (int a = 0; a < 3 && !st; a++) {
        put(&out[n++], "mechanism", fa[a].arm, fa[a].d, k, NAN, (double)fa[a].trees, fa[a].k, fa[a].cover,
            fa[a].overlap, NAN);
        if (a > 0 && fa[a].overlap > *worst) *worst = fa[a].overlap; /* arm 0 is uncoupled */
    }
    static const double pcd[3] = {5.0, 4.0, 3.0};
    for (int i = 0; i < 3 && !st; i++) {
        figstand_pc_row pr;
        if ((st = figstand_pointcloud(o, pcd[i], btrain, k, &pr, worst))) break;
        double kc[3] = {pr.k1_c, NAN, NAN}, ku[3] = {pr.k1_u, NAN, NAN};
        put(&out[n++], "pointcloud", "coupled", pcd[i], k, (double)pr.stems, (double)pr.trees, kc, NAN, pr.ovl_c,
            100.0 * pr.contact);
        put(&out[n++], "pointcloud", "uncoupled", pcd[i], k, (double)pr.stems, (double)pr.trees, ku, NAN, pr.ovl_u,
            NAN);
    }
    static const double hd[2] = {3.0, 6.5};
    for (int i = 0; i < 2 && !st; i++) {
        size_t m;
        if (!(st = figstand_hero_stems(o, hd[i], k, &m)))
            put(&out[n++], "hero", "beta_train", hd[i], k, (double)m, NAN, NULL, NAN, NAN, NAN);
    }
    return st;
}

static void write_row(tsv_writer *w, const rep_row *r)
{
    tsv_writer_str(w, r->family);
    tsv_writer_str(w, r->arm);
    tsv_writer_dbl(w, r->d);
    tsv_writer_long(w, (long)r->stand);
    tsv_writer_dbl(w, r->stems);
    tsv_writer_dbl(w, r->trees);
    for (int q = 0; q < 3; q++) tsv_writer_dbl(w, r->k[q]);
    tsv_writer_dbl(w, r->cover);
    tsv_writer_dbl(w, r->overlap);
    tsv_writer_dbl(w, r->contact_pct);
    tsv_writer_endrow(w);
}

cs_status exp_replicates_run(const exp_opts *o)
{
    prov pv;
    exp_prov_begin(&pv, "replicates", &o->rd, o->argc, o->argv);
    double btrain;
    cs_status st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &btrain);
    if (st) return st;
    size_t nr = (size_t)o->stands * ROWS_PER_STAND;
    rep_row *rows = calloc(nr, sizeof *rows);
    if (!rows) return cs_err(CS_ENOMEM, "replicates: out of memory");
    double worst = 0.0;
    for (int k = 0; k < o->stands && !st; k++)
        st = stand_rows(o, (unsigned)k, btrain, rows + (size_t)k * ROWS_PER_STAND, &worst);
    tsv_writer *w = NULL;
    char path[512];
    if (!st) st = unit_out_open(o, "replicates", "figure_stands.tsv", &w, path, sizeof path);
    if (!st) {
        pv.worst_overlap_m = worst;
        snprintf(pv.seeds, sizeof pv.seeds,
                 "seed_derive(fig/mechanism|fig/pointcloud|fig/hero, d, k, stems|crowns), k = 0..%d (k = 0: the "
                 "figure's stand)",
                 o->stands - 1);
        st = prov_write(w, &pv);
        if (st) tsv_writer_abort(w);
    }
    if (!st) {
        unit_out_meta(w, o);
        tsv_writer_meta(w, "what",
                        "replicate stands of the one-stand figure numbers (design.md §6.1): E1 figure stand arms, E8 "
                        "point-cloud stands, E9 hero stems");
        tsv_writer_meta(w, "dieback", "%.17g (gates/mechanism.gate dieback_train; the E1 arms: the ablation's)",
                        btrain);
        tsv_writer_columns(
            w, "family\tarm\tspacing_m\tstand\tstems\ttrees\tk1_m\tk2_m\tk3_m\tcover\toverlap_m\tcontact_pct");
        for (size_t i = 0; i < nr; i++) write_row(w, &rows[i]);
        st = unit_out_finish(w, &pv, path);
    }
    free(rows);
    return st;
}
