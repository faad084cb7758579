/* stems: jittered lattice and hard-core Poisson stem processes (design.md §2). */
#include "stems.h"
#include "crown.h"
#include "seed.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_randist.h>

static cs_status stems_new(stems **out, size_t cap, double d, double L)
{
    stems *s = calloc(1, sizeof *s);
    if (!s) return cs_err(CS_ENOMEM, "stems: out of memory");
    s->x = malloc((cap ? cap : 1) * sizeof *s->x);
    s->y = malloc((cap ? cap : 1) * sizeof *s->y);
    if (!s->x || !s->y) { stems_free(s); return cs_err(CS_ENOMEM, "stems: out of memory"); }
    s->d = d;
    s->L = L;
    *out = s;
    return CS_OK;
}

void stems_free(stems *s)
{
    if (!s) return;
    free(s->x);
    free(s->y);
    free(s);
}

int stems_interior(const stems *s, size_t i)
{
    double m = 2.0 * s->d;
    return s->x[i] >= m && s->x[i] <= s->L - m && s->y[i] >= m && s->y[i] <= s->L - m;
}

cs_status stems_from_xy(stems **out, size_t n, const double *x, const double *y, double d, double L)
{
    cs_status st = stems_new(out, n, d, L);
    if (st) return st;
    for (size_t i = 0; i < n; i++) { (*out)->x[i] = x[i]; (*out)->y[i] = y[i]; }
    (*out)->n = n;
    return CS_OK;
}

cs_status stems_lattice_alloc(stems **out, double d, double L, double jitter_a, uint64_t seed)
{
    *out = NULL;
    if (!(d > 0.0) || !(L > 0.0) || !(jitter_a >= 0.0))
        return cs_err(CS_EINPUT, "stems: lattice needs d > 0, L > 0, a >= 0 (got d=%g L=%g a=%g)", d, L, jitter_a);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (!rng) return cs_err(CS_ENOMEM, "stems: out of memory");
    gsl_rng_set(rng, seed_mt(seed));
    double w = 0.5 * CROWN_PI * gsl_rng_uniform(rng); /* rotation U[0, pi/2) */
    double u = gsl_rng_uniform(rng), v = gsl_rng_uniform(rng); /* phase, lattice units */
    double cw = cos(w), sw = sin(w);
    /* Nodes (i+u, j+v) d rotated about the footprint centre; the index range
     * covers the rotated square's circumscribed disk. */
    double half = 0.5 * L;
    int m = (int)ceil(half * 1.4142135623730951 / d) + 2;
    size_t cap = (size_t)(2 * m + 1) * (size_t)(2 * m + 1);
    cs_status st = stems_new(out, cap, d, L);
    if (st) { gsl_rng_free(rng); return st; }
    stems *s = *out;
    for (int j = -m; j <= m; j++)
        for (int i = -m; i <= m; i++) {
            double lx = ((double)i + u) * d, ly = ((double)j + v) * d;
            double px = half + cw * lx - sw * ly, py = half + sw * lx + cw * ly;
            if (px < 0.0 || px >= L || py < 0.0 || py >= L) continue;
            s->x[s->n] = px;
            s->y[s->n] = py;
            s->n++;
        }
    /* Jitter drawn after membership, in node order, x then y. */
    for (size_t k = 0; k < s->n; k++) {
        s->x[k] += gsl_ran_gaussian(rng, jitter_a * d);
        s->y[k] += gsl_ran_gaussian(rng, jitter_a * d);
    }
    gsl_rng_free(rng);
    return CS_OK;
}

cs_status stems_hardcore_alloc(stems **out, double d, double L, double c, uint64_t seed)
{
    *out = NULL;
    if (!(d > 0.0) || !(L > 0.0) || !(c >= 0.0))
        return cs_err(CS_EINPUT, "stems: hard-core needs d > 0, L > 0, c >= 0 (got d=%g L=%g c=%g)", d, L, c);
    double ratio = L / d;
    size_t n = (size_t)floor(ratio * ratio);
    cs_status st = stems_new(out, n, d, L);
    if (st) return st;
    stems *s = *out;
    /* Acceptance grid: cell side >= c d so a conflict lies in the 3x3 block. */
    double rad = c * d, rad2 = rad * rad;
    int g = rad > 0.0 ? (int)floor(L / rad) : 1;
    if (g < 1) g = 1;
    if (g > 1024) g = 1024;
    double cell = L / (double)g;
    int *head = malloc((size_t)g * (size_t)g * sizeof *head);
    int *next = malloc((n ? n : 1) * sizeof *next);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    if (!head || !next || !rng) {
        free(head); free(next); if (rng) gsl_rng_free(rng);
        stems_free(s); *out = NULL;
        return cs_err(CS_ENOMEM, "stems: out of memory");
    }
    for (int k = 0; k < g * g; k++) head[k] = -1;
    gsl_rng_set(rng, seed_mt(seed));
    double max_reject = 1e5 * (double)n, rejects = 0.0;
    while (s->n < n) {
        double px = L * gsl_rng_uniform(rng), py = L * gsl_rng_uniform(rng);
        int cx = (int)(px / cell), cy = (int)(py / cell);
        if (cx >= g) cx = g - 1;
        if (cy >= g) cy = g - 1;
        int ok = 1;
        for (int yy = cy - 1; yy <= cy + 1 && ok; yy++) {
            if (yy < 0 || yy >= g) continue;
            for (int xx = cx - 1; xx <= cx + 1 && ok; xx++) {
                if (xx < 0 || xx >= g) continue;
                for (int q = head[yy * g + xx]; q >= 0; q = next[q]) {
                    double dx = px - s->x[q], dy = py - s->y[q];
                    if (dx * dx + dy * dy < rad2) { ok = 0; break; }
                }
            }
        }
        if (!ok) {
            rejects += 1.0;
            if (rejects > max_reject) {
                size_t got = s->n;
                free(head); free(next); gsl_rng_free(rng);
                stems_free(s); *out = NULL;
                return cs_err(CS_EINPUT,
                              "stems: hard-core process unbuildable: c=%g d=%g L=%g placed %zu of %zu stems "
                              "after %.0f rejected proposals", c, d, L, got, n, max_reject);
            }
            continue;
        }
        s->x[s->n] = px;
        s->y[s->n] = py;
        next[s->n] = head[cy * g + cx];
        head[cy * g + cx] = (int)s->n;
        s->n++;
    }
    free(head); free(next); gsl_rng_free(rng);
    return CS_OK;
}

cs_status stems_focal(const stems *s, size_t *focal)
{
    double best = INFINITY, c = 0.5 * s->L;
    int found = 0;
    for (size_t i = 0; i < s->n; i++) {
        if (!stems_interior(s, i)) continue;
        double dd = hypot(s->x[i] - c, s->y[i] - c);
        if (dd < best) { best = dd; *focal = i; found = 1; }
    }
    return found ? CS_OK : cs_err(CS_EINPUT, "stems: no interior stem (d = %g m, L = %g m)", s->d, s->L);
}

static const stems_type LATTICE = {"lattice", "jitter sd a", stems_lattice_alloc};
static const stems_type HARDCORE = {"hardcore", "minimum distance c", stems_hardcore_alloc};
const stems_type *const stems_lattice = &LATTICE;
const stems_type *const stems_hardcore = &HARDCORE;
const stems_type *const stems_types[] = {&LATTICE, &HARDCORE, NULL};

const stems_type *stems_type_find(const char *name)
{
    for (const stems_type *const *t = stems_types; *t; t++)
        if (!strcmp((*t)->name, name)) return *t;
    return NULL;
}
