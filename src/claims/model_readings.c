/* model_readings: the generator readings table; see model_readings.h. */
#include "model_readings.h"
#include "gate.h"
#include "paths.h"
#include "prov.h"
#include "stats.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define MAXSEED 64

static const struct { const char *reading, *role, *dir; } READ[] = {
    {"paper", "gated", "paper-reading"},
    {"pair", "extension", "extension-pair"},
    {"paper-fourier", "descriptive", "model-readings/paper-fourier"},
    {"plain", "descriptive", "model-readings/plain"},
};
#define NREAD (sizeof READ / sizeof READ[0])

static double med(const double *x, size_t n)
{
    double m = NAN;
    if (n) stats_median(x, n, &m);
    return m;
}

/* errors[arm][probe][seed-1] of main/runs.tsv (arm 0 joint, 1 indep; probe 0
 * generated, 1 shuffled, 2 rotated); *ns seeds; has[arm][probe]. */
static cs_status read_main(const char *path, double e[2][3][MAXSEED], int has[2][3], int *ns)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    memset(has, 0, sizeof(int) * 6);
    *ns = 0;
    for (size_t i = 0; i < tsv_nrows(t) && !st; i++) {
        long s;
        double v;
        if ((st = tsv_long(t, i, "seed", &s)) || (st = tsv_double(t, i, "error", &v))) break;
        const char *arm = tsv_str(t, i, "arm"), *probe = tsv_str(t, i, "probe");
        int a = arm && !strcmp(arm, "joint") ? 0 : arm && !strcmp(arm, "indep") ? 1 : -1;
        int q = probe && !strcmp(probe, "generated")  ? 0
                : probe && !strcmp(probe, "shuffled") ? 1
                : probe && !strcmp(probe, "rotated")  ? 2
                                                      : -1;
        if (a < 0 || q < 0 || s < 1 || s > MAXSEED) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'seed'/'arm'/'probe' invalid", path, tsv_line(t, i));
            break;
        }
        e[a][q][s - 1] = v;
        has[a][q]++;
        if (s > *ns) *ns = (int)s;
    }
    for (int a = 0; a < 2 && !st; a++)
        for (int q = 0; q < 3 && !st; q++)
            if (has[a][q] && has[a][q] != *ns)
                st = cs_err(CS_EINPUT, "%s: %d of %d seeds have the %s %s rows", path, has[a][q], *ns,
                            a ? "indep" : "joint", q ? (q == 1 ? "shuffled" : "rotated") : "generated");
    if (!st && (!has[0][0] || !has[1][0])) st = cs_err(CS_EINPUT, "%s: both arms' generated rows are required", path);
    tsv_free(t);
    return st;
}

/* Relative improvement at the lower (lo = 1) or upper extrapolation spacing. */
static cs_status extrap_rel(const char *path, double *lo, double *hi)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    double d[2] = {NAN, NAN}, v[2][2][MAXSEED];
    size_t n[2][2] = {{0}};
    for (size_t i = 0; i < tsv_nrows(t) && !st; i++) {
        double sp, w;
        if ((st = tsv_double(t, i, "spacing", &sp)) || (st = tsv_double(t, i, "w1", &w))) break;
        const char *arm = tsv_str(t, i, "arm");
        int a = arm && !strcmp(arm, "joint") ? 0 : 1, k = isnan(d[0]) || d[0] == sp ? 0 : 1;
        if (k == 1 && !isnan(d[1]) && d[1] != sp) { st = cs_err(CS_EINPUT, "%s: more than two spacings", path); break; }
        d[k] = sp;
        if (n[k][a] < MAXSEED) v[k][a][n[k][a]++] = w;
    }
    tsv_free(t);
    if (st) return st;
    double r[2];
    for (int k = 0; k < 2; k++) {
        double mj = med(v[k][0], n[k][0]), mi = med(v[k][1], n[k][1]);
        r[k] = (mi - mj) / mi;
    }
    const int low = d[0] < d[1] ? 0 : 1;
    *lo = r[low];
    *hi = r[1 - low];
    return CS_OK;
}

static double blind_level(const char *root)
{
    char p[1024];
    snprintf(p, sizeof p, "%s/paper-reading/main/baselines.tsv", root);
    tsv *t;
    if (tsv_read(p, &t)) return NAN;
    double s = 0;
    int n = 0;
    for (size_t i = 0; i < tsv_nrows(t); i++) {
        double v;
        const char *sp = tsv_str(t, i, "split");
        if (sp && !strcmp(sp, "unseen") && !tsv_double(t, i, "direction_blind_w1", &v)) { s += v; n++; }
    }
    tsv_free(t);
    return n ? s / n : NAN;
}

/* params of the seed-1 joint run, median steps/s over the units with a training time */
static void run_meta(const char *dir, int ns, long *params, double *sps)
{
    double v[2 * MAXSEED];
    size_t nv = 0;
    *params = -1;
    for (int s = 1; s <= ns; s++)
        for (int a = 0; a < 2; a++) {
            char p[1100];
            snprintf(p, sizeof p, "%s/main/run_s%02d_%s.tsv", dir, s, a ? "indep" : "joint");
            tsv *t;
            if (tsv_read(p, &t)) continue;
            const char *m = tsv_meta(t, "model"), *tt = tsv_meta(t, "train_time");
            const char *q = m ? strstr(m, "params ") : NULL;
            if (q && *params < 0) *params = atol(q + 7);
            q = tt ? strstr(tt, "steps_per_s ") : NULL;
            if (q && nv < 2 * MAXSEED) v[nv++] = atof(q + 12);
            tsv_free(t);
        }
    *sps = med(v, nv);
}

cs_status model_readings_compute(const char *root, model_readings_row *rows, size_t *n)
{
    *n = 0;
    const double blind = blind_level(root);
    double thr;
    cs_status gst = gate_read_value(PATHS_GATE("main"), "shuffle_ratio_min", 0, &thr);
    if (gst) return gst;
    for (size_t k = 0; k < NREAD; k++) {
        char dir[1024], p[1100];
        snprintf(dir, sizeof dir, "%s/%s", root, READ[k].dir);
        snprintf(p, sizeof p, "%s/main/runs.tsv", dir);
        if (access(p, F_OK) != 0) continue;
        double e[2][3][MAXSEED];
        int has[2][3], ns;
        cs_status st = read_main(p, e, has, &ns);
        if (st) return st;
        model_readings_row *r = &rows[(*n)++];
        memset(r, 0, sizeof *r);
        r->reading = READ[k].reading; r->role = READ[k].role; r->dir = READ[k].dir;
        r->seeds = ns;
        r->joint = med(e[0][0], (size_t)ns);
        r->indep = med(e[1][0], (size_t)ns);
        r->blind = blind;
        r->rel = (r->indep - r->joint) / r->indep;
        r->p = NAN;
        if (ns >= 1 && (st = stats_wilcoxon_exact(e[1][0], e[0][0], (size_t)ns, &r->p, NULL, NULL))) return st;
        r->shuf_joint = has[0][1] ? med(e[0][1], (size_t)ns) / r->joint : NAN;
        r->shuf_indep = has[1][1] ? med(e[1][1], (size_t)ns) / r->indep : NAN;
        r->rot_joint = has[0][2] ? med(e[0][2], (size_t)ns) / r->joint : NAN;
        for (int q = 0; q < ns && has[0][1]; q++) r->coupled += e[0][1][q] / e[0][0][q] >= thr;
        snprintf(p, sizeof p, "%s/extrapolation/runs.tsv", dir);
        if ((st = extrap_rel(p, &r->ex_lo, &r->ex_hi))) return st;
        run_meta(dir, ns, &r->params, &r->steps_per_s);
    }
    return CS_OK;
}

cs_status model_readings_write(const char *path, const char *root, const model_readings_row *rows, size_t n,
                               int argc, char **argv)
{
    prov pv;
    prov_begin(&pv, "model-readings", argc, argv);
    snprintf(pv.seeds, sizeof pv.seeds, "the seeds of each reading's runs (see its run tables)");
    pv.worst_overlap_m = -1;
    tsv_writer *w;
    cs_status st = tsv_writer_open(&w, path);
    if (st) return st;
    if ((st = prov_write(w, &pv))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "root", "%s", root);
    tsv_writer_meta(w, "what",
                    "the generator readings (src/claims/model_readings.h): role gated = the reading the preregistered "
                    "gates judge (the reference paper's method), "
                    "extension = added after the first verdict, descriptive = an intermediate reading; errors W1 (m), "
                    "medians over seeds; ratios median probe error / median error");
    /* A training speed is the machine's, not a result: it goes to the
     * provenance lines, so a rerun's data rows equal the frozen ones. */
    for (size_t i = 0; i < n; i++) {
        char key[64];
        snprintf(key, sizeof key, "steps_per_s_%s", rows[i].reading);
        tsv_writer_meta(w, key, "%.4g (median over its units' training, wall clock)", rows[i].steps_per_s);
    }
    tsv_writer_columns(
        w,
        "reading\trole\tdir\tseeds\tcoupled_seeds\tparams\tjoint\tindep\tdirection_blind\trel_improvement\twilcoxon_p\t"
        "shuffle_ratio_joint\tshuffle_ratio_indep\trotation_ratio_joint\textrap_low_rel\textrap_high_rel");
    for (size_t i = 0; i < n; i++) {
        const model_readings_row *r = &rows[i];
        tsv_writer_str(w, r->reading); tsv_writer_str(w, r->role); tsv_writer_str(w, r->dir);
        tsv_writer_long(w, r->seeds); tsv_writer_long(w, r->coupled); tsv_writer_long(w, r->params);
        const double v[] = {r->joint,      r->indep,      r->blind,     r->rel,   r->p,
                            r->shuf_joint, r->shuf_indep, r->rot_joint, r->ex_lo, r->ex_hi};
        for (size_t k = 0; k < sizeof v / sizeof *v; k++) tsv_writer_dbl(w, v[k]);
        tsv_writer_endrow(w);
    }
    return tsv_writer_commit(w);
}

static int same_cell(double a, double b) { return (isnan(a) && isnan(b)) || a == b; }

cs_status model_readings_check(const char *path, const model_readings_row *rows, size_t n)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    if (tsv_nrows(t) != n)
        st = cs_err(CS_EINPUT, "%s: %zu rows, the run tables give %zu readings", path, tsv_nrows(t), n);
    static const char *col[] = {"seeds",
                                "coupled_seeds",
                                "params",
                                "joint",
                                "indep",
                                "direction_blind",
                                "rel_improvement",
                                "wilcoxon_p",
                                "shuffle_ratio_joint",
                                "shuffle_ratio_indep",
                                "rotation_ratio_joint",
                                "extrap_low_rel",
                                "extrap_high_rel"};
    for (size_t i = 0; i < n && !st; i++) {
        const model_readings_row *r = &rows[i];
        const char *name = tsv_str(t, i, "reading");
        if (!name || strcmp(name, r->reading)) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'reading': expected %s", path, tsv_line(t, i), r->reading);
            break;
        }
        const double want[] = {r->seeds, r->coupled, (double)r->params, r->joint, r->indep, r->blind, r->rel, r->p,
                               r->shuf_joint, r->shuf_indep, r->rot_joint, r->ex_lo, r->ex_hi};
        for (size_t c = 0; c < sizeof col / sizeof *col && !st; c++) {
            double v;
            if ((st = tsv_double_nf(t, i, col[c], &v))) break;
            if (!same_cell(v, want[c]))
                st = cs_err(CS_EINPUT, "%s:%d: field '%s': says %.17g but the run tables give %.17g (reading %s)", path,
                            tsv_line(t, i), col[c], v, want[c], r->reading);
        }
    }
    tsv_free(t);
    return st;
}
