/* stand: stems + crown draws from derived seeds (design.md §1-§3). */
#include "stand.h"
#include "seed.h"
#include <stdlib.h>
#include <gsl/gsl_rng.h>

void stand_free(stand *sd)
{
    if (!sd) return;
    stems_free(sd->s);
    free(sd->draw); free(sd->h); free(sd->R); free(sd->rstar);
    free(sd);
}

cs_status stand_from_stems_dist(stand **out, stems *s, uint64_t crown_seed, const crown_dist *cd)
{
    *out = NULL;
    stand *sd = calloc(1, sizeof *sd);
    if (!sd) { stems_free(s); return cs_err(CS_ENOMEM, "stand: out of memory"); }
    sd->s = s;
    size_t n = s->n, m = n ? n : 1;
    sd->draw = malloc(m * sizeof *sd->draw);
    sd->h = malloc(m * sizeof *sd->h);
    sd->R = malloc(m * sizeof *sd->R);
    sd->rstar = malloc(m * CROWN_NSEC * sizeof *sd->rstar);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (!sd->draw || !sd->h || !sd->R || !sd->rstar || !rng) {
        if (rng) gsl_rng_free(rng);
        stand_free(sd);
        return cs_err(CS_ENOMEM, "stand: out of memory");
    }
    gsl_rng_set(rng, seed_mt(crown_seed));
    cs_status st = crown_draw_n_dist(rng, n, cd, sd->draw);
    gsl_rng_free(rng);
    if (st) { stand_free(sd); return st; }
    for (size_t i = 0; i < n; i++) {
        sd->h[i] = sd->draw[i].h;
        sd->R[i] = sd->draw[i].R;
        crown_target(&sd->draw[i], sd->rstar + i * CROWN_NSEC);
    }
    *out = sd;
    return CS_OK;
}

cs_status stand_alloc(stand **out, const stems_type *kind, double d, double L, double shape,
                      const char *experiment, unsigned index)
{
    return stand_alloc_dist(out, kind, d, L, shape, experiment, index, NULL);
}

cs_status stand_alloc_dist(stand **out, const stems_type *kind, double d, double L, double shape,
                           const char *experiment, unsigned index, const crown_dist *cd)
{
    *out = NULL;
    stems *s = NULL;
    uint64_t ss = seed_derive(experiment, d, index, "stems");
    cs_status st = kind->alloc(&s, d, L, shape, ss);
    if (st) return st;
    return stand_from_stems_dist(out, s, seed_derive(experiment, d, index, "crowns"), cd);
}

void stand_view(const stand *sd, stand_arrays *v)
{
    v->n = sd->s->n;
    v->x = sd->s->x;
    v->y = sd->s->y;
    v->h = sd->h;
    v->R = sd->R;
    v->rstar = sd->rstar;
}
