/* crown: interpolation rule and crown draws (design.md §1, §3; paper Eq. 1). */
#include "crown.h"
#include <math.h>
#include <gsl/gsl_randist.h>

double crown_theta(int s) { return CROWN_DTHETA * (double)s; }

double crown_radius_at(const double r[CROWN_NSEC], double theta)
{
    /* u in sector units, wrapped to [0, NSEC). */
    double u = theta * ((double)CROWN_NSEC / (2.0 * CROWN_PI));
    u -= (double)CROWN_NSEC * floor(u / (double)CROWN_NSEC);
    if (!(u < (double)CROWN_NSEC)) u = 0.0; /* u rounded up to NSEC, or NaN guard */
    int s = (int)u;
    if (s >= CROWN_NSEC) s = CROWN_NSEC - 1;
    double f = u - (double)s;
    int s1 = (s + 1 == CROWN_NSEC) ? 0 : s + 1;
    return r[s] + f * (r[s1] - r[s]);
}

void crown_target(const crown_draw *c, double rstar[CROWN_NSEC])
{
    for (int s = 0; s < CROWN_NSEC; s++)
        rstar[s] = c->R * (1.0 + c->a * cos((double)c->k * crown_theta(s) + c->phi));
}

void crown_dist_default(crown_dist *c)
{
    const crown_dist d = CROWN_DIST_DEFAULT;
    *c = d;
}

cs_status crown_draw_n(gsl_rng *rng, size_t n, crown_draw *out) { return crown_draw_n_dist(rng, n, NULL, out); }

cs_status crown_draw_n_dist(gsl_rng *rng, size_t n, const crown_dist *c, crown_draw *out)
{
    crown_dist d;
    if (c) d = *c;
    else crown_dist_default(&d);
    if (!(d.h_sd >= 0.0) || !(d.h_lo < d.h_hi) || !(d.R_scale > 0.0) || !(d.R_lnsd >= 0.0) ||
        !(d.a_max >= 0.0 && d.a_max < 1.0))
        return cs_err(CS_EINPUT, "crown: distribution cannot be drawn (h sd %g in [%g, %g], R %g exp(%g z), a_max %g)",
                      d.h_sd, d.h_lo, d.h_hi, d.R_scale, d.R_lnsd, d.a_max);
    for (size_t i = 0; i < n; i++) {
        double h = 0.0;
        int tries = 0;
        do {
            if (++tries > 1000) return cs_err(CS_ENUMERIC, "crown: height redraw did not terminate");
            h = d.h_mean + gsl_ran_gaussian(rng, d.h_sd);
        } while (h < d.h_lo || h > d.h_hi);
        double z = gsl_ran_gaussian(rng, 1.0);
        out[i].h = h;
        out[i].R = d.R_scale * exp(d.R_lnsd * z);
        out[i].a = d.a_max * gsl_rng_uniform(rng);
        out[i].k = 2 + (int)gsl_rng_uniform_int(rng, 4);
        out[i].phi = 2.0 * CROWN_PI * gsl_rng_uniform(rng);
    }
    return CS_OK;
}
