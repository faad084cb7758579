/* claim_samples: every W1 of the E3/E4 run tables and of the baselines
 * recomputed from the frozen clearance samples behind it (design.md §8; README
 * "Frozen samples and weights") with est_w1, the pinned estimator's W1, and
 * compared bit for bit. run_s<NN>_<arm>.tsv: W1(spacing, probe) =
 * est_w1(generated values of that spacing and probe, teacher values of that
 * spacing) from samples_s<NN>_<arm>.tsv; baselines.tsv: direction-blind and
 * the teacher probes against the teacher's values, the noise floor between
 * the first n_half teacher values and the rest, from samples_baselines.tsv. */
#include "claims.h"
#include "estimator.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct { double *v; size_t n, cap; } vec;

static int vec_push(vec *x, double v)
{
    if (x->n == x->cap) {
        size_t c = x->cap ? 2 * x->cap : 1024;
        double *p = realloc(x->v, c * sizeof *p);
        if (!p) return -1;
        x->v = p; x->cap = c;
    }
    x->v[x->n++] = v;
    return 0;
}

/* Values of `path` with the given spacing, probe and which, in file order. */
static cs_status pick(const tsv *t, const char *path, double d, const char *probe, const char *which, vec *out)
{
    out->n = 0;
    for (size_t i = 0; i < tsv_nrows(t); i++) {
        double sd, v;
        cs_status st;
        if ((st = tsv_double(t, i, "spacing", &sd))) return st;
        const char *p = tsv_str(t, i, "probe"), *w = tsv_str(t, i, "which");
        if (!p || !w) return cs_err(CS_EINPUT, "%s:%d: field 'probe'/'which' missing", path, tsv_line(t, i));
        if (fabs(sd - d) > 1e-9 || strcmp(p, probe) || strcmp(w, which)) continue;
        if ((st = tsv_double(t, i, "value", &v))) return st;
        if (vec_push(out, v)) return cs_err(CS_ENOMEM, "out of memory");
    }
    return CS_OK;
}

static cs_status same_w1(const char *where, const vec *a, const vec *b, double want, char *msg, size_t mn)
{
    double w1;
    cs_status st = est_w1(a->v, a->n, b->v, b->n, &w1);
    if (st) { snprintf(msg, mn, "%s: %s", where, cs_errmsg()); return st; }
    if (w1 != want) {
        snprintf(msg, mn, "%s: W1 %.17g in the table, %.17g from the samples", where, want, w1);
        return cs_err(CS_EINVARIANT, "%s", msg);
    }
    return CS_OK;
}

static cs_status check_run(const char *run, const char *smp, char *msg, size_t mn, int *nchecked)
{
    tsv *t = NULL, *s = NULL;
    vec g = {0}, te = {0};
    cs_status st = tsv_read(run, &t);
    if (!st) st = tsv_read(smp, &s);
    if (st) snprintf(msg, mn, "%s", cs_errmsg());
    for (size_t i = 0; t && s && i < tsv_nrows(t) && !st; i++) {
        double d, w1;
        long ng, nt;
        const char *probe = tsv_str(t, i, "probe");
        if ((st = tsv_double(t, i, "spacing", &d)) || (st = tsv_double(t, i, "w1", &w1)) ||
            (st = tsv_long(t, i, "n_gen", &ng)) || (st = tsv_long(t, i, "n_teacher", &nt)) || !probe) {
            if (!st) st = cs_err(CS_EINPUT, "%s:%d: field 'probe' missing", run, tsv_line(t, i));
            snprintf(msg, mn, "%s", cs_errmsg());
            break;
        }
        if ((st = pick(s, smp, d, probe, "generated", &g)) || (st = pick(s, smp, d, "none", "teacher", &te))) {
            snprintf(msg, mn, "%s", cs_errmsg());
            break;
        }
        char where[2400];
        snprintf(where, sizeof where, "%s:%d (%.1f m, %s) from %s", run, tsv_line(t, i), d, probe, smp);
        if ((long)g.n != ng || (long)te.n != nt) {
            snprintf(msg, mn, "%s: %zu generated and %zu teacher samples, the table says %ld and %ld", where, g.n, te.n,
                     ng, nt);
            st = cs_err(CS_EINVARIANT, "%s", msg);
            break;
        }
        if ((st = same_w1(where, &g, &te, w1, msg, mn))) break;
        (*nchecked)++;
    }
    free(g.v); free(te.v);
    tsv_free(t); tsv_free(s);
    return st;
}

static cs_status check_baselines(const char *tab, const char *smp, char *msg, size_t mn, int *nchecked)
{
    tsv *t = NULL, *s = NULL;
    vec a = {0}, te = {0};
    cs_status st = tsv_read(tab, &t);
    if (!st) st = tsv_read(smp, &s);
    if (st) snprintf(msg, mn, "%s", cs_errmsg());
    static const char *col[3] = {"direction_blind_w1", "teacher_shuffled_w1", "teacher_rotated_w1"};
    static const char *probe[3] = {"none", "shuffled", "rotated"}, *which[3] = {"blind", "teacher", "teacher"};
    for (size_t i = 0; t && s && i < tsv_nrows(t) && !st; i++) {
        double d, w1;
        long half;
        char where[2400];
        if ((st = tsv_double(t, i, "spacing", &d)) || (st = tsv_long(t, i, "n_half", &half)) ||
            (st = pick(s, smp, d, "none", "teacher", &te))) { snprintf(msg, mn, "%s", cs_errmsg()); break; }
        for (int q = 0; q < 3 && !st; q++) {
            snprintf(where, sizeof where, "%s:%d (%.1f m, %s) from %s", tab, tsv_line(t, i), d, col[q], smp);
            if ((st = tsv_double(t, i, col[q], &w1)) || (st = pick(s, smp, d, probe[q], which[q], &a))) {
                snprintf(msg, mn, "%s", cs_errmsg());
                break;
            }
            if (!(st = same_w1(where, &a, &te, w1, msg, mn))) (*nchecked)++;
        }
        if (st) break;
        if (half < 1 || (size_t)half >= te.n) {
            snprintf(msg, mn, "%s:%d: field 'n_half': %ld outside 1..%zu", tab, tsv_line(t, i), half, te.n - 1);
            st = cs_err(CS_EINPUT, "%s", msg);
            break;
        }
        snprintf(where, sizeof where, "%s:%d (%.1f m, noise_floor_w1) from %s", tab, tsv_line(t, i), d, smp);
        vec h1 = {te.v, (size_t)half, 0}, h2 = {te.v + half, te.n - (size_t)half, 0};
        if ((st = tsv_double(t, i, "noise_floor_w1", &w1))) { snprintf(msg, mn, "%s", cs_errmsg()); break; }
        if (!(st = same_w1(where, &h1, &h2, w1, msg, mn))) (*nchecked)++;
    }
    free(a.v); free(te.v);
    tsv_free(t); tsv_free(s);
    return st;
}

cs_status claim_main_samples_check(const char *root, int maxseed, char *msg, size_t mn, int *nchecked)
{
    static const char *arms[2] = {"joint", "indep"};
    char run[1024], smp[1024];
    *nchecked = 0;
    msg[0] = '\0';
    for (int sd = 1; sd <= maxseed; sd++)
        for (int a = 0; a < 2; a++) {
            snprintf(run, sizeof run, "%s/main/run_s%02d_%s.tsv", root, sd, arms[a]);
            snprintf(smp, sizeof smp, "%s/main/samples_s%02d_%s.tsv", root, sd, arms[a]);
            if (access(run, F_OK) != 0) continue;
            cs_status st = check_run(run, smp, msg, mn, nchecked);
            if (st) return st;
        }
    snprintf(run, sizeof run, "%s/main/baselines.tsv", root);
    snprintf(smp, sizeof smp, "%s/main/samples_baselines.tsv", root);
    if (access(run, F_OK) == 0) return check_baselines(run, smp, msg, mn, nchecked);
    return CS_OK;
}
