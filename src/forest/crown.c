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

cs_status crown_draw_n(gsl_rng *rng, size_t n, crown_draw *out)
{
    for (size_t i = 0; i < n; i++) {
        double h = 0.0;
        int tries = 0;
        do {
            if (++tries > 1000) return cs_err(CS_ENUMERIC, "crown: height redraw did not terminate");
            h = 25.0 + gsl_ran_gaussian(rng, 4.0);
        } while (h < 12.0 || h > 38.0);
        double z = gsl_ran_gaussian(rng, 1.0);
        out[i].h = h;
        out[i].R = 4.0 * exp(CROWN_R_LOG_SD * z);
        out[i].a = 0.2 * gsl_rng_uniform(rng);
        out[i].k = 2 + (int)gsl_rng_uniform_int(rng, 4);
        out[i].phi = 2.0 * CROWN_PI * gsl_rng_uniform(rng);
    }
    return CS_OK;
}
