/* experiments: E1 mechanism and E2 irreducibility units, and teacher figure
 * data (SPEC §7, §12; paper §3.2-3.3). Choices the spec leaves open, written
 * down here and in each file's provenance:
 *  - stands per cell: 8 (--stands), stand k of spacing d uses
 *    seed_derive(<experiment key>, d, k, "stems"/"crowns"); the E1 sweep rows
 *    of one spacing and the ablation share stands (identical stems and draws);
 *  - statistics pool interior trees (>= 2 d from the edge) over the stands of
 *    a cell: k-th NN clearance = median of the pooled values; cover = mean
 *    over stands of the interior-square cover;
 *  - E2 focal tree: the interior stem nearest the footprint centre; judged:
 *    its 4 nearest stems (est_knn); the perturbed run keeps the unperturbed
 *    mean height; magnitude = mean |dr| over the judged trees' 96 sectors,
 *    pooled over stands;
 *  - E2 reduction: sigma on a grid -1.000:0.001:3.000 m, one sigma for all
 *    interior sectors of all spacings pooled; miss in steps = pooled mean
 *    miss / pooled mean Delta at N = 48;
 *  - figures: hard-core stems c = 0.5, L = 36 m.
 * Outputs (columns; every file starts with the provenance block):
 *  mechanism/sweep.tsv     beta spacing_m stands trees k1_m k2_m k3_m cover
 *                          worst_overlap_m pass train_row   (16 rows)
 *  mechanism/ablation.tsv  arm(coupling_off|abrasion_off|both_on) coupled beta
 *                          spacing_m stands trees k1_m k2_m k3_m cover overlap_m
 *  irreducibility/perturb_<tag>.tsv  spacing_m beta nres stands judged responded
 *                          response_fraction magnitude_m step_m   (5 rows)
 *  irreducibility/refine_<tag>.tsv   scope(pooled|spacing) spacing_m nres stands
 *                          judged responded magnitude_m step_m step_ratio
 *                          magnitude_ratio   (pooled rows first; gate on pooled N=384)
 *  irreducibility/reduction_<tag>.tsv scope spacing_m sectors sigma_m miss_m step_m
 *                          miss_steps own_sigma_m own_miss_m (pooled row first)
 *  <exp>/figure_crowns.tsv panel spacing_m tree x_m y_m h_m interior r0..r23
 *  <exp>/figure_poly_<panel>_<d>.tsv tree x_m y_m h_m (97 rows per tree, figures)
 *  pointcloud/stats.tsv    spacing_m trees contact_fraction overlap_fraction_coupled
 *                          overlap_fraction_uncoupled k1_coupled_m k1_uncoupled_m */
#include "experiments.h"
#include "figdata.h"
#include "crown.h"
#include "estimator.h"
#include "gate.h"
#include "prov.h"
#include "stand.h"
#include "teacher.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NS CROWN_NSEC
#define GATES_DIR "gates"

typedef struct {
    const char *unit;
    const char *out;
    int stands;
    double beta;      /* NAN: the gate's dieback_train */
    const char *tag;  /* "train" | "field" */
    int argc;
    char **argv;
} exp_opts;

/* ---- shared helpers ------------------------------------------------------------ */

static cs_status gate_get1(const char *file, const char *key, double *v)
{
    char path[256];
    snprintf(path, sizeof path, GATES_DIR "/%s", file);
    return gate_read_value(path, key, 0, v);
}

/* Copy all values of a gate key into v (at most cap). */
static cs_status gate_getv(const char *file, const char *key, double *v, size_t cap, size_t *n)
{
    char path[256];
    snprintf(path, sizeof path, GATES_DIR "/%s", file);
    return gate_read_values(path, key, v, cap, n);
}

/* Grow one stand; keeps the worst self-check overlap seen in *worst. */
static cs_status grow(const stand *sd, const teacher_params *p, double *r, teacher_info *inf, double *worst)
{
    teacher_stand v;
    stand_view(sd, &v);
    teacher_info tmp;
    cs_status st = teacher_grow(&v, p, r, inf ? inf : &tmp);
    if (!st && p->coupled && worst) {
        double w = (inf ? inf : &tmp)->worst_overlap;
        if (w > *worst) *worst = w;
    }
    return st;
}

/* Growable double array. */
typedef struct { double *v; size_t n, cap; } dvec;
static cs_status dv_push(dvec *a, double x)
{
    if (a->n == a->cap) {
        size_t c = a->cap ? 2 * a->cap : 256;
        double *nv = realloc(a->v, c * sizeof *nv);
        if (!nv) return cs_err(CS_ENOMEM, "experiments: out of memory");
        a->v = nv;
        a->cap = c;
    }
    a->v[a->n++] = x;
    return CS_OK;
}

/* k = 1..3 NN clearances of the interior trees, appended to g[0..2]; interior cover. */
static cs_status stand_metrics(const stand *sd, const double *r, dvec g[3], double *cover, size_t *ntrees)
{
    const stems *s = sd->s;
    cs_status st = CS_OK;
    size_t m = 0;
    for (size_t i = 0; i < s->n && !st; i++) {
        if (!stems_interior(s, i)) continue;
        m++;
        for (int k = 1; k <= 3 && !st; k++) {
            double v;
            st = est_knn_clearance(s->x, s->y, r, s->n, i, k, &v);
            if (!st) st = dv_push(&g[k - 1], v);
        }
    }
    if (ntrees) *ntrees += m;
    if (st || !cover) return st;
    double lo = 2.0 * s->d, hi = s->L - 2.0 * s->d;
    return est_cover(s->x, s->y, r, s->n, lo, lo, hi, hi, cover);
}

static cs_status open_out(const exp_opts *o, const char *experiment, const char *file, tsv_writer **w,
                          char *path, size_t pathsz)
{
    snprintf(path, pathsz, "%s/%s/%s", o->out, experiment, file);
    return tsv_writer_open(w, path);
}

static cs_status finish(tsv_writer *w, prov *pv, const char *path)
{
    cs_status st = tsv_writer_commit(w);
    if (!st) fprintf(stderr, "wrote %s (%.1f s)\n", path, prov_now() - pv->t0);
    return st;
}

/* Metadata lines shared by all units (after the provenance block). */
static void common_meta(tsv_writer *w, const exp_opts *o)
{
    tsv_writer_meta(w, "stands_per_cell", "%d", o->stands);
    tsv_writer_meta(w, "teacher_resolution", "N = 48 unless a column says otherwise; gamma = 1");
}

/* ---- E1 mechanism ---------------------------------------------------------------- */

typedef struct { double k[3], cover, overlap; size_t trees; } cell_result;

/* One (stem process, d, params) cell over o->stands stands of key `key`. */
static cs_status run_cell(const exp_opts *o, const char *key, stand_kind kind, double d, double shape,
                          const teacher_params *p, cell_result *res, double *worst)
{
    dvec g[3] = {{0}, {0}, {0}};
    double cov_sum = 0.0, ovl = 0.0;
    size_t trees = 0;
    cs_status st = CS_OK;
    for (int k = 0; k < o->stands && !st; k++) {
        stand *sd = NULL;
        st = stand_alloc(&sd, kind, d, 12.0 * d, shape, key, (unsigned)k);
        if (st) break;
        double *r = malloc(sd->s->n * NS * sizeof *r);
        if (!r) st = cs_err(CS_ENOMEM, "experiments: out of memory");
        if (!st) st = grow(sd, p, r, NULL, worst);
        double cov = 0.0, w = 0.0;
        if (!st) st = stand_metrics(sd, r, g, &cov, &trees);
        if (!st) st = teacher_worst_overlap(sd->s->x, sd->s->y, r, sd->s->n, &w);
        cov_sum += cov;
        if (w > ovl) ovl = w;
        free(r);
        stand_free(sd);
    }
    for (int k = 0; k < 3 && !st; k++) st = est_median(g[k].v, g[k].n, &res->k[k]);
    res->cover = cov_sum / (double)o->stands;
    res->overlap = ovl;
    res->trees = trees;
    for (int k = 0; k < 3; k++) free(g[k].v);
    return st;
}

static cs_status unit_mechanism_sweep(const exp_opts *o)
{
    prov pv;
    prov_begin(&pv, "mechanism", o->argc, o->argv);
    double betas[16], ds[16], thr[4], btrain;
    size_t nb, nd;
    cs_status st = gate_getv("mechanism.gate", "dieback_sweep", betas, 16, &nb);
    if (!st) st = gate_getv("mechanism.gate", "spacings_m", ds, 16, &nd);
    if (!st) st = gate_get1("mechanism.gate", "clearance_k1_min_m", &thr[0]);
    if (!st) st = gate_get1("mechanism.gate", "clearance_k2_min_m", &thr[1]);
    if (!st) st = gate_get1("mechanism.gate", "clearance_k3_min_m", &thr[2]);
    if (!st) st = gate_get1("mechanism.gate", "cover_min", &thr[3]);
    if (!st) st = gate_get1("mechanism.gate", "dieback_train", &btrain);
    if (st) return st;
    cell_result *res = calloc(nb * nd, sizeof *res);
    if (!res) return cs_err(CS_ENOMEM, "experiments: out of memory");
    double worst = 0.0;
    for (size_t a = 0; a < nd && !st; a++)
        for (size_t b = 0; b < nb && !st; b++) {
            teacher_params p;
            teacher_params_default(&p);
            p.beta = betas[b];
            st = run_cell(o, "mechanism", STAND_LATTICE, ds[a], 0.04, &p, &res[a * nb + b], &worst);
            if (!st) fprintf(stderr, "mechanism sweep: d=%.1f beta=%.2f k1=%+.3f k2=%+.3f k3=%+.3f cover=%.3f\n",
                             ds[a], betas[b], res[a * nb + b].k[0], res[a * nb + b].k[1],
                             res[a * nb + b].k[2], res[a * nb + b].cover);
        }
    tsv_writer *w = NULL;
    char path[512];
    if (!st) st = open_out(o, "mechanism", "sweep.tsv", &w, path, sizeof path);
    if (st) { free(res); return st; }
    pv.worst_overlap_m = worst;
    snprintf(pv.seeds, sizeof pv.seeds, "seed_derive(mechanism,d,k,stems|crowns) k=0..%d", o->stands - 1);
    st = prov_write(w, &pv);
    if (st) { tsv_writer_abort(w); free(res); return st; }
    common_meta(w, o);
    tsv_writer_meta(w, "stems", "controlled lattice a = 0.04, L = 12 d");
    tsv_writer_meta(w, "statistic", "k-th NN clearance: median over interior trees pooled over stands; cover: mean over stands");
    tsv_writer_columns(w, "beta\tspacing_m\tstands\ttrees\tk1_m\tk2_m\tk3_m\tcover\tworst_overlap_m\tpass\ttrain_row");
    for (size_t a = 0; a < nd; a++)
        for (size_t b = 0; b < nb; b++) {
            const cell_result *c = &res[a * nb + b];
            int pass = c->k[0] >= thr[0] && c->k[1] >= thr[1] && c->k[2] >= thr[2] && c->cover >= thr[3];
            tsv_writer_dbl(w, betas[b]);
            tsv_writer_dbl(w, ds[a]);
            tsv_writer_long(w, o->stands);
            tsv_writer_long(w, (long)c->trees);
            for (int k = 0; k < 3; k++) tsv_writer_dbl(w, c->k[k]);
            tsv_writer_dbl(w, c->cover);
            tsv_writer_dbl(w, c->overlap);
            tsv_writer_long(w, pass);
            tsv_writer_long(w, betas[b] == btrain);
            tsv_writer_endrow(w);
        }
    free(res);
    return finish(w, &pv, path);
}

/* The E1 ablation's three arms (coupling off, abrasion off, both on) at the
 * gate's ablation spacing; the table unit and the figure unit share them. */
static const char *const ablation_arms[3] = {"coupling_off", "abrasion_off", "both_on"};
static const int ablation_coupled[3] = {0, 1, 1};

static cs_status ablation_gate(double *d, double beta[3])
{
    double btrain;
    cs_status st = gate_get1("mechanism.gate", "ablation_spacing_m", d);
    if (!st) st = gate_get1("mechanism.gate", "dieback_train", &btrain);
    if (st) return st;
    beta[0] = btrain;
    beta[1] = 0.0;
    beta[2] = btrain;
    return CS_OK;
}

static cs_status unit_mechanism_ablation(const exp_opts *o)
{
    prov pv;
    prov_begin(&pv, "mechanism", o->argc, o->argv);
    double d, beta[3];
    cs_status st = ablation_gate(&d, beta);
    if (st) return st;
    const char *const *arms = ablation_arms;
    const int *coupled = ablation_coupled;
    cell_result res[3];
    double worst = 0.0;
    for (int a = 0; a < 3 && !st; a++) {
        teacher_params p;
        teacher_params_default(&p);
        p.coupled = coupled[a];
        p.beta = beta[a];
        st = run_cell(o, "mechanism", STAND_LATTICE, d, 0.04, &p, &res[a], &worst);
        if (!st) fprintf(stderr, "mechanism ablation: %s k1=%+.3f k2=%+.3f k3=%+.3f cover=%.3f overlap=%.3g\n",
                         arms[a], res[a].k[0], res[a].k[1], res[a].k[2], res[a].cover, res[a].overlap);
    }
    tsv_writer *w = NULL;
    char path[512];
    if (!st) st = open_out(o, "mechanism", "ablation.tsv", &w, path, sizeof path);
    if (st) return st;
    pv.worst_overlap_m = worst;
    snprintf(pv.seeds, sizeof pv.seeds, "seed_derive(mechanism,%.1f,k,stems|crowns) k=0..%d (the sweep's stands)",
             d, o->stands - 1);
    st = prov_write(w, &pv);
    if (st) { tsv_writer_abort(w); return st; }
    common_meta(w, o);
    tsv_writer_meta(w, "stems", "controlled lattice a = 0.04, L = 12 d; identical stems and crown draws in all arms");
    tsv_writer_meta(w, "overlap", "worst overlap of the final crowns (teacher self-check measure), m");
    tsv_writer_columns(w, "arm\tcoupled\tbeta\tspacing_m\tstands\ttrees\tk1_m\tk2_m\tk3_m\tcover\toverlap_m");
    for (int a = 0; a < 3; a++) {
        tsv_writer_str(w, arms[a]);
        tsv_writer_long(w, coupled[a]);
        tsv_writer_dbl(w, beta[a]);
        tsv_writer_dbl(w, d);
        tsv_writer_long(w, o->stands);
        tsv_writer_long(w, (long)res[a].trees);
        for (int k = 0; k < 3; k++) tsv_writer_dbl(w, res[a].k[k]);
        tsv_writer_dbl(w, res[a].cover);
        tsv_writer_dbl(w, res[a].overlap);
        tsv_writer_endrow(w);
    }
    return finish(w, &pv, path);
}

/* ---- E2 irreducibility ------------------------------------------------------------- */

/* Interior stem nearest the footprint centre. */
static size_t focal_tree(const stems *s)
{
    size_t f = 0;
    double best = INFINITY, c = 0.5 * s->L;
    for (size_t i = 0; i < s->n; i++) {
        if (!stems_interior(s, i)) continue;
        double dd = hypot(s->x[i] - c, s->y[i] - c);
        if (dd < best) { best = dd; f = i; }
    }
    return f;
}

typedef struct { size_t judged, responded, sectors; double abs_sum, step_sum; int stands; } perturb_acc;

/* One stand at resolution nres: baseline and perturbed growth, accumulated. */
static cs_status perturb_stand(const stand *sd, double beta, int nres, double hfac, double tol, int njudge,
                               perturb_acc *acc, double *worst)
{
    size_t n = sd->s->n;
    double *ra = malloc(n * NS * sizeof *ra), *rb = malloc(n * NS * sizeof *rb), *h2 = malloc(n * sizeof *h2);
    cs_status st = (!ra || !rb || !h2) ? cs_err(CS_ENOMEM, "experiments: out of memory") : CS_OK;
    teacher_params p;
    teacher_params_default(&p);
    p.beta = beta;
    p.nres = nres;
    teacher_info ia;
    if (!st) st = grow(sd, &p, ra, &ia, worst);
    if (!st) {
        size_t f = focal_tree(sd->s);
        memcpy(h2, sd->h, n * sizeof *h2);
        h2[f] *= hfac;
        teacher_stand v;
        stand_view(sd, &v);
        v.h = h2;
        p.hbar = ia.hbar; /* the perturbation keeps the unperturbed mean height */
        teacher_info ib;
        st = teacher_grow(&v, &p, rb, &ib);
        if (!st && ib.worst_overlap > *worst) *worst = ib.worst_overlap;
        for (int k = 1; k <= njudge && !st; k++) {
            long j = est_knn(sd->s->x, sd->s->y, n, f, k);
            if (j < 0) { st = cs_err(CS_EINPUT, "experiments: focal tree has fewer than %d neighbours", njudge); break; }
            int resp = 0;
            for (int s = 0; s < NS; s++) {
                double dr = fabs(rb[(size_t)j * NS + s] - ra[(size_t)j * NS + s]);
                if (dr > tol) resp = 1;
                acc->abs_sum += dr;
                acc->sectors++;
            }
            acc->judged++;
            acc->responded += (size_t)resp;
        }
        acc->step_sum += ia.step;
        acc->stands++;
    }
    free(ra); free(rb); free(h2);
    return st;
}

typedef struct { double ds[8]; size_t nd; double hfac, tol; int njudge; double levels[8]; size_t nlev; } irred_cfg;

static cs_status irred_cfg_load(irred_cfg *c)
{
    double v;
    cs_status st = gate_getv("irreducibility.gate", "spacings_m", c->ds, 8, &c->nd);
    if (!st) st = gate_get1("irreducibility.gate", "height_factor", &c->hfac);
    if (!st) st = gate_get1("irreducibility.gate", "response_tol_m", &c->tol);
    if (!st) st = gate_get1("irreducibility.gate", "neighbours_judged", &v);
    if (!st) c->njudge = (int)v;
    if (!st) st = gate_getv("irreducibility.gate", "refine_levels", c->levels, 8, &c->nlev);
    return st;
}

static void irred_meta(tsv_writer *w, const exp_opts *o, double beta)
{
    common_meta(w, o);
    tsv_writer_meta(w, "dieback", "%.17g (%s)", beta, o->tag);
    tsv_writer_meta(w, "stems", "controlled lattice a = 0.04, L = 12 d");
    tsv_writer_meta(w, "focal", "interior stem nearest the footprint centre, height x 1.30, stand mean height kept");
    tsv_writer_meta(w, "judged", "the focal tree's 4 nearest stems; responds when any sector moves by > 1e-6 m");
}

/* Stand k of the E2 design at spacing d: controlled lattice, a = 0.04, L = 12 d. */
static cs_status irred_stand(stand **sd, double d, int k)
{
    return stand_alloc(sd, STAND_LATTICE, d, 12.0 * d, 0.04, "irreducibility", (unsigned)k);
}

/* Open irreducibility/<prefix>_<tag>.tsv and write the provenance block and
 * the shared metadata; on failure nothing is left open. */
static cs_status irred_open(const exp_opts *o, const char *prefix, double beta, prov *pv,
                            double worst, tsv_writer **w, char *path, size_t pathsz)
{
    char file[64];
    snprintf(file, sizeof file, "%s_%s.tsv", prefix, o->tag);
    cs_status st = open_out(o, "irreducibility", file, w, path, pathsz);
    if (st) return st;
    pv->worst_overlap_m = worst;
    snprintf(pv->seeds, sizeof pv->seeds, "seed_derive(irreducibility,d,k,stems|crowns) k=0..%d", o->stands - 1);
    st = prov_write(*w, pv);
    if (st) { tsv_writer_abort(*w); return st; }
    irred_meta(*w, o, beta);
    return CS_OK;
}

static cs_status unit_irred_perturb(const exp_opts *o, double beta)
{
    prov pv;
    prov_begin(&pv, "irreducibility", o->argc, o->argv);
    irred_cfg c;
    cs_status st = irred_cfg_load(&c);
    if (st) return st;
    perturb_acc acc[8];
    memset(acc, 0, sizeof acc);
    double worst = 0.0;
    for (size_t a = 0; a < c.nd && !st; a++) {
        for (int k = 0; k < o->stands && !st; k++) {
            stand *sd = NULL;
            st = irred_stand(&sd, c.ds[a], k);
            if (!st) st = perturb_stand(sd, beta, 48, c.hfac, c.tol, c.njudge, &acc[a], &worst);
            stand_free(sd);
        }
        if (!st) fprintf(stderr, "irreducibility perturb (%s): d=%.1f responded %zu/%zu\n", o->tag, c.ds[a],
                         acc[a].responded, acc[a].judged);
    }
    tsv_writer *w = NULL;
    char path[512];
    if (!st) st = irred_open(o, "perturb", beta, &pv, worst, &w, path, sizeof path);
    if (st) return st;
    tsv_writer_columns(w, "spacing_m\tbeta\tnres\tstands\tjudged\tresponded\tresponse_fraction\tmagnitude_m\tstep_m");
    for (size_t a = 0; a < c.nd; a++) {
        tsv_writer_dbl(w, c.ds[a]);
        tsv_writer_dbl(w, beta);
        tsv_writer_long(w, 48);
        tsv_writer_long(w, acc[a].stands);
        tsv_writer_long(w, (long)acc[a].judged);
        tsv_writer_long(w, (long)acc[a].responded);
        tsv_writer_dbl(w, (double)acc[a].responded / (double)acc[a].judged);
        tsv_writer_dbl(w, acc[a].abs_sum / (double)acc[a].sectors);
        tsv_writer_dbl(w, acc[a].step_sum / (double)acc[a].stands);
        tsv_writer_endrow(w);
    }
    return finish(w, &pv, path);
}

static cs_status unit_irred_refine(const exp_opts *o, double beta)
{
    prov pv;
    prov_begin(&pv, "irreducibility", o->argc, o->argv);
    irred_cfg c;
    cs_status st = irred_cfg_load(&c);
    if (st) return st;
    perturb_acc acc[8][8], pool[8];
    memset(acc, 0, sizeof acc);
    memset(pool, 0, sizeof pool);
    double worst = 0.0;
    for (size_t l = 0; l < c.nlev && !st; l++) {
        for (size_t a = 0; a < c.nd && !st; a++)
            for (int k = 0; k < o->stands && !st; k++) {
                stand *sd = NULL;
                st = irred_stand(&sd, c.ds[a], k);
                if (!st) st = perturb_stand(sd, beta, (int)c.levels[l], c.hfac, c.tol, c.njudge, &acc[l][a], &worst);
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
    if (!st) st = irred_open(o, "refine", beta, &pv, worst, &w, path, sizeof path);
    if (st) return st;
    tsv_writer_meta(w, "scope", "pooled rows (spacing_m = 0) pool every judged sector of every spacing; gate on pooled");
    tsv_writer_columns(w, "scope\tspacing_m\tnres\tstands\tjudged\tresponded\tmagnitude_m\tstep_m\tstep_ratio\tmagnitude_ratio");
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
    return finish(w, &pv, path);
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
#define SIGMA(q) ((double)((q) - 1000) / 1000.0)

static cs_status unit_irred_reduction(const exp_opts *o, double beta)
{
    prov pv;
    prov_begin(&pv, "irreducibility", o->argc, o->argv);
    irred_cfg c;
    cs_status st = irred_cfg_load(&c);
    if (st) return st;
    /* Per spacing: triples (r_teacher, r*, b) of every interior sector. */
    dvec rt[8], rs[8], bb[8];
    memset(rt, 0, sizeof rt); memset(rs, 0, sizeof rs); memset(bb, 0, sizeof bb);
    double step_sum[8] = {0}, worst = 0.0;
    for (size_t a = 0; a < c.nd && !st; a++)
        for (int k = 0; k < o->stands && !st; k++) {
            stand *sd = NULL;
            st = irred_stand(&sd, c.ds[a], k);
            if (st) break;
            double *r = malloc(sd->s->n * NS * sizeof *r);
            teacher_params p;
            teacher_params_default(&p);
            p.beta = beta;
            teacher_info inf;
            st = r ? grow(sd, &p, r, &inf, &worst) : cs_err(CS_ENOMEM, "experiments: out of memory");
            if (!st) step_sum[a] += inf.step;
            for (size_t i = 0; i < sd->s->n && !st; i++) {
                if (!stems_interior(sd->s, i)) continue;
                for (int s = 0; s < NS && !st; s++) {
                    st = dv_push(&rt[a], r[i * NS + s]);
                    if (!st) st = dv_push(&rs[a], sd->rstar[i * NS + s]);
                    if (!st) st = dv_push(&bb[a], territory(sd->s, i, crown_theta(s)));
                }
            }
            free(r);
            stand_free(sd);
        }
    /* miss[a][q]: summed |r_t - min(r*, b - sigma_q)| for spacing a. */
    double *miss = st ? NULL : calloc(c.nd * SIG_N, sizeof *miss);
    if (!st && !miss) st = cs_err(CS_ENOMEM, "experiments: out of memory");
    size_t ntot = 0;
    double steptot = 0.0;
    for (size_t a = 0; a < c.nd && !st; a++) {
        ntot += rt[a].n;
        steptot += step_sum[a];
        for (int q = 0; q < SIG_N; q++) {
            double sig = SIGMA(q), sum = 0.0;
            for (size_t e = 0; e < rt[a].n; e++) sum += fabs(rt[a].v[e] - fmin(rs[a].v[e], bb[a].v[e] - sig));
            miss[a * SIG_N + q] = sum;
        }
    }
    tsv_writer *w = NULL;
    char path[512];
    if (!st) st = irred_open(o, "reduction", beta, &pv, worst, &w, path, sizeof path);
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
        tsv_writer_meta(w, "scope", "pooled row (spacing_m = 0): one sigma for all spacings; spacing rows use that sigma, own_* their own best");
        tsv_writer_columns(w, "scope\tspacing_m\tsectors\tsigma_m\tmiss_m\tstep_m\tmiss_steps\town_sigma_m\town_miss_m");
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
        st = finish(w, &pv, path);
    }
    free(miss);
    for (size_t a = 0; a < 8; a++) { free(rt[a].v); free(rs[a].v); free(bb[a].v); }
    return st;
}

/* ---- figure data --------------------------------------------------------------------- */

/* Crowns of one panel: one row per tree: panel, tree, x, y, h, interior, r0..r23. */
static void write_crowns(tsv_writer *w, const char *panel, double d, const stand *sd, const double *r)
{
    for (size_t i = 0; i < sd->s->n; i++) {
        tsv_writer_str(w, panel);
        tsv_writer_dbl(w, d);
        tsv_writer_long(w, (long)i);
        tsv_writer_dbl(w, sd->s->x[i]);
        tsv_writer_dbl(w, sd->s->y[i]);
        tsv_writer_dbl(w, sd->h[i]);
        tsv_writer_long(w, stems_interior(sd->s, i));
        for (int s = 0; s < NS; s++) tsv_writer_dbl(w, r[i * NS + s]);
        tsv_writer_endrow(w);
    }
}

static void crown_columns(tsv_writer *w)
{
    char cols[1024];
    int off = snprintf(cols, sizeof cols, "panel\tspacing_m\ttree\tx_m\ty_m\th_m\tinterior");
    for (int s = 0; s < NS; s++) off += snprintf(cols + off, sizeof cols - (size_t)off, "\tr%d", s);
    tsv_writer_columns(w, cols);
}

static cs_status write_polygons(const exp_opts *o, prov *pv, const char *experiment, const char *panel, double d,
                                const stand *sd, const double *r, double k1)
{
    char file[128], path[512];
    snprintf(file, sizeof file, "figure_poly_%s_%.1f.tsv", panel, d);
    tsv_writer *w = NULL;
    cs_status st = open_out(o, experiment, file, &w, path, sizeof path);
    if (st) return st;
    st = prov_write(w, pv);
    if (st) { tsv_writer_abort(w); return st; }
    size_t n = sd->s->n;
    tsv_writer_meta(w, "panel", "%s, spacing %.2f m, footprint %.0f m, %zu trees, %d rows per tree", panel, d, sd->s->L, n, FIGDATA_ROWS);
    tsv_writer_meta(w, "k1_median_m", "%.3f", k1);
    st = figdata_write_polygons(w, n, sd->s->x, sd->s->y, sd->h, r, NULL, NULL);
    if (st) { tsv_writer_abort(w); return st; }
    return tsv_writer_commit(w);
}

/* Median k1 clearance of the interior trees of one stand. */
static double stand_k1(const stand *sd, const double *r)
{
    dvec g[3] = {{0}, {0}, {0}};
    double med = NAN;
    if (!stand_metrics(sd, r, g, NULL, NULL)) est_median(g[0].v, g[0].n, &med);
    for (int k = 0; k < 3; k++) free(g[k].v);
    return med;
}

#define FIG_L 36.0
#define FIG_C 0.5

static cs_status unit_fig_mechanism(const exp_opts *o)
{
    prov pv;
    prov_begin(&pv, "mechanism", o->argc, o->argv);
    double d, beta[3];
    cs_status st = ablation_gate(&d, beta);
    if (st) return st;
    stand *sd = NULL;
    st = stand_alloc(&sd, STAND_HARDCORE, d, FIG_L, FIG_C, "fig/mechanism", 0);
    if (st) return st;
    size_t n = sd->s->n;
    double *r = malloc(3 * n * NS * sizeof *r);
    if (!r) { stand_free(sd); return cs_err(CS_ENOMEM, "experiments: out of memory"); }
    const char *const *arms = ablation_arms;
    const int *coupled = ablation_coupled;
    double worst = 0.0;
    for (int a = 0; a < 3 && !st; a++) {
        teacher_params p;
        teacher_params_default(&p);
        p.coupled = coupled[a];
        p.beta = beta[a];
        st = grow(sd, &p, r + (size_t)a * n * NS, NULL, &worst);
    }
    tsv_writer *w = NULL;
    char path[512];
    if (!st) st = open_out(o, "mechanism", "figure_crowns.tsv", &w, path, sizeof path);
    if (!st) {
        pv.worst_overlap_m = worst;
        snprintf(pv.seeds, sizeof pv.seeds, "seed_derive(fig/mechanism,%.1f,0,stems|crowns)", d);
        st = prov_write(w, &pv);
        if (st) tsv_writer_abort(w);
    }
    if (!st) {
        tsv_writer_meta(w, "stems", "hard-core Poisson c = %.2f, d = %.2f m, L = %.0f m; one stand, identical in all panels", FIG_C, d, FIG_L);
        /* NN clearance on the stand shown (interior trees), for the panel captions. */
        for (int a = 0; a < 3; a++)
            tsv_writer_meta(w, arms[a], "median k1 clearance %.3f m", stand_k1(sd, r + (size_t)a * n * NS));
        crown_columns(w);
        for (int a = 0; a < 3; a++) write_crowns(w, arms[a], d, sd, r + (size_t)a * n * NS);
        for (int a = 0; a < 3 && !st; a++)
            st = write_polygons(o, &pv, "mechanism", arms[a], d, sd, r + (size_t)a * n * NS,
                                stand_k1(sd, r + (size_t)a * n * NS));
        if (st) tsv_writer_abort(w);
        else st = finish(w, &pv, path);
    }
    free(r);
    stand_free(sd);
    return st;
}

/* Hero (E9) and point cloud (E8): hard-core stands at L = 36 m over spacings;
 * crown draws shared within a column (one stand per spacing, both rows). */
static cs_status unit_fig_stands(const exp_opts *o, const char *experiment, const char *key,
                                 const double *ds, size_t nd, const double *betas, const char **rows,
                                 size_t nrows, int with_uncoupled)
{
    prov pv;
    prov_begin(&pv, experiment, o->argc, o->argv);
    tsv_writer *w = NULL;
    char path[512];
    cs_status st = open_out(o, experiment, "figure_crowns.tsv", &w, path, sizeof path);
    if (st) return st;
    /* Grow everything first (the provenance needs the worst overlap). */
    size_t total = nd * (nrows + (size_t)with_uncoupled);
    stand **sds = calloc(nd, sizeof *sds);
    double **rs = calloc(total, sizeof *rs);
    double worst = 0.0;
    if (!sds || !rs) st = cs_err(CS_ENOMEM, "experiments: out of memory");
    for (size_t a = 0; a < nd && !st; a++) {
        st = stand_alloc(&sds[a], STAND_HARDCORE, ds[a], FIG_L, FIG_C, key, 0);
        for (size_t b = 0; b < nrows + (size_t)with_uncoupled && !st; b++) {
            double *r = malloc(sds[a]->s->n * NS * sizeof *r);
            rs[a * (nrows + (size_t)with_uncoupled) + b] = r;
            if (!r) { st = cs_err(CS_ENOMEM, "experiments: out of memory"); break; }
            teacher_params p;
            teacher_params_default(&p);
            if (b < nrows) p.beta = betas[b];
            else p.coupled = 0;
            st = grow(sds[a], &p, r, NULL, &worst);
        }
    }
    if (!st) {
        pv.worst_overlap_m = worst;
        snprintf(pv.seeds, sizeof pv.seeds, "seed_derive(%s,d,0,stems|crowns)", key);
        st = prov_write(w, &pv);
    }
    if (!st) {
        tsv_writer_meta(w, "stems", "hard-core Poisson c = %.2f, L = %.0f m; crown draws shared within a column", FIG_C, FIG_L);
        for (size_t b = 0; b < nrows; b++) tsv_writer_meta(w, rows[b], "dieback %.17g", betas[b]);
        crown_columns(w);
        for (size_t a = 0; a < nd; a++)
            for (size_t b = 0; b < nrows + (size_t)with_uncoupled; b++)
                write_crowns(w, b < nrows ? rows[b] : "uncoupled", ds[a], sds[a], rs[a * (nrows + (size_t)with_uncoupled) + b]);
        for (size_t a = 0; a < nd && !st; a++)
            for (size_t b = 0; b < nrows + (size_t)with_uncoupled && !st; b++) {
                const double *r = rs[a * (nrows + (size_t)with_uncoupled) + b];
                st = write_polygons(o, &pv, experiment, b < nrows ? rows[b] : "uncoupled", ds[a], sds[a], r,
                                    stand_k1(sds[a], r));
            }
        if (st) tsv_writer_abort(w);
        else st = finish(w, &pv, path);
    } else if (w) tsv_writer_abort(w);
    for (size_t a = 0; sds && a < nd; a++) stand_free(sds[a]);
    for (size_t k = 0; rs && k < total; k++) free(rs[k]);
    free(sds); free(rs);
    return st;
}

/* E8 numbers on the point-cloud stands: per spacing, the share of interior
 * crowns that made contact during coupled growth (a sector froze), the share
 * of interior crowns that interpenetrate a neighbour (some g(i,j) < 0) in
 * each arm, and the median NN clearance coupled vs uncoupled. */
static cs_status unit_pointcloud_stats(const exp_opts *o, const double *ds, size_t nd, double beta)
{
    prov pv;
    prov_begin(&pv, "pointcloud", o->argc, o->argv);
    typedef struct { size_t trees; double contact, ovl_c, ovl_u, k1_c, k1_u; } pc_row;
    pc_row rows[8];
    double worst = 0.0;
    cs_status st = CS_OK;
    for (size_t a = 0; a < nd && !st; a++) {
        stand *sd = NULL;
        st = stand_alloc(&sd, STAND_HARDCORE, ds[a], FIG_L, FIG_C, "fig/pointcloud", 0);
        if (st) break;
        size_t n = sd->s->n;
        double *rc = malloc(n * NS * sizeof *rc), *ru = malloc(n * NS * sizeof *ru);
        unsigned char *fz = malloc(n * NS);
        if (!rc || !ru || !fz) st = cs_err(CS_ENOMEM, "experiments: out of memory");
        teacher_params p;
        teacher_params_default(&p);
        p.beta = beta;
        p.frozen_out = fz;
        if (!st) st = grow(sd, &p, rc, NULL, &worst);
        p.coupled = 0;
        p.frozen_out = NULL;
        if (!st) st = grow(sd, &p, ru, NULL, NULL);
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
            rows[a].trees = m;
            rows[a].contact = (double)contact / (double)m;
            rows[a].ovl_c = (double)oc / (double)m;
            rows[a].ovl_u = (double)ou / (double)m;
            rows[a].k1_c = stand_k1(sd, rc);
            rows[a].k1_u = stand_k1(sd, ru);
        }
        free(rc); free(ru); free(fz);
        stand_free(sd);
    }
    tsv_writer *w = NULL;
    char path[512];
    if (!st) st = open_out(o, "pointcloud", "stats.tsv", &w, path, sizeof path);
    if (st) return st;
    pv.worst_overlap_m = worst;
    snprintf(pv.seeds, sizeof pv.seeds, "seed_derive(fig/pointcloud,d,0,stems|crowns)");
    st = prov_write(w, &pv);
    if (st) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "stems", "hard-core Poisson c = %.2f, L = %.0f m, one stand per spacing (the figure's)", FIG_C, FIG_L);
    tsv_writer_meta(w, "dieback", "%.17g", beta);
    tsv_writer_meta(w, "contact", "interior crowns with a sector frozen on contact during coupled growth");
    tsv_writer_columns(w, "spacing_m	trees	contact_fraction	overlap_fraction_coupled	overlap_fraction_uncoupled	k1_coupled_m	k1_uncoupled_m");
    for (size_t a = 0; a < nd; a++) {
        tsv_writer_dbl(w, ds[a]);
        tsv_writer_long(w, (long)rows[a].trees);
        tsv_writer_dbl(w, rows[a].contact);
        tsv_writer_dbl(w, rows[a].ovl_c);
        tsv_writer_dbl(w, rows[a].ovl_u);
        tsv_writer_dbl(w, rows[a].k1_c);
        tsv_writer_dbl(w, rows[a].k1_u);
        tsv_writer_endrow(w);
    }
    return finish(w, &pv, path);
}

/* ---- command handlers ----------------------------------------------------------------- */

static const char *RUN_HELP =
    "usage: crownshy run <unit> [--stands N] [--out DIR] [--beta B] [--tag train|field]\n"
    "units (each writes DIR/<experiment>/<file>.tsv, DIR defaults to build/results):\n"
    "  mechanism-sweep          E1: 16 rows beta x d on the controlled lattice -> mechanism/sweep.tsv\n"
    "  mechanism-ablation       E1: coupling off / abrasion off / both on at 3.5 m -> mechanism/ablation.tsv\n"
    "  irreducibility-perturb   E2: one tree 30% taller, 5 spacings -> irreducibility/perturb_<tag>.tsv\n"
    "  irreducibility-refine    E2: N in {48,96,192,384} -> irreducibility/refine_<tag>.tsv\n"
    "  irreducibility-reduction E2: best-fit Voronoi reduction -> irreducibility/reduction_<tag>.tsv\n"
    "  fig-mechanism            crowns of the three mechanism panels (hard-core, 3.5 m, L = 36 m)\n"
    "  fig-hero                 crowns of the hero figure (hard-core, L = 36 m, d = 3.0..6.5)\n"
    "  fig-pointcloud           E8: crowns of the point-cloud stands (hard-core, L = 36 m, 5/4/3 m, + uncoupled)\n"
    "                           and pointcloud/stats.tsv (contact share, coupled vs uncoupled NN clearance)\n"
    "options: --stands N stands per cell (default 8); --beta B die-back for E2 (default: the\n"
    "gate's dieback_train); --tag names the E2 output (default train).\n";

int exp_cmd_run(int argc, char **argv)
{
    exp_opts o = {.out = "build/results", .stands = EXP_STANDS_DEFAULT, .beta = NAN, .tag = "train",
                  .argc = argc, .argv = argv};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) { fputs(RUN_HELP, stdout); return 0; }
        int more = i + 1 < argc;
        if (!strcmp(argv[i], "--stands") && more) o.stands = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--out") && more) o.out = argv[++i];
        else if (!strcmp(argv[i], "--beta") && more) o.beta = atof(argv[++i]);
        else if (!strcmp(argv[i], "--tag") && more) o.tag = argv[++i];
        else if (argv[i][0] != '-' && !o.unit) o.unit = argv[i];
        else { fprintf(stderr, "crownshy run: bad argument '%s'\n%s", argv[i], RUN_HELP); return 2; }
    }
    if (!o.unit) { fprintf(stderr, "%s", RUN_HELP); return 2; }
    if (o.stands < 1 || o.stands > 10000) { fprintf(stderr, "crownshy run: --stands must be in 1..10000\n"); return 2; }
    if (strcmp(o.tag, "train") && strcmp(o.tag, "field")) { fprintf(stderr, "crownshy run: --tag must be train or field\n"); return 2; }
    if (!isnan(o.beta) && !(o.beta >= 0.0 && o.beta < 1.0)) { fprintf(stderr, "crownshy run: --beta must be in [0,1)\n"); return 2; }
    cs_status st = CS_OK;
    double beta = o.beta;
    if (isnan(beta) && !strncmp(o.unit, "irreducibility", 14)) {
        if (!strcmp(o.tag, "field")) { fprintf(stderr, "crownshy run: --tag field needs --beta (the calibrated field die-back)\n"); return 2; }
        st = gate_get1("mechanism.gate", "dieback_train", &beta);
    }
    if (!st) {
        if (!strcmp(o.unit, "mechanism-sweep")) st = unit_mechanism_sweep(&o);
        else if (!strcmp(o.unit, "mechanism-ablation")) st = unit_mechanism_ablation(&o);
        else if (!strcmp(o.unit, "irreducibility-perturb")) st = unit_irred_perturb(&o, beta);
        else if (!strcmp(o.unit, "irreducibility-refine")) st = unit_irred_refine(&o, beta);
        else if (!strcmp(o.unit, "irreducibility-reduction")) st = unit_irred_reduction(&o, beta);
        else if (!strcmp(o.unit, "fig-mechanism")) st = unit_fig_mechanism(&o);
        else if (!strcmp(o.unit, "fig-hero") || !strcmp(o.unit, "fig-pointcloud")) {
            double btrain;
            st = gate_get1("mechanism.gate", "dieback_train", &btrain);
            if (!st && !strcmp(o.unit, "fig-hero")) {
                const double ds[8] = {3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0, 6.5};
                double b[2] = {btrain, isnan(o.beta) ? btrain : o.beta};
                const char *rows[2] = {"beta_train", "beta_field"};
                /* beta_field comes from E5; without --beta only the train row is drawn. */
                st = unit_fig_stands(&o, "hero", "fig/hero", ds, 8, b, rows, isnan(o.beta) ? 1 : 2, 0);
            } else if (!st) {
                const double ds[3] = {5.0, 4.0, 3.0};
                const char *rows[1] = {"coupled"};
                st = unit_fig_stands(&o, "pointcloud", "fig/pointcloud", ds, 3, &btrain, rows, 1, 1);
                if (!st) st = unit_pointcloud_stats(&o, ds, 3, btrain);
            }
        } else { fprintf(stderr, "crownshy run: unknown unit '%s'\n%s", o.unit, RUN_HELP); return 2; }
    }
    if (st) fprintf(stderr, "crownshy run %s: %s\n", o.unit, cs_errmsg()[0] ? cs_errmsg() : cs_status_name(st));
    return cs_exit_code(st);
}

int exp_cmd_bench_teacher(int argc, char **argv)
{
    if (argc > 1 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        puts("usage: crownshy bench-teacher [reps]\n"
             "teacher ms per 144-tree controlled-lattice stand (d = 3.5 m, beta 0.06) at N = 48 and N = 384");
        return 0;
    }
    int reps = argc > 1 ? atoi(argv[1]) : 10;
    if (reps < 1) { fprintf(stderr, "bench-teacher: reps must be >= 1\n"); return 2; }
    const int levels[2] = {48, 384};
    for (int k = 0; k < 2; k++) {
        double ms = 0.0;
        cs_status st = teacher_bench(levels[k], k ? (reps + 3) / 4 : reps, &ms);
        if (st) { fprintf(stderr, "bench-teacher: %s\n", cs_errmsg()); return cs_exit_code(st); }
        printf("teacher_ms_per_stand_N%d\t%.3f\n", levels[k], ms);
    }
    return 0;
}
