/* teacher: coupled growth with contact abrasion (design.md §4; paper §3.1,
 * Eqs. 1-3), `teacher-2` (mutual abrasion) by default; the one-sided and the
 * two further die-back readings on switches (design.md §7, E0). See teacher.h
 * for the rule, the readings, why the entered
 * crown's die-back is safe, and the contact test. Limits: 24 sectors, 8 sample
 * points per sector interval; overlap thinner than the gap between sample
 * points is invisible to the contact test and to the self-check alike.
 * Why the test is shaped as it
 * is: the self-check must never fire, so the contact test evaluates the very
 * same sample points and clearances, with the same arithmetic (smp_point,
 * pen_into, est_clearance), that teacher_worst_overlap measures. The cheap
 * bounds in front of it (per-tree clear radius, wedge/disk distance) only ever
 * skip neighbours that provably cannot be touched, with a 1e-9 m margin. */
#include "teacher.h"
#include "estimator.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#define NS CROWN_NSEC
#define SPS TEACHER_SAMPLES_PER_SECTOR
#define NSMP (NS * SPS)
#define MARGIN 1e-9

void teacher_params_default(teacher_params *p)
{
    p->beta = 0.06;
    p->coupled = 1;
    p->nres = 48;
    p->gamma = 1.0;
    p->hbar = 0.0;
    p->frozen_out = NULL;
    p->one_sided = 0;
    p->dieback = TEACHER_DIEBACK_OWN;
    p->start_frac = 0.05;
}

const char *teacher_version(const teacher_params *p)
{
    static const char *const names[2][3] = {
        {TEACHER_VERSION, TEACHER_VERSION "-arc", TEACHER_VERSION "-target"},
        {TEACHER_VERSION_ONE_SIDED, TEACHER_VERSION_ONE_SIDED "-arc", TEACHER_VERSION_ONE_SIDED "-target"}};
    int d = p->dieback >= TEACHER_DIEBACK_OWN && p->dieback <= TEACHER_DIEBACK_TARGET ? (int)p->dieback : 0;
    return names[p->one_sided ? 1 : 0][d];
}

/* Die-back of sector k of tree j (flat index jk) under the reading's rule,
 * freezing it; the active count drops when a still-growing sector freezes. */
static void die_back(const teacher_params *p, double *r, const double *rstar, unsigned char *frozen,
                     int *active_j, size_t jk, size_t *nfrozen)
{
    if (!frozen[jk]) {
        if (r[jk] != rstar[jk]) (*active_j)--;
        frozen[jk] = 1;
        (*nfrozen)++;
    }
    if (p->dieback == TEACHER_DIEBACK_TARGET) r[jk] = fmax(0.0, r[jk] - p->beta * rstar[jk]);
    else r[jk] = (1.0 - p->beta) * r[jk];
}

/* The sectors a contact at sector k of tree j abrades: k, and k +- 1 under
 * the neighbouring-sector reading. */
static void abrade(const teacher_params *p, double *r, const double *rstar, unsigned char *frozen,
                   int *active, size_t j, int k, size_t *nfrozen)
{
    int w = p->dieback == TEACHER_DIEBACK_NEIGHBOURS ? 1 : 0;
    for (int q = -w; q <= w; q++)
        die_back(p, r, rstar, frozen, active + j, j * NS + (size_t)((k + q + NS) % NS), nfrozen);
}

/* Unit vectors of the 192 sample bearings (index 8s+q) and of the sector centres. */
typedef struct { double c[NSMP], s[NSMP]; } smp_dirs;

static void smp_dirs_init(smp_dirs *d)
{
    for (int k = 0; k < NSMP; k++) {
        double th = (2.0 * CROWN_PI / (double)NSMP) * (double)k;
        d->c[k] = cos(th);
        d->s[k] = sin(th);
    }
}

/* Sample point k = 8s+q of crown r around (x, y). One function for the contact
 * test and the self-check, so both see identical bits. */
static inline void smp_point(const smp_dirs *d, double x, double y, const double *r, int k,
                             double *px, double *py)
{
    int s = k / SPS, q = k % SPS;
    int s1 = (s + 1 == NS) ? 0 : s + 1;
    double rho = r[s] + ((double)q / (double)SPS) * (r[s1] - r[s]);
    *px = x + rho * d->c[k];
    *py = y + rho * d->s[k];
}

/* Penetration of point (px,py) into crown rj at (xj,yj): rj(theta) - dist
 * (> 0 means strictly inside). Returns -1 without the atan2 when the point is
 * outside the disk of radius rjmax (then it cannot be inside). */
static inline double pen_into(double px, double py, double xj, double yj, const double *rj, double rjmax)
{
    double dx = px - xj, dy = py - yj;
    double d2 = dx * dx + dy * dy;
    if (d2 >= rjmax * rjmax) return -1.0;
    return crown_radius_at(rj, atan2(dy, dx)) - sqrt(d2);
}

/* ---- neighbour lists from a uniform grid ------------------------------------ */
typedef struct { size_t *start; size_t *idx; size_t cap; } nbrs;

static void nbrs_free(nbrs *nb) { free(nb->start); free(nb->idx); nb->start = NULL; nb->idx = NULL; }

/* Pairs (i, j != i) with stem distance < reach_i + reach_j. */
static cs_status nbrs_build(nbrs *nb, size_t n, const double *x, const double *y, const double *reach)
{
    nb->start = calloc(n + 1, sizeof *nb->start);
    nb->idx = NULL;
    if (!nb->start) return cs_err(CS_ENOMEM, "teacher: out of memory");
    if (n == 0) return CS_OK;
    double xmin = x[0], xmax = x[0], ymin = y[0], ymax = y[0], rmax = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (x[i] < xmin) xmin = x[i];
        if (x[i] > xmax) xmax = x[i];
        if (y[i] < ymin) ymin = y[i];
        if (y[i] > ymax) ymax = y[i];
        if (reach[i] > rmax) rmax = reach[i];
    }
    double cell = 2.0 * rmax;
    if (!(cell > 1e-6)) cell = 1e-6;
    long gx = (long)((xmax - xmin) / cell) + 1, gy = (long)((ymax - ymin) / cell) + 1;
    if (gx > 4096) gx = 4096;
    if (gy > 4096) gy = 4096;
    cell = fmax(cell, fmax((xmax - xmin) / (double)gx, (ymax - ymin) / (double)gy) * (1.0 + 1e-12));
    long *head = malloc((size_t)(gx * gy) * sizeof *head);
    long *next = malloc(n * sizeof *next);
    long *cx = malloc(n * sizeof *cx), *cy = malloc(n * sizeof *cy);
    if (!head || !next || !cx || !cy) {
        free(head); free(next); free(cx); free(cy);
        return cs_err(CS_ENOMEM, "teacher: out of memory");
    }
    for (long k = 0; k < gx * gy; k++) head[k] = -1;
    /* Insert in descending index so each cell's list runs in ascending index. */
    for (size_t t = n; t-- > 0;) {
        long a = (long)((x[t] - xmin) / cell), b = (long)((y[t] - ymin) / cell);
        if (a >= gx) a = gx - 1;
        if (b >= gy) b = gy - 1;
        cx[t] = a; cy[t] = b;
        next[t] = head[b * gx + a];
        head[b * gx + a] = (long)t;
    }
    cs_status st = CS_OK;
    for (int pass = 0; pass < 2 && st == CS_OK; pass++) {
        size_t cnt = 0;
        for (size_t i = 0; i < n; i++) {
            if (pass == 0) nb->start[i] = cnt;
            for (long b = cy[i] - 1; b <= cy[i] + 1; b++) {
                if (b < 0 || b >= gy) continue;
                for (long a = cx[i] - 1; a <= cx[i] + 1; a++) {
                    if (a < 0 || a >= gx) continue;
                    for (long j = head[b * gx + a]; j >= 0; j = next[j]) {
                        if ((size_t)j == i) continue;
                        double dx = x[j] - x[i], dy = y[j] - y[i];
                        double lim = reach[i] + reach[j];
                        if (dx * dx + dy * dy >= lim * lim) continue;
                        if (pass == 1) nb->idx[cnt] = (size_t)j;
                        cnt++;
                    }
                }
            }
        }
        if (pass == 0) {
            nb->start[n] = cnt;
            nb->idx = malloc((cnt ? cnt : 1) * sizeof *nb->idx);
            if (!nb->idx) st = cs_err(CS_ENOMEM, "teacher: out of memory");
        }
    }
    free(head); free(next); free(cx); free(cy);
    return st;
}

/* ---- self-check --------------------------------------------------------------- */
static cs_status worst_overlap_d(const smp_dirs *dirs, const double *x, const double *y,
                                 const double *r, size_t n, double *worst)
{
    double *reach = malloc((n ? n : 1) * sizeof *reach);
    if (!reach) return cs_err(CS_ENOMEM, "teacher: out of memory");
    for (size_t i = 0; i < n; i++) {
        double m = 0.0;
        for (int s = 0; s < NS; s++) if (r[i * NS + s] > m) m = r[i * NS + s];
        reach[i] = m;
    }
    nbrs nb;
    cs_status st = nbrs_build(&nb, n, x, y, reach);
    if (st) { free(reach); nbrs_free(&nb); return st; }
    double w = 0.0;
    for (size_t i = 0; i < n; i++) {
        const double *ri = r + i * NS;
        for (size_t e = nb.start[i]; e < nb.start[i + 1]; e++) {
            size_t j = nb.idx[e];
            const double *rj = r + j * NS;
            double g = est_clearance(x[i], y[i], ri, x[j], y[j], rj);
            if (-g > w) w = -g;
            for (int k = 0; k < NSMP; k++) {
                double px, py;
                smp_point(dirs, x[i], y[i], ri, k, &px, &py);
                double p = pen_into(px, py, x[j], y[j], rj, reach[j]);
                if (p > w) w = p;
            }
        }
    }
    free(reach);
    nbrs_free(&nb);
    *worst = w;
    return CS_OK;
}

cs_status teacher_worst_overlap(const double *x, const double *y, const double *r, size_t n, double *worst)
{
    smp_dirs dirs;
    smp_dirs_init(&dirs);
    return worst_overlap_d(&dirs, x, y, r, n, worst);
}

/* ---- growth ------------------------------------------------------------------- */
typedef struct {
    const teacher_stand *st;
    double *r;
    unsigned char *frozen;
    double *curmax;   /* upper bound on max_s r_i,s (stale-high after die-back: safe) */
    nbrs nb;
    double *pvx, *pvy, *pnu; /* per neighbour entry: p_j - p_i and its length */
    smp_dirs dirs;
    double uc[NS], us[NS]; /* sector-centre unit vectors */
    size_t *hits;     /* teacher-2: the crowns one proposal would enter (<= max degree) */
} grow_ws;

/* Would proposal r_i,s = rp enter another crown? (teacher.h (a)-(c)) With
 * hits == NULL (teacher-1) the answer comes at the first crown entered; with
 * hits (teacher-2) every neighbour is tested against the same state and each
 * crown the proposal would enter is listed (ascending neighbour-list order),
 * *nhit of them. */
static int conflict(grow_ws *w, size_t i, int s, double rp, double clear_i, size_t *hits, size_t *nhit)
{
    const teacher_stand *st = w->st;
    const double *ri = w->r + i * NS;
    int sm = (s + NS - 1) % NS, sp = (s + 1) % NS;
    double rho_max = fmax(rp, fmax(ri[sm], ri[sp]));
    if (nhit) *nhit = 0;
    if (rho_max + MARGIN < clear_i) return 0;
    double xi = st->x[i], yi = st->y[i];
    double tmp[NS];
    int have_tmp = 0;
    for (size_t e = w->nb.start[i]; e < w->nb.start[i + 1]; e++) {
        size_t j = w->nb.idx[e];
        double cm = w->curmax[j] + MARGIN;
        double nu = w->pnu[e];
        if (nu - rho_max >= cm) continue;
        double vx = w->pvx[e], vy = w->pvy[e];
        double nu2 = vx * vx + vy * vy;
        /* Distance from p_j to the wedge {bearing in [theta_sm, theta_sp], radius <= rho_max}. */
        double c1 = w->uc[sm] * vy - w->us[sm] * vx;
        double c2 = w->uc[sp] * vy - w->us[sp] * vx;
        if (!(c1 >= 0.0 && c2 <= 0.0)) {
            double best = nu2;
            for (int ray = 0; ray < 2; ray++) {
                int sr = ray ? sp : sm;
                double t = vx * w->uc[sr] + vy * w->us[sr];
                double perp = ray ? c2 : c1;
                double d2;
                if (t <= 0.0) d2 = nu2;
                else if (t >= rho_max) d2 = (t - rho_max) * (t - rho_max) + perp * perp;
                else d2 = perp * perp;
                if (d2 < best) best = d2;
            }
            if (best >= cm * cm) continue;
        }
        if (!have_tmp) {
            memcpy(tmp, ri, sizeof tmp);
            tmp[s] = rp;
            have_tmp = 1;
        }
        const double *rj = w->r + j * NS;
        double xj = st->x[j], yj = st->y[j];
        double rjmax = w->curmax[j];
        /* (b) clearance along the stem line, Eq. 5. */
        if (est_clearance(xi, yi, tmp, xj, yj, rj) < 0.0) goto contact;
        /* (a) i's changed sample points: intervals sm (q = 1..7) and s (q = 0..7). */
        for (int k = sm * SPS + 1; k < sm * SPS + SPS; k++) {
            double px, py;
            smp_point(&w->dirs, xi, yi, tmp, k, &px, &py);
            if (pen_into(px, py, xj, yj, rj, rjmax) > 0.0) goto contact;
        }
        for (int k = s * SPS; k < s * SPS + SPS; k++) {
            double px, py;
            smp_point(&w->dirs, xi, yi, tmp, k, &px, &py);
            if (pen_into(px, py, xj, yj, rj, rjmax) > 0.0) goto contact;
        }
        /* (c) j's sample points inside i's proposed crown. Points farther from
         * p_i than rho_max are outside the changed arcs, and were outside i's
         * unchanged arcs already. */
        /* Only j's points within rho_max of p_i matter; when rho_max < nu they
         * lie within asin(rho_max/nu) of the bearing theta_ji, so scan only the
         * sector intervals covering that cone (plus a 1e-9 rad margin). */
        int t0 = 0, t1 = NS - 1;
        if (rho_max < nu) {
            double half = asin(rho_max / nu) + 1e-9;
            double thji = atan2(-vy, -vx);
            t0 = (int)floor((thji - half) / CROWN_DTHETA);
            t1 = (int)floor((thji + half) / CROWN_DTHETA);
            if (t1 - t0 >= NS) { t0 = 0; t1 = NS - 1; }
        }
        for (int t = t0; t <= t1; t++)
        for (int k = ((t % NS) + NS) % NS * SPS, ke = k + SPS; k < ke; k++) {
            double px, py;
            smp_point(&w->dirs, xj, yj, rj, k, &px, &py);
            double qx = px - xi, qy = py - yi;
            if (qx * qx + qy * qy >= rho_max * rho_max) continue;
            /* Outside the closed wedge [theta_sm, theta_sp] i's radius is unchanged. */
            double scale = MARGIN * (fabs(qx) + fabs(qy));
            if (w->uc[sm] * qy - w->us[sm] * qx < -scale || w->uc[sp] * qy - w->us[sp] * qx > scale) continue;
            if (pen_into(px, py, xi, yi, tmp, rho_max) > 0.0) goto contact;
        }
        continue;
    contact:
        if (!hits) return 1;
        hits[(*nhit)++] = j;
    }
    return hits ? *nhit > 0 : 0;
}

/* Sector whose centre is nearest bearing atan2(dy, dx): round(theta / (2 pi/24))
 * mod 24, a bearing exactly half-way going to the counter-clockwise sector. */
static int nearest_sector(double dx, double dy)
{
    int t = (int)floor(atan2(dy, dx) / CROWN_DTHETA + 0.5);
    return ((t % NS) + NS) % NS;
}

static const double *sort_h;
static int cmp_desc_h(const void *a, const void *b)
{
    size_t i = *(const size_t *)a, j = *(const size_t *)b;
    if (sort_h[i] > sort_h[j]) return -1;
    if (sort_h[i] < sort_h[j]) return 1;
    return (i > j) - (i < j);
}

cs_status teacher_grow(const teacher_stand *st, const teacher_params *p, double *r, teacher_info *info)
{
    teacher_info inf = {0};
    size_t n = st->n;
    if (p->nres < 1 || !(p->beta >= 0.0 && p->beta < 1.0) || !(p->gamma >= 0.0) ||
        !(p->start_frac > 0.0 && p->start_frac <= 1.0) ||
        !(p->dieback >= TEACHER_DIEBACK_OWN && p->dieback <= TEACHER_DIEBACK_TARGET))
        return cs_err(CS_EINPUT, "teacher: bad parameters (N=%d beta=%g gamma=%g start_frac=%g dieback=%d)",
                      p->nres, p->beta, p->gamma, p->start_frac, (int)p->dieback);
    if (n == 0) { if (info) *info = inf; return CS_OK; }
    for (size_t i = 0; i < n * NS; i++)
        if (!(st->rstar[i] > 0.0) || !isfinite(st->rstar[i]))
            return cs_err(CS_EINPUT, "teacher: target radius of tree %zu sector %zu not positive", i / NS, i % NS);

    /* Delta = median R / N; hbar = mean height unless overridden. */
    double *tmpR = malloc(n * sizeof *tmpR);
    if (!tmpR) return cs_err(CS_ENOMEM, "teacher: out of memory");
    memcpy(tmpR, st->R, n * sizeof *tmpR);
    gsl_sort(tmpR, 1, n);
    inf.step = gsl_stats_median_from_sorted_data(tmpR, 1, n) / (double)p->nres;
    free(tmpR);
    double hsum = 0.0;
    for (size_t i = 0; i < n; i++) hsum += st->h[i];
    inf.hbar = p->hbar > 0.0 ? p->hbar : hsum / (double)n;

    if (!p->coupled) {
        /* min(r + k step, r*) reaches r* exactly for every sector: the
         * uncoupled result is the targets themselves. */
        memcpy(r, st->rstar, n * NS * sizeof *r);
        if (p->frozen_out) memset(p->frozen_out, 0, n * NS);
        if (info) *info = inf;
        return CS_OK;
    }

    grow_ws w;
    memset(&w, 0, sizeof w);
    w.st = st;
    w.r = r;
    smp_dirs_init(&w.dirs);
    for (int s = 0; s < NS; s++) { w.uc[s] = cos(crown_theta(s)); w.us[s] = sin(crown_theta(s)); }
    w.frozen = calloc(n * NS, 1);
    w.curmax = malloc(n * sizeof *w.curmax);
    double *step = malloc(n * sizeof *step);
    double *reach = malloc(n * sizeof *reach);
    size_t *order = malloc(n * sizeof *order);
    int *active = malloc(n * sizeof *active);
    cs_status rc = CS_OK;
    if (!w.frozen || !w.curmax || !step || !reach || !order || !active) {
        rc = cs_err(CS_ENOMEM, "teacher: out of memory");
        goto done;
    }
    for (size_t i = 0; i < n; i++) {
        double m = 0.0, c = 0.0;
        for (int s = 0; s < NS; s++) {
            double t = st->rstar[i * NS + s];
            r[i * NS + s] = p->start_frac * t;
            if (t > m) m = t;
            if (r[i * NS + s] > c) c = r[i * NS + s];
        }
        reach[i] = m;
        w.curmax[i] = c;
        double v = p->gamma == 1.0 ? st->h[i] / inf.hbar : pow(st->h[i] / inf.hbar, p->gamma);
        step[i] = inf.step * v;
        order[i] = i;
        active[i] = NS;
    }
    rc = nbrs_build(&w.nb, n, st->x, st->y, reach);
    if (rc) goto done;
    {
        size_t ne = w.nb.start[n];
        w.pvx = malloc((ne ? ne : 1) * sizeof *w.pvx);
        w.pvy = malloc((ne ? ne : 1) * sizeof *w.pvy);
        w.pnu = malloc((ne ? ne : 1) * sizeof *w.pnu);
        if (!w.pvx || !w.pvy || !w.pnu) { rc = cs_err(CS_ENOMEM, "teacher: out of memory"); goto done; }
        size_t deg = 1;
        for (size_t i = 0; i < n; i++) {
            if (w.nb.start[i + 1] - w.nb.start[i] > deg) deg = w.nb.start[i + 1] - w.nb.start[i];
            for (size_t e = w.nb.start[i]; e < w.nb.start[i + 1]; e++) {
                size_t j = w.nb.idx[e];
                w.pvx[e] = st->x[j] - st->x[i];
                w.pvy[e] = st->y[j] - st->y[i];
                w.pnu[e] = sqrt(w.pvx[e] * w.pvx[e] + w.pvy[e] * w.pvy[e]);
            }
        }
        w.hits = malloc(deg * sizeof *w.hits);
        if (!w.hits) { rc = cs_err(CS_ENOMEM, "teacher: out of memory"); goto done; }
    }
    /* Stems closer than their starting crowns (f r*) cannot start without
     * overlap; the rule is not bent for them: the stand is reported unbuildable. */
    {
        double w0 = 0.0;
        rc = worst_overlap_d(&w.dirs, st->x, st->y, r, n, &w0);
        if (rc) goto done;
        if (w0 > TEACHER_OVERLAP_MAX_M) {
            rc = cs_err(CS_EINPUT, "teacher: stand unbuildable: starting crowns (%g r*) already overlap by "
                        "%.17g m (stems too close)", p->start_frac, w0);
            goto done;
        }
    }
    sort_h = st->h;
    qsort(order, n, sizeof *order, cmp_desc_h);

    long max_rounds = 100L * p->nres;
    const int mutual = !p->one_sided;
    for (;;) {
        int moved = 0;
        for (size_t oi = 0; oi < n; oi++) {
            size_t i = order[oi];
            if (!active[i]) continue;
            /* No neighbour can be reached by an arc of radius below clear_i. */
            double clear_i = INFINITY;
            for (size_t e = w.nb.start[i]; e < w.nb.start[i + 1]; e++) {
                double c = w.pnu[e] - w.curmax[w.nb.idx[e]];
                if (c < clear_i) clear_i = c;
            }
            double *ri = r + i * NS;
            const double *ti = st->rstar + i * NS;
            unsigned char *fi = w.frozen + i * NS;
            for (int s = 0; s < NS; s++) {
                if (fi[s] || ri[s] == ti[s]) continue;
                double rp = fmin(ri[s] + step[i], ti[s]);
                moved = 1;
                size_t nhit = 0;
                if (conflict(&w, i, s, rp, clear_i, mutual ? w.hits : NULL, &nhit)) {
                    abrade(p, r, st->rstar, w.frozen, active, i, s, &inf.frozen);
                    /* teacher-2: each crown j the proposal would enter loses beta
                     * of the sector nearest the bearing from p_j to i's proposed
                     * tip, and that sector freezes (again at every contact). */
                    double tx = st->x[i] + rp * w.uc[s], ty = st->y[i] + rp * w.us[s];
                    for (size_t h = 0; h < nhit; h++) {
                        size_t j = w.hits[h];
                        int t = nearest_sector(tx - st->x[j], ty - st->y[j]);
                        abrade(p, r, st->rstar, w.frozen, active, j, t, &inf.frozen);
                        inf.abraded++;
                    }
                } else {
                    ri[s] = rp;
                    if (rp > w.curmax[i]) w.curmax[i] = rp;
                    if (rp == ti[s]) active[i]--;
                }
            }
        }
        if (!moved) break;
        if (++inf.rounds > max_rounds) {
            rc = cs_err(CS_ENUMERIC, "teacher: growth did not settle within 100 N = %ld rounds", max_rounds);
            goto done;
        }
    }
    if (p->frozen_out) memcpy(p->frozen_out, w.frozen, n * NS);
    rc = worst_overlap_d(&w.dirs, st->x, st->y, r, n, &inf.worst_overlap);
    if (rc) goto done;
    if (inf.worst_overlap > TEACHER_OVERLAP_MAX_M)
        rc = cs_err(CS_EINVARIANT, "teacher: self-check failed: worst crown overlap %.17g m > %g m",
                    inf.worst_overlap, TEACHER_OVERLAP_MAX_M);
done:
    nbrs_free(&w.nb);
    free(w.pvx); free(w.pvy); free(w.pnu); free(w.hits);
    free(w.frozen); free(w.curmax); free(step); free(reach); free(order); free(active);
    if (info) *info = inf;
    return rc;
}
