/* mainset: E3/E4 data, generation and probes (see mainset.h). */
#include "mainset.h"
#include "estimator.h"
#include "gate.h"
#include "paths.h"
#include "seed.h"
#include "stand.h"
#include "stand_grow.h"
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

cs_status mainset_design_get(mainset_design *d)
{
    cs_status st;
    memset(d, 0, sizeof *d);
    crown_dist_default(&d->crowns);
    d->nres = 48;
    d->start_frac = 0.05;
    if ((st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &d->beta))) return st;
    if ((st = gate_read_value(PATHS_GATE("anisotropy"), "canonical_jitter", 0, &d->jitter))) return st;
    if ((st = gate_read_value(PATHS_GATE("main"), "estimator_agreement_tol_m", 0, &d->tol))) return st;
    if ((st = gate_read_values(PATHS_GATE("main"), "train_spacings_m", d->train_d, MAINSET_MAXSP, &d->ntrain)))
        return st;
    if ((st = gate_read_values(PATHS_GATE("main"), "unseen_spacings_m", d->unseen_d, MAINSET_MAXSP, &d->nunseen)))
        return st;
    if ((st = gate_read_values(PATHS_GATE("extrapolation"), "spacings_m", d->extrap_d, MAINSET_MAXSP, &d->nextrap)))
        return st;
    return CS_OK;
}

double mainset_eval_spacing(const mainset_design *d, size_t i, int *unseen)
{
    if (unseen) *unseen = i < d->nunseen;
    return i < d->nunseen ? d->unseen_d[i] : d->extrap_d[i - d->nunseen];
}

const char *mainset_probe_name(mainset_probe p)
{
    return p == MAINSET_SHUFFLED ? "shuffled" : p == MAINSET_ROTATED ? "rotated" : "generated";
}

/* Teacher stand k of experiment `exp` at spacing d; every interior stem
 * becomes one patch in ps. *added (may be NULL) gets the patches added. */
static cs_status add_stand_patches(const mainset_design *ds, const char *exp, double d, unsigned k,
                                   patch_set *ps, int *added, double *worst)
{
    stand *sd;
    cs_status st = stand_alloc_dist(&sd, stems_lattice, d, 12.0 * d, ds->jitter, exp, k, &ds->crowns);
    if (st) return st;
    size_t n = sd->s->n;
    double *r = malloc(n * CROWN_NSEC * sizeof *r);
    if (!r) { stand_free(sd); return cs_err(CS_ENOMEM, "out of memory"); }
    teacher_params tp;
    teacher_params_default(&tp);
    tp.beta = ds->beta;
    tp.nres = ds->nres;
    tp.start_frac = ds->start_frac;
    tp.dieback = (teacher_dieback)ds->dieback;
    st = stand_grow(sd, &tp, NULL, r, NULL, worst);
    patch_stand pst;
    if (!st) st = patch_stand_init(&pst, (int)n, sd->s->x, sd->s->y, r, sd->h, d);
    int cnt = 0;
    for (size_t i = 0; i < n && !st; i++) {
        if (!stems_interior(sd->s, i)) continue;
        patch p;
        st = patch_build(&pst, (int)i, &p);
        if (!st) st = patch_set_add(ps, &p);
        cnt++;
    }
    if (added) *added = cnt;
    free(r);
    stand_free(sd);
    return st;
}

cs_status mainset_train_build(const mainset_design *ds, int nstands, patch_set **out, double *worst)
{
    cs_status st = patch_set_alloc(out, (int)ds->ntrain * nstands * 100);
    for (size_t s = 0; s < ds->ntrain && !st; s++)
        for (int k = 0; k < nstands && !st; k++)
            st = add_stand_patches(ds, "main-train", ds->train_d[s], (unsigned)k, *out, NULL, worst);
    return st;
}

void mainset_eval_free(mainset_eval *e)
{
    if (e->ps) patch_set_free(e->ps);
    free(e->per_stand);
    free(e->teach);
    memset(e, 0, sizeof *e);
}

/* Focal NN clearances of patches [k0, k0+b) of ps with standardised
 * deviations x (b*T*P); rbuf holds b*T*P radii. */
static cs_status focal_nn(const patch_set *ps, int k0, int b, const float *x, double *rbuf, double *out)
{
    for (int k = 0; k < b; k++)
        patch_set_radii(ps, k0 + k, x + (size_t)k * PATCH_T * PATCH_P, rbuf + (size_t)k * PATCH_T * PATCH_P);
    return patch_focal_clearances(ps->px + (size_t)k0 * PATCH_T, ps->py + (size_t)k0 * PATCH_T, rbuf, b, 1, out);
}

cs_status mainset_eval_build(const mainset_design *ds, int nstands, double d, double scale,
                             mainset_eval *e, double *worst, double *maxdiff)
{
    memset(e, 0, sizeof *e);
    e->d = d;
    e->nstands = nstands;
    cs_status st = patch_set_alloc(&e->ps, nstands * 100);
    if (st) return st;
    e->per_stand = calloc((size_t)nstands, sizeof *e->per_stand);
    if (!e->per_stand) return cs_err(CS_ENOMEM, "out of memory");
    for (int k = 0; k < nstands && !st; k++)
        st = add_stand_patches(ds, "main-eval", d, (unsigned)k, e->ps, &e->per_stand[k], worst);
    if (!st) st = patch_set_standardise(e->ps, scale);
    if (st) return st;
    int n = e->ps->n;
    e->teach = malloc((size_t)n * sizeof *e->teach);
    double *rbuf = malloc((size_t)64 * PATCH_T * PATCH_P * sizeof *rbuf);
    if (!e->teach || !rbuf) { free(rbuf); return cs_err(CS_ENOMEM, "out of memory"); }
    for (int k0 = 0; k0 < n && !st; k0 += 64) {
        int b = n - k0 < 64 ? n - k0 : 64;
        st = focal_nn(e->ps, k0, b, e->ps->x1 + (size_t)k0 * PATCH_T * PATCH_P, rbuf, e->teach + k0);
        /* The instrument guard of paper §4.3: the batched estimator must agree
         * with the canonical one on every pair of the first batch. */
        if (!st && k0 == 0) {
            double md;
            st = patch_clearance_check(est_clearance, e->ps->px, e->ps->py, rbuf, b, &md);
            if (!st && md > *maxdiff) *maxdiff = md;
            if (!st && md > ds->tol)
                st =
                    cs_err(CS_EINVARIANT, "batched estimator differs from est_clearance by %.3g m > %.3g m at d = %.1f",
                           md, ds->tol, d);
        }
    }
    free(rbuf);
    return st;
}

cs_status mainset_generate(model *m, int Bmax, const mainset_eval *e, int gen_patches, int euler,
                           unsigned seed, mainset_probe probe, double *gen, int *ngen)
{
    int G = e->ps->n < gen_patches ? e->ps->n : gen_patches;
    static const char *key[MAINSET_NPROBE] = {"main-model", "main-model-shuffled", "main-model-rotated"};
    double *r = malloc((size_t)G * PATCH_T * PATCH_P * sizeof *r);
    float *rot = probe == MAINSET_ROTATED ? malloc((size_t)G * PATCH_T * PATCH_NFEAT * sizeof *rot) : NULL;
    double *al = probe == MAINSET_ROTATED ? malloc((size_t)G * sizeof *al) : NULL;
    gsl_rng *noise = gsl_rng_alloc(gsl_rng_mt19937), *perm = gsl_rng_alloc(gsl_rng_mt19937);
    cs_status st =
        r && noise && perm && (probe != MAINSET_ROTATED || (rot && al)) ? CS_OK : cs_err(CS_ENOMEM, "out of memory");
    if (!st) {
        gsl_rng_set(noise, (unsigned long)seed_derive(key[probe], e->d, seed, "sample"));
        gsl_rng_set(perm, (unsigned long)seed_derive("main-model", e->d, seed, "shuffle"));
        patch_set view = *e->ps;
        if (probe == MAINSET_ROTATED) {
            /* the same patches with turned geometry; radii and evaluation use the true ones */
            memcpy(rot, e->ps->feat, (size_t)G * PATCH_T * PATCH_NFEAT * sizeof *rot);
            for (int g = 0; g < G; g++) al[g] = patch_rotation_angle(g);
            patch_rotate_positions(rot, G, al);
            view.feat = rot;
        }
        st = model_sample_radii(m, Bmax, &view, G, euler, noise, probe == MAINSET_SHUFFLED ? perm : NULL, r);
    }
    if (!st) st = patch_focal_clearances(e->ps->px, e->ps->py, r, G, 1, gen);
    *ngen = G;
    free(r); free(rot); free(al);
    if (noise) gsl_rng_free(noise);
    if (perm) gsl_rng_free(perm);
    return st;
}

cs_status mainset_teacher_probe(const mainset_eval *e, mainset_probe probe, double *out)
{
    const int n = e->ps->n;
    const size_t tp = (size_t)PATCH_T * PATCH_P;
    if (probe == MAINSET_GENERATED) { memcpy(out, e->teach, (size_t)n * sizeof *out); return CS_OK; }
    float *x = malloc(64 * tp * sizeof *x);
    double *rbuf = malloc(64 * tp * sizeof *rbuf), *t = malloc(PATCH_P * sizeof *t), *u = malloc(PATCH_P * sizeof *u);
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    cs_status st = x && rbuf && t && u && g ? CS_OK : cs_err(CS_ENOMEM, "out of memory");
    if (!st) gsl_rng_set(g, (unsigned long)seed_derive("main-teacher", e->d, 0, "shuffle"));
    for (int k0 = 0; k0 < n && !st; k0 += 64) {
        int b = n - k0 < 64 ? n - k0 : 64;
        for (int k = 0; k < b; k++) {
            const float *x1 = e->ps->x1 + (size_t)(k0 + k) * tp;
            float *xo = x + (size_t)k * tp;
            if (probe == MAINSET_SHUFFLED) {
                int perm[PATCH_T];
                patch_shuffle_perm(g, perm);
                for (int i = 0; i < PATCH_T; i++)
                    memcpy(xo + i * PATCH_P, x1 + perm[i] * PATCH_P, PATCH_P * sizeof *xo);
            } else {
                int steps = (int)lround(patch_rotation_angle(k0 + k) / (2 * M_PI / PATCH_P));
                for (int i = 0; i < PATCH_T; i++) {
                    for (int s = 0; s < PATCH_P; s++) t[s] = x1[i * PATCH_P + s];
                    patch_rotate_crown(t, steps, u);
                    for (int s = 0; s < PATCH_P; s++) xo[i * PATCH_P + s] = (float)u[s];
                }
            }
        }
        st = focal_nn(e->ps, k0, b, x, rbuf, out + k0);
    }
    free(x); free(rbuf); free(t); free(u);
    if (g) gsl_rng_free(g);
    return st;
}

cs_status mainset_blind(const mainset_eval *e, double *out)
{
    const int n = e->ps->n;
    float *zero = calloc((size_t)64 * PATCH_T * PATCH_P, sizeof *zero);
    double *rbuf = malloc((size_t)64 * PATCH_T * PATCH_P * sizeof *rbuf);
    cs_status st = zero && rbuf ? CS_OK : cs_err(CS_ENOMEM, "out of memory");
    for (int k0 = 0; k0 < n && !st; k0 += 64) {
        int b = n - k0 < 64 ? n - k0 : 64;
        st = focal_nn(e->ps, k0, b, zero, rbuf, out + k0);
    }
    free(zero); free(rbuf);
    return st;
}
