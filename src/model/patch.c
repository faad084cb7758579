/* patch: patch extraction, features, conditions, standardisation and the
 * batched clearance estimator (see patch.h; paper §4.1 and Eq. 5; design.md §1, §5, §8).
 * Neighbour search is a full sort per focal stem: stands here have ~150 stems,
 * so O(n log n) per patch is cheaper than maintaining a grid. */
#include "patch.h"
#include <gsl/gsl_randist.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

cs_status patch_stand_init(patch_stand *s, int n, const double *x, const double *y,
                           const double *r, const double *h, double d)
{
    if (n < PATCH_T) return cs_err(CS_EINPUT, "stand: %d stems, need at least %d for a patch", n, PATCH_T);
    if (!(d > 0) || !isfinite(d)) return cs_err(CS_EINPUT, "stand: spacing d = %g must be positive", d);
    for (int i = 0; i < n; i++) {
        if (!isfinite(x[i]) || !isfinite(y[i])) return cs_err(CS_EINPUT, "stand: stem %d position not finite", i);
        for (int k = 0; k < PATCH_P; k++)
            if (!isfinite(r[i * PATCH_P + k]) || r[i * PATCH_P + k] < 0)
                return cs_err(CS_EINPUT, "stand: crown %d sector %d radius %g invalid", i, k, r[i * PATCH_P + k]);
    }
    s->n = n; s->x = x; s->y = y; s->r = r; s->d = d; s->median_h = 0;
    if (h) {
        double *tmp = malloc(sizeof(double) * n);
        if (!tmp) return cs_err(CS_ENOMEM, "stand: out of memory");
        for (int i = 0; i < n; i++) {
            if (!isfinite(h[i])) { free(tmp); return cs_err(CS_EINPUT, "stand: height %d not finite", i); }
            tmp[i] = h[i];
        }
        gsl_sort(tmp, 1, n);
        s->median_h = gsl_stats_median_from_sorted_data(tmp, 1, n);
        free(tmp);
    }
    return CS_OK;
}

typedef struct { double d2; int i; } dist_idx;
static int cmp_dist(const void *a, const void *b)
{
    const dist_idx *p = a, *q = b;
    if (p->d2 < q->d2) return -1;
    if (p->d2 > q->d2) return 1;
    return (p->i > q->i) - (p->i < q->i);
}

cs_status patch_neighbours(const patch_stand *s, int focal, int idx[PATCH_T])
{
    if (focal < 0 || focal >= s->n) return cs_err(CS_EINPUT, "patch: focal stem %d outside 0..%d", focal, s->n - 1);
    dist_idx *a = malloc(sizeof *a * s->n);
    if (!a) return cs_err(CS_ENOMEM, "patch: out of memory");
    for (int i = 0; i < s->n; i++) {
        double dx = s->x[i] - s->x[focal], dy = s->y[i] - s->y[focal];
        a[i].d2 = i == focal ? -1.0 : dx * dx + dy * dy; /* focal first even if a stem coincides */
        a[i].i = i;
    }
    qsort(a, s->n, sizeof *a, cmp_dist);
    for (int k = 0; k < PATCH_T; k++) idx[k] = a[k].i;
    free(a);
    return CS_OK;
}

cs_status patch_build(const patch_stand *s, int focal, patch *p)
{
    cs_status st = patch_neighbours(s, focal, p->idx);
    if (st) return st;
    const double d = s->d;
    double nn[PATCH_T];
    for (int k = 0; k < PATCH_T; k++) {
        int i = p->idx[k];
        p->px[k] = s->x[i] - s->x[focal];
        p->py[k] = s->y[i] - s->y[focal];
        const double *r = s->r + (size_t)i * PATCH_P;
        double m = 0;
        for (int j = 0; j < PATCH_P; j++) m += r[j];
        m /= PATCH_P;
        p->rbar[k] = m;
        for (int j = 0; j < PATCH_P; j++) p->dev[k * PATCH_P + j] = r[j] - m;
        p->feat[k * PATCH_NFEAT + 0] = (float)(p->px[k] / d);
        p->feat[k * PATCH_NFEAT + 1] = (float)(p->py[k] / d);
        p->feat[k * PATCH_NFEAT + PATCH_FEAT_RBAR] = (float)(m / d);
        double rho = hypot(p->px[k], p->py[k]), phi = atan2(p->py[k], p->px[k]);
        for (int h = 1; h <= 4; h++) {
            p->feat[k * PATCH_NFEAT + 1 + 2 * h] = rho > 0 ? (float)cos(h * phi) : 0.f;
            p->feat[k * PATCH_NFEAT + 2 + 2 * h] = rho > 0 ? (float)sin(h * phi) : 0.f;
        }
        p->feat[k * PATCH_NFEAT + 11] = (float)(rho / d);
    }
    /* nearest-neighbour distance of each patch stem, over the whole stand */
    for (int k = 0; k < PATCH_T; k++) {
        int i = p->idx[k];
        double best = INFINITY;
        for (int j = 0; j < s->n; j++) {
            if (j == i) continue;
            double dx = s->x[j] - s->x[i], dy = s->y[j] - s->y[i];
            double e = dx * dx + dy * dy;
            if (e < best) best = e;
        }
        nn[k] = sqrt(best) / d;
    }
    double rho = hypot(p->px[PATCH_T - 1], p->py[PATCH_T - 1]);
    double mean = gsl_stats_mean(nn, 1, PATCH_T);
    double sd = gsl_stats_sd_m(nn, 1, PATCH_T, mean);
    p->cond[0] = (float)(d / 5.0);
    p->cond[1] = rho > 0 ? (float)(PATCH_T / (M_PI * rho * rho) * d * d) : 0.f;
    p->cond[2] = (float)mean;
    p->cond[3] = (float)sd;
    p->cond[4] = (float)(s->median_h / 25.0);
    return CS_OK;
}

cs_status patch_set_alloc(patch_set **out, int cap)
{
    *out = NULL;
    if (cap < 1) cap = 1;
    patch_set *s = calloc(1, sizeof *s);
    if (!s) return cs_err(CS_ENOMEM, "patch set: out of memory");
    s->cap = cap;
    const size_t T = PATCH_T;
    s->x1 = malloc(sizeof(float) * cap * T * PATCH_P);
    s->feat = malloc(sizeof(float) * cap * T * PATCH_NFEAT);
    s->cond = malloc(sizeof(float) * cap * PATCH_NCOND);
    s->px = malloc(sizeof(double) * cap * T);
    s->py = malloc(sizeof(double) * cap * T);
    s->rbar = malloc(sizeof(double) * cap * T);
    if (!s->x1 || !s->feat || !s->cond || !s->px || !s->py || !s->rbar) {
        patch_set_free(s);
        return cs_err(CS_ENOMEM, "patch set: out of memory (%d patches)", cap);
    }
    *out = s;
    return CS_OK;
}

void patch_set_free(patch_set *s)
{
    if (!s) return;
    free(s->x1); free(s->feat); free(s->cond); free(s->px); free(s->py); free(s->rbar);
    free(s);
}

#define GROW(ptr, type, per) do { \
        type *q_ = realloc(s->ptr, sizeof(type) * (size_t)nc * (per)); \
        if (!q_) { return cs_err(CS_ENOMEM, "patch set: out of memory"); } \
        s->ptr = q_; \
    } while (0)

cs_status patch_set_add(patch_set *s, const patch *p)
{
    if (s->scale > 0) return cs_err(CS_EINVARIANT, "patch set: add after standardisation");
    if (s->n == s->cap) {
        int nc = s->cap * 2;
        GROW(x1, float, PATCH_T * PATCH_P); GROW(feat, float, PATCH_T * PATCH_NFEAT);
        GROW(cond, float, PATCH_NCOND); GROW(px, double, PATCH_T); GROW(py, double, PATCH_T);
        GROW(rbar, double, PATCH_T);
        s->cap = nc;
    }
    size_t k = s->n;
    for (int i = 0; i < PATCH_T * PATCH_P; i++) s->x1[k * PATCH_T * PATCH_P + i] = (float)p->dev[i];
    memcpy(s->feat + k * PATCH_T * PATCH_NFEAT, p->feat, sizeof p->feat);
    memcpy(s->cond + k * PATCH_NCOND, p->cond, sizeof p->cond);
    memcpy(s->px + k * PATCH_T, p->px, sizeof p->px);
    memcpy(s->py + k * PATCH_T, p->py, sizeof p->py);
    memcpy(s->rbar + k * PATCH_T, p->rbar, sizeof p->rbar);
    s->n++;
    return CS_OK;
}

double patch_set_rms(const patch_set *s)
{
    size_t n = (size_t)s->n * PATCH_T * PATCH_P;
    double a = 0;
    for (size_t i = 0; i < n; i++) a += (double)s->x1[i] * s->x1[i];
    return n ? sqrt(a / (double)n) : 0.0;
}

cs_status patch_set_standardise(patch_set *s, double scale)
{
    if (!(scale > 0) || !isfinite(scale)) return cs_err(CS_EINPUT, "patch set: scale %g must be positive", scale);
    if (s->scale > 0) return cs_err(CS_EINVARIANT, "patch set: already standardised");
    size_t n = (size_t)s->n * PATCH_T * PATCH_P;
    for (size_t i = 0; i < n; i++) s->x1[i] = (float)(s->x1[i] / scale);
    s->scale = scale;
    return CS_OK;
}

void patch_set_radii(const patch_set *s, int k, const float *x, double *r)
{
    for (int t = 0; t < PATCH_T; t++)
        for (int j = 0; j < PATCH_P; j++)
            r[t * PATCH_P + j] = s->rbar[(size_t)k * PATCH_T + t] + s->scale * x[t * PATCH_P + j];
}

double patch_radius_at(const double *r, double theta)
{
    double u = theta / (2 * M_PI) * PATCH_P;
    u -= PATCH_P * floor(u / PATCH_P);
    int s = (int)u;
    if (s >= PATCH_P) s = 0, u = 0; /* u rounded up to exactly P */
    double f = u - s;
    return (1 - f) * r[s] + f * r[(s + 1) % PATCH_P];
}

double patch_clearance(double xi, double yi, const double *ri, double xj, double yj,
                       const double *rj)
{
    double dx = xj - xi, dy = yj - yi;
    double th = atan2(dy, dx);
    return hypot(dx, dy) - patch_radius_at(ri, th) - patch_radius_at(rj, th + M_PI);
}

cs_status patch_focal_clearances(const double *px, const double *py, const double *r,
                                 int n, int K, double *out)
{
    if (K < 1 || K >= PATCH_T) return cs_err(CS_EINPUT, "clearances: K = %d outside 1..%d", K, PATCH_T - 1);
    for (int b = 0; b < n; b++) {
        const double *x = px + (size_t)b * PATCH_T, *y = py + (size_t)b * PATCH_T;
        const double *rr = r + (size_t)b * PATCH_T * PATCH_P;
        for (int k = 1; k <= K; k++)
            out[(size_t)b * K + k - 1] = patch_clearance(x[0], y[0], rr, x[k], y[k], rr + k * PATCH_P);
    }
    return CS_OK;
}

cs_status patch_clearance_check(patch_clearance_ref ref, const double *px, const double *py,
                                const double *r, int n, double *maxdiff)
{
    double worst = 0;
    if (!ref) return cs_err(CS_EINVARIANT, "clearance check: no reference estimator given");
    for (int b = 0; b < n; b++) {
        const double *x = px + (size_t)b * PATCH_T, *y = py + (size_t)b * PATCH_T;
        const double *rr = r + (size_t)b * PATCH_T * PATCH_P;
        for (int i = 0; i < PATCH_T; i++)
            for (int j = 0; j < PATCH_T; j++) {
                if (i == j) continue;
                double a = patch_clearance(x[i], y[i], rr + i * PATCH_P, x[j], y[j], rr + j * PATCH_P);
                double e = ref(x[i], y[i], rr + i * PATCH_P, x[j], y[j], rr + j * PATCH_P);
                double diff = fabs(a - e);
                if (!(diff <= 1e-6)) {
                    if (maxdiff) *maxdiff = isfinite(diff) ? diff : INFINITY;
                    return cs_err(CS_EINVARIANT,
                                  "batched clearance disagrees with the canonical estimator: patch %d, "
                                  "trees %d->%d: batched %.17g m, canonical %.17g m (|diff| %.3g > 1e-6)",
                                  b, i, j, a, e, diff);
                }
                if (diff > worst) worst = diff;
            }
    }
    if (maxdiff) *maxdiff = worst;
    return CS_OK;
}

void patch_toy_stand(gsl_rng *rng, int side, double d, double *x, double *y, double *r)
{
    const int n = side * side;
    for (int a = 0; a < side; a++)
        for (int b = 0; b < side; b++) {
            int i = a * side + b;
            x[i] = d * b + gsl_ran_gaussian_ziggurat(rng, 0.1 * d);
            y[i] = d * a + gsl_ran_gaussian_ziggurat(rng, 0.1 * d);
        }
    for (int i = 0; i < n; i++) {
        double R = 0.4 * d * (1 + 0.1 * gsl_ran_gaussian_ziggurat(rng, 1.0));
        int nn = -1;
        double best = INFINITY;
        for (int j = 0; j < n; j++) {
            if (j == i) continue;
            double e = (x[j] - x[i]) * (x[j] - x[i]) + (y[j] - y[i]) * (y[j] - y[i]);
            if (e < best) best = e, nn = j;
        }
        double th = atan2(y[nn] - y[i], x[nn] - x[i]);
        for (int s = 0; s < PATCH_P; s++)
            r[i * PATCH_P + s] = R * (1 - 0.2 * cos(2 * M_PI * s / PATCH_P - th));
    }
}

cs_status patch_set_add_toy(patch_set *s, int nstands, double d, unsigned long seed)
{
    enum { SIDE = 12, NS = SIDE * SIDE };
    double x[NS], y[NS], r[NS * PATCH_P];
    gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
    if (!g) return cs_err(CS_ENOMEM, "toy stands: out of memory");
    cs_status st = CS_OK;
    for (int k = 0; k < nstands && !st; k++) {
        gsl_rng_set(g, seed + (unsigned long)k);
        patch_toy_stand(g, SIDE, d, x, y, r);
        patch_stand ps;
        st = patch_stand_init(&ps, NS, x, y, r, NULL, d);
        for (int a = 2; a < SIDE - 2 && !st; a++)
            for (int b = 2; b < SIDE - 2 && !st; b++) {
                patch p;
                st = patch_build(&ps, a * SIDE + b, &p);
                if (!st) st = patch_set_add(s, &p);
            }
    }
    gsl_rng_free(g);
    return st;
}

void patch_shuffle_perm(gsl_rng *rng, int perm[PATCH_T])
{
    for (int i = 0; i < PATCH_T; i++) perm[i] = i;
    gsl_ran_shuffle(rng, perm, PATCH_T, sizeof(int));
}

void patch_shuffle_positions(float *feat, int n, gsl_rng *rng)
{
    int perm[PATCH_T];
    float pos[PATCH_T * PATCH_NFEAT];
    for (int k = 0; k < n; k++) {
        float *f = feat + (size_t)k * PATCH_T * PATCH_NFEAT;
        memcpy(pos, f, sizeof pos);
        patch_shuffle_perm(rng, perm);
        /* every positional feature moves with its position; rbar stays with its tree */
        for (int i = 0; i < PATCH_T; i++)
            for (int q = 0; q < PATCH_NFEAT; q++)
                if (q != PATCH_FEAT_RBAR) f[i * PATCH_NFEAT + q] = pos[perm[i] * PATCH_NFEAT + q];
    }
}

void patch_direction_blind(const double *r, int ncrowns, double *out)
{
    for (int i = 0; i < ncrowns; i++) {
        double m = 0;
        for (int s = 0; s < PATCH_P; s++) m += r[i * PATCH_P + s];
        m /= PATCH_P;
        for (int s = 0; s < PATCH_P; s++) out[i * PATCH_P + s] = m;
    }
}

double patch_rotation_angle(int g)
{
    return (double)(1 + (g < 0 ? -g : g) % 7) * (M_PI / 4.0);
}

void patch_rotate_positions(float *feat, int n, const double *alpha)
{
    for (int k = 0; k < n; k++) {
        const double c = cos(alpha[k]), s = sin(alpha[k]);
        for (int i = 0; i < PATCH_T; i++) {
            float *f = feat + ((size_t)k * PATCH_T + i) * PATCH_NFEAT;
            const double x = f[0], y = f[1];
            const double xr = c * x - s * y, yr = s * x + c * y;
            f[0] = (float)xr;
            f[1] = (float)yr;
            if (f[11] > 0) { /* the focal stem (rho = 0) keeps its zero basis */
                const double phi = atan2(yr, xr);
                for (int h = 1; h <= 4; h++) {
                    f[1 + 2 * h] = (float)cos(h * phi);
                    f[2 + 2 * h] = (float)sin(h * phi);
                }
            }
        }
    }
}

void patch_rotate_crown(const double *r, int steps, double *out)
{
    int m = ((steps % PATCH_P) + PATCH_P) % PATCH_P;
    for (int s = 0; s < PATCH_P; s++) out[s] = r[(s - m + PATCH_P) % PATCH_P];
}
