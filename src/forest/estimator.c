/* estimator: the canonical instrument (design.md §5; reference paper §4.3).
 * This file is pinned by SHA-256 (audit/pins): any edit changes the pin.
 * Eq. 5 clearance, k-NN clearance, exact W1 (Eq. 6), canopy cover on a
 * 0.05 m grid, cardinal gaps, tree-mean clearance, anisotropy, elongation,
 * spread. Crown radius between sector centres: crown_radius_at (the one rule);
 * at a sector centre r(theta_s) is r_s by definition, read directly.
 * Elongation (paper §5.3, design.md §5): longest / shortest of the
 * 12 axes r_s + r_{s+12}. Between sector centres an axis length is linear
 * (both ends interpolate over the same fraction), so these 12 hold its extremes
 * and the value is exact for the 24-sector profile. Limit: shape finer than
 * 15 degrees is not in the profile, so not in the statistic. The two-axis
 * cardinal reading stays as est_elongation_cardinal (readings only).
 * Plain loops, no acceleration structures: the instrument favours being
 * obviously right over being fast. */
#include "estimator.h"
#include "crown.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

double est_clearance(double xi, double yi, const double *ri, double xj, double yj, const double *rj)
{
    double dx = xj - xi, dy = yj - yi;
    double nu = hypot(dx, dy);
    return nu - crown_radius_at(ri, atan2(dy, dx)) - crown_radius_at(rj, atan2(-dy, -dx));
}

long est_knn(const double *x, const double *y, size_t n, size_t i, int k)
{
    if (k < 1 || (size_t)k >= n) return -1;
    /* Keep the k best (distance, index) pairs by insertion; k <= 3 in use. */
    double bd[16];
    long bi[16];
    if (k > 16) return -1;
    int have = 0;
    for (size_t j = 0; j < n; j++) {
        if (j == i) continue;
        double dx = x[j] - x[i], dy = y[j] - y[i];
        double d2 = dx * dx + dy * dy;
        /* Strict < keeps the lower index first among equal distances. */
        int pos = have;
        while (pos > 0 && d2 < bd[pos - 1]) pos--;
        if (pos >= k) continue;
        int last = have < k ? have : k - 1;
        for (int q = last; q > pos; q--) { bd[q] = bd[q - 1]; bi[q] = bi[q - 1]; }
        bd[pos] = d2;
        bi[pos] = (long)j;
        if (have < k) have++;
    }
    return have == k ? bi[k - 1] : -1;
}

cs_status est_knn_clearance(const double *x, const double *y, const double *r, size_t n,
                            size_t i, int k, double *g)
{
    long j = est_knn(x, y, n, i, k);
    if (j < 0) return cs_err(CS_EINPUT, "estimator: tree %zu has fewer than %d neighbours", i, k);
    *g = est_clearance(x[i], y[i], r + i * CROWN_NSEC, x[j], y[j], r + (size_t)j * CROWN_NSEC);
    return CS_OK;
}

double est_w1_sorted(const double *a, size_t na, const double *b, size_t nb)
{
    /* Breakpoints in units of 1/(na nb): a's step i ends at (i+1) nb, b's step
     * j at (j+1) na; integer arithmetic keeps the merge exact. */
    size_t i = 0, j = 0;
    unsigned long long u = 0, ea = nb, eb = na;
    double sum = 0.0;
    while (i < na && j < nb) {
        unsigned long long e = ea < eb ? ea : eb;
        sum += fabs(a[i] - b[j]) * (double)(e - u);
        u = e;
        if (ea == e) { i++; ea += nb; }
        if (eb == e) { j++; eb += na; }
    }
    return sum / ((double)na * (double)nb);
}

static cs_status est_sorted_copy(const double *v, size_t n, double **out)
{
    if (n == 0) return cs_err(CS_EINPUT, "estimator: empty sample");
    double *c = malloc(n * sizeof *c);
    if (!c) return cs_err(CS_ENOMEM, "estimator: out of memory");
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(v[i])) { free(c); return cs_err(CS_EINPUT, "estimator: non-finite value at %zu", i); }
        c[i] = v[i];
    }
    gsl_sort(c, 1, n);
    *out = c;
    return CS_OK;
}

cs_status est_w1(const double *a, size_t na, const double *b, size_t nb, double *w1)
{
    double *sa = NULL, *sb = NULL;
    cs_status st = est_sorted_copy(a, na, &sa);
    if (st) return st;
    st = est_sorted_copy(b, nb, &sb);
    if (st) { free(sa); return st; }
    *w1 = est_w1_sorted(sa, na, sb, nb);
    free(sa);
    free(sb);
    return CS_OK;
}

cs_status est_cover(const double *x, const double *y, const double *r, size_t n,
                    double x0, double y0, double x1, double y1, double *cover)
{
    if (!(x1 > x0) || !(y1 > y0)) return cs_err(CS_EINPUT, "estimator: empty cover window");
    size_t nx = (size_t)ceil((x1 - x0) / EST_COVER_GRID_M);
    size_t ny = (size_t)ceil((y1 - y0) / EST_COVER_GRID_M);
    double hx = (x1 - x0) / (double)nx, hy = (y1 - y0) / (double)ny;
    unsigned char *in = calloc(nx * ny, 1);
    if (!in) return cs_err(CS_ENOMEM, "estimator: out of memory");
    for (size_t t = 0; t < n; t++) {
        const double *rt = r + t * CROWN_NSEC;
        double rmax = 0.0;
        for (int s = 0; s < CROWN_NSEC; s++) if (rt[s] > rmax) rmax = rt[s];
        /* Cells whose centre can lie within rmax of the stem. */
        double lo_x = (x[t] - rmax - x0) / hx - 0.5, hi_x = (x[t] + rmax - x0) / hx - 0.5;
        double lo_y = (y[t] - rmax - y0) / hy - 0.5, hi_y = (y[t] + rmax - y0) / hy - 0.5;
        if (hi_x < 0.0 || hi_y < 0.0 || lo_x > (double)nx || lo_y > (double)ny) continue;
        size_t ix0 = lo_x < 0.0 ? 0 : (size_t)lo_x, iy0 = lo_y < 0.0 ? 0 : (size_t)lo_y;
        size_t ix1 = hi_x + 1.0 > (double)nx ? nx : (size_t)(hi_x + 1.0);
        size_t iy1 = hi_y + 1.0 > (double)ny ? ny : (size_t)(hi_y + 1.0);
        for (size_t iy = iy0; iy < iy1; iy++) {
            double py = y0 + ((double)iy + 0.5) * hy - y[t];
            for (size_t ix = ix0; ix < ix1; ix++) {
                if (in[iy * nx + ix]) continue;
                double px = x0 + ((double)ix + 0.5) * hx - x[t];
                double d2 = px * px + py * py;
                if (d2 > rmax * rmax) continue;
                if (sqrt(d2) <= crown_radius_at(rt, atan2(py, px))) in[iy * nx + ix] = 1;
            }
        }
    }
    size_t cnt = 0;
    for (size_t k = 0; k < nx * ny; k++) cnt += in[k];
    free(in);
    *cover = (double)cnt / ((double)nx * (double)ny);
    return CS_OK;
}

void est_cardinal_gaps(const double *x, const double *y, const double *r, size_t n,
                       size_t i, double gaps[4])
{
    for (int c = 0; c < 4; c++) gaps[c] = NAN;
    for (size_t j = 0; j < n; j++) {
        if (j == i) continue;
        double dx = x[j] - x[i], dy = y[j] - y[i];
        double th = atan2(dy, dx);
        double g = est_clearance(x[i], y[i], r + i * CROWN_NSEC, x[j], y[j], r + j * CROWN_NSEC);
        for (int c = 0; c < 4; c++) {
            /* Angular distance to the cardinal bearing c*pi/2, in [0, pi]. */
            double dth = fabs(remainder(th - 0.5 * CROWN_PI * (double)c, 2.0 * CROWN_PI));
            if (dth <= 0.25 * CROWN_PI + 1e-12 && !(g >= gaps[c])) gaps[c] = g;
        }
    }
}

double est_tree_mean(const double gaps[4])
{
    return 0.25 * (gaps[0] + gaps[1] + gaps[2] + gaps[3]);
}

int est_anisotropy(const double gaps[4], double *aniso)
{
    double lo = gaps[0], hi = gaps[0];
    for (int c = 0; c < 4; c++) {
        if (!(gaps[c] > 0.0)) return 0;
        if (gaps[c] < lo) lo = gaps[c];
        if (gaps[c] > hi) hi = gaps[c];
    }
    *aniso = hi / lo;
    return 1;
}

double est_elongation_cardinal(const double *ri)
{
    double ns = crown_radius_at(ri, 0.5 * CROWN_PI) + crown_radius_at(ri, 1.5 * CROWN_PI);
    double ew = crown_radius_at(ri, 0.0) + crown_radius_at(ri, CROWN_PI);
    return ns > ew ? ns / ew : ew / ns;
}

double est_elongation(const double *ri)
{
    /* Axis s runs through sector centres s and s + 12; between centres both
     * ends interpolate linearly over the same angle fraction, so the axis
     * length is piecewise linear and its extremes lie on these 12. */
    double lo = INFINITY, hi = 0.0;
    for (int s = 0; s < CROWN_NSEC / 2; s++) {
        double ax = ri[s] + ri[s + CROWN_NSEC / 2];
        if (ax < lo) lo = ax;
        if (ax > hi) hi = ax;
    }
    return hi / lo;
}

cs_status est_quantile(const double *v, size_t n, double q, double *out)
{
    double *c = NULL;
    cs_status st = est_sorted_copy(v, n, &c);
    if (st) return st;
    *out = gsl_stats_quantile_from_sorted_data(c, 1, n, q);
    free(c);
    return CS_OK;
}

cs_status est_median(const double *v, size_t n, double *out)
{
    double *c = NULL;
    cs_status st = est_sorted_copy(v, n, &c);
    if (st) return st;
    *out = gsl_stats_median_from_sorted_data(c, 1, n);
    free(c);
    return CS_OK;
}

cs_status est_spread(const double *gaps, size_t n, double *iqr)
{
    double *c = NULL;
    cs_status st = est_sorted_copy(gaps, n, &c);
    if (st) return st;
    *iqr = gsl_stats_quantile_from_sorted_data(c, 1, n, 0.75) - gsl_stats_quantile_from_sorted_data(c, 1, n, 0.25);
    free(c);
    return CS_OK;
}

cs_status est_directional_summary(const double *x, const double *y, const double *r, size_t n,
                                  const unsigned char *use, est_directional *out)
{
    memset(out, 0, sizeof *out);
    out->aniso_median = NAN;
    size_t m = n ? n : 1;
    double *tm = malloc(m * sizeof *tm), *gp = malloc(4 * m * sizeof *gp);
    double *an = malloc(m * sizeof *an), *el = malloc(m * sizeof *el), *ec = malloc(m * sizeof *ec);
    if (!tm || !gp || !an || !el || !ec) {
        free(tm); free(gp); free(an); free(el); free(ec);
        return cs_err(CS_ENOMEM, "estimator: out of memory");
    }
    size_t nt = 0, na = 0;
    for (size_t i = 0; i < n; i++) {
        if (use && !use[i]) continue;
        double g[4];
        est_cardinal_gaps(x, y, r, n, i, g);
        if (isnan(g[0]) || isnan(g[1]) || isnan(g[2]) || isnan(g[3])) { out->incomplete++; continue; }
        for (int c = 0; c < 4; c++) gp[4 * nt + c] = g[c];
        tm[nt] = est_tree_mean(g);
        el[nt] = est_elongation(r + i * CROWN_NSEC);
        ec[nt] = est_elongation_cardinal(r + i * CROWN_NSEC);
        if (est_anisotropy(g, &an[na])) na++;
        else out->aniso_excluded++;
        nt++;
    }
    cs_status st = CS_OK;
    out->trees = nt;
    if (nt == 0) st = cs_err(CS_EINPUT, "estimator: no complete tree to summarise");
    if (!st) st = est_median(tm, nt, &out->tree_mean_median);
    if (!st) st = est_spread(gp, 4 * nt, &out->spread);
    if (!st) st = est_median(el, nt, &out->elong_median);
    if (!st) st = est_median(ec, nt, &out->elong_cardinal_median);
    if (!st && na > 0) st = est_median(an, na, &out->aniso_median);
    free(tm); free(gp); free(an); free(el); free(ec);
    return st;
}
