/* claim_main: computing functions for the E3 main and E4 extrapolation
 * claims (reference paper §5.1-§5.2; gates/main.gate, gates/extrapolation.gate),
 * from a reading's main/runs.tsv, main/baselines.tsv and extrapolation/runs.tsv
 * written by src/exp/exp_main.c (frozen/extension-pair-16-stands/: the pair
 * extension at 16-stands), or from its per-run tables directly: a source
 * "<root>/main/run_s*_*.tsv" (the paper reading, frozen/paper-reading/), or a
 * main/runs.tsv not made yet, is gathered by src/claims/mainruns.h with
 * main-summary's reduction, and is pending, naming the frozen seeds and the
 * missing units, until every unit of the design is frozen. The runs and
 * baselines of a claim are those of the root of its source, and what a
 * function computes (arm, probe, bound, quantity) comes from the row's params,
 * so one function serves every reading (design.md §8 "Readings of the
 * generator"). m_J and m_I are medians over seeds of the per-run error; p is
 * the exact two-sided Wilcoxon signed-rank test of the paired per-seed errors. */
#include "claims.h"
#include "mainruns.h"
#include "paths.h"
#include "stats.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* the folder of the paper reading under its training choices (design.md §8.2) */
#define GENSENS_DIR "/generator-sensitivity/"

#define MAXSEED 64

/* Per seed: k = 0 joint generated, 1 indep generated, 2 joint shuffled (the
 * three the gates judge, required), then the probes added after the first
 * verdict: 3 indep shuffled, 4 joint rotated, 5 indep rotated
 * (present for every seed or for none). */
#define NK 6
typedef struct { int n; double v[NK][MAXSEED]; int has[NK]; int partial; } main_runs;

static int run_kind(const char *arm, const char *probe)
{
    int a = !strcmp(arm, "joint") ? 0 : !strcmp(arm, "indep") ? 1 : -1;
    int q = !strcmp(probe, "generated") ? 0 : !strcmp(probe, "shuffled") ? 1 : !strcmp(probe, "rotated") ? 2 : -1;
    if (a < 0 || q < 0) return -1;
    static const int k[3][2] = {{0, 1}, {2, 3}, {4, 5}};
    return k[q][a];
}

static const char *kind_name(int k)
{
    static const char *n[NK] = {"joint", "indep", "shuffled", "indep shuffled", "joint rotated", "indep rotated"};
    return n[k];
}

/* dir of "<dir>/runs.tsv" when that summary is not there: its units are read instead */
static int summary_absent(const char *path, char *dir, size_t n)
{
    size_t l = strlen(path), k = strlen("/main/runs.tsv");
    if (l < k || strcmp(path + l - k, "/main/runs.tsv") || access(path, F_OK) == 0) return 0;
    snprintf(dir, n, "%.*s", (int)(l - strlen("/runs.tsv")), path);
    return 1;
}

/* The units of dir (mainruns.h); a set not yet whole leaves res pending. */
static cs_status load_units(const claim_row *row, const char *dir, mainruns *m, claim_result *res)
{
    int want;
    cs_status st = claim_param_seeds(row, &want);
    if (!st) st = mainruns_load(dir, want, m);
    if (st) return st;
    if (m->nmissing) {
        mainruns_pending_text(m, dir, res->why, sizeof res->why);
        res->status = VERDICT_PENDING;
    }
    snprintf(res->where, sizeof res->where,
             "%s/run_s*_*.tsv (%d seeds x 2 arms; per seed the mean W1 over the unseen spacings)", dir, m->want);
    return CS_OK;
}

/* A set not yet whole leaves res pending; the values of an arm whose every
 * seed is frozen are kept all the same (r->partial), for the descriptive rows
 * that read that arm alone (arm_whole). */
static cs_status read_units(const claim_row *row, const char *dir, main_runs *r, claim_result *res)
{
    static mainruns m;
    cs_status st = load_units(row, dir, &m, res);
    if (st) return st;
    const int pending = res->status == VERDICT_PENDING;
    r->n = m.want;
    r->partial = pending;
    for (int a = 0; a < 2; a++)
        for (int q = 0; q < 3; q++) {
            static const int k[3][2] = {{0, 1}, {2, 3}, {4, 5}};
            r->has[k[q][a]] = pending ? m.has[a][q] == m.want : m.has[a][q] > 0;
            memcpy(r->v[k[q][a]], m.err[a][q], sizeof r->v[0]);
        }
    return CS_OK;
}

/* Whether a claim may be computed from the kinds ka and kb (-1: none) of r:
 * always for a whole set; for a set still pending only when the row is
 * descriptive (kind probe: never gated, no interval) and those kinds' arm
 * has every seed frozen, then computed and said so (design.md §8.2). */
static int arm_whole(const claim_row *row, const main_runs *r, claim_result *res, int ka, int kb)
{
    if (res->status != VERDICT_PENDING) return 1;
    if (!r->partial || strcmp(row->kind, "probe") || !r->has[ka] || (kb >= 0 && !r->has[kb])) return 0;
    res->status = VERDICT_PASS;
    res->why[0] = '\0';
    size_t l = strlen(res->where);
    snprintf(res->where + l, sizeof res->where - l, "; that arm whole, the other still running");
    return 1;
}

static cs_status read_runs(const claim_row *row, const char *path, main_runs *r, claim_result *res)
{
    tsv *t;
    memset(r, 0, sizeof *r);
    char dir[300];
    if (mainruns_unit_set(path, dir, sizeof dir) || summary_absent(path, dir, sizeof dir))
        return read_units(row, dir, r, res);
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    int seen[MAXSEED][NK] = {{0}};
    int maxs = 0;
    for (size_t i = 0; i < tsv_nrows(t) && !st; i++) {
        long s;
        double e;
        if ((st = tsv_long(t, i, "seed", &s)) || (st = tsv_double(t, i, "error", &e))) break;
        const char *arm = tsv_str(t, i, "arm"), *probe = tsv_str(t, i, "probe");
        if (s < 1 || s > MAXSEED || !arm || !probe) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'seed': out of range or arm/probe missing", path, tsv_line(t, i));
            break;
        }
        int k = run_kind(arm, probe);
        if (k < 0) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'arm'/'probe': unexpected '%s'/'%s'", path, tsv_line(t, i), arm,
                        probe);
            break;
        }
        if (seen[s - 1][k]++) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'seed': seed %ld %s/%s appears twice", path, tsv_line(t, i), s, arm,
                        probe);
            break;
        }
        r->v[k][s - 1] = e;
        r->has[k] = 1;
        if (s > maxs) maxs = (int)s;
    }
    for (int s = 0; s < maxs && !st; s++)
        for (int k = 0; k < NK; k++)
            if ((k < 3 || r->has[k]) && !seen[s][k]) {
                st = cs_err(CS_EINPUT, "%s: seed %d lacks its %s row", path, s + 1, kind_name(k));
                break;
            }
    double want;
    if (!st && !(st = gate_read_value(PATHS_GATE("main"), "seeds", 0, &want)) && maxs != (int)want)
        st = cs_err(CS_EINPUT, "%s: %d seeds, gates/main.gate requires %g", path, maxs, want);
    r->n = maxs;
    snprintf(res->where, sizeof res->where, "%s (%d seeds x 2 arms)", path, maxs);
    tsv_free(t);
    return st;
}

/* out = <root of source>/main/<leaf>: the root is what precedes the last
 * "/main/" or "/extrapolation/" of the source path. */
static void reading_path(const char *source, const char *leaf, char *out, size_t n)
{
    const char *cut = NULL;
    for (const char *q = source; (q = strstr(q, "/main/")); q++) cut = q;
    for (const char *q = source; (q = strstr(q, "/extrapolation/")); q++) if (!cut || q > cut) cut = q;
    int len = cut ? (int)(cut - source) : (int)strlen("frozen");
    snprintf(out, n, "%.*s/main/%s", len, cut ? source : "frozen", leaf);
}

static double med(const double *x, int n)
{
    double m = NAN;
    stats_median(x, (size_t)n, &m);
    return m;
}

/* mean over the unseen spacings of the direction-blind or noise-floor W1 */
/* source: the row's source (a reading's main/ or extrapolation/ table, whose
 * baselines.tsv is read), or a baselines table itself (a sensitivity run's,
 * design.md §7 E0). */
cs_status claim_main_baseline_mean(const char *source, const char *col, const char *split, double d_only, double *out,
                                   char *where, size_t wn)
{
    char path[200];
    size_t ls = strlen(source), lb = strlen("baselines.tsv");
    const char *choice = strstr(source, GENSENS_DIR);
    if (ls >= lb && !strcmp(source + ls - lb, "baselines.tsv")) snprintf(path, sizeof path, "%s", source);
    /* a training choice is evaluated on the paper reading's stands: its baselines are that reading's */
    else if (choice)
        snprintf(path, sizeof path, "%.*s/paper-reading/main/baselines.tsv", (int)(choice - source), source);
    else reading_path(source, "baselines.tsv", path, sizeof path);
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    double s = 0;
    int n = 0;
    for (size_t i = 0; i < tsv_nrows(t) && !st; i++) {
        double v, d;
        const char *sp = tsv_str(t, i, "split");
        if ((st = tsv_double(t, i, col, &v)) || (st = tsv_double(t, i, "spacing", &d))) break;
        if (!sp) { st = cs_err(CS_EINPUT, "%s:%d: field 'split' missing", path, tsv_line(t, i)); break; }
        if (strcmp(sp, split) || (d_only > 0 && fabs(d - d_only) > 1e-9)) continue;
        s += v;
        n++;
    }
    if (!st && n == 0) st = cs_err(CS_EINPUT, "%s: no %s rows%s", path, split, d_only > 0 ? " at that spacing" : "");
    if (!st) *out = s / n;
    if (where) snprintf(where, wn, "%s (%s, %s)", path, col, split);
    tsv_free(t);
    return st;
}

cs_status claim_main_median(const claim_row *row, claim_result *res)
{
    main_runs r;
    int k;
    cs_status st = claim_param_seed_column(row, &k);
    if (!st) st = read_runs(row, row->source, &r, res);
    if (st || !arm_whole(row, &r, res, k, -1)) return st;
    claim_set_value(row, res, med(r.v[k], r.n));
    return CS_OK;
}

/* How many seeds' joint arm passes the preregistered shuffle threshold on its
 * own (its shuffled error over its error, main.gate:shuffle_ratio_min): a
 * reading whose seeds split into two kinds of solution shows it here, where a
 * ratio of medians would hide it. */
cs_status claim_main_coupled(const claim_row *row, claim_result *res)
{
    main_runs r;
    cs_status st = read_runs(row, row->source, &r, res);
    if (st || !arm_whole(row, &r, res, 0, 2)) return st;
    double thr;
    if ((st = gate_read_value(PATHS_GATE("main"), "shuffle_ratio_min", 0, &thr))) return st;
    if (!r.has[2]) return cs_err(CS_EINPUT, "%s: no shuffled rows for the joint arm", row->source);
    int n = 0;
    for (int s = 0; s < r.n; s++) n += r.v[2][s] / r.v[0][s] >= thr;
    claim_set_value(row, res, n);
    return CS_OK;
}

cs_status claim_main_range(const claim_row *row, claim_result *res)
{
    main_runs r;
    int k;
    cs_status st = claim_param_need(row, PARAM_BOUND);
    if (!st) st = claim_param_seed_column(row, &k);
    if (!st) st = read_runs(row, row->source, &r, res);
    if (st || res->status == VERDICT_PENDING) return st;
    const double *x = r.v[k];
    claim_set_value(row, res, row->param.bound == BOUND_HI ? stats_max(x, (size_t)r.n) : stats_min(x, (size_t)r.n));
    return CS_OK;
}

cs_status claim_main_rel(const claim_row *row, claim_result *res)
{
    main_runs r;
    cs_status st = read_runs(row, row->source, &r, res);
    if (st || res->status == VERDICT_PENDING) return st;
    double mj = med(r.v[0], r.n), mi = med(r.v[1], r.n);
    double rel = (mi - mj) / mi;
    claim_set_value(row, res, 100.0 * rel);
    claim_judge(row, res, GATE_GE, rel);
    return CS_OK;
}

cs_status claim_main_p(const claim_row *row, claim_result *res)
{
    main_runs r;
    cs_status st = read_runs(row, row->source, &r, res);
    if (st || res->status == VERDICT_PENDING) return st;
    double p;
    if ((st = stats_wilcoxon_exact(r.v[1], r.v[0], (size_t)r.n, &p, NULL, NULL))) return st;
    claim_set_value(row, res, p);
    claim_judge(row, res, GATE_LT, p);
    return CS_OK;
}

cs_status claim_main_geom_ratio(const claim_row *row, claim_result *res)
{
    main_runs r;
    cs_status st = read_runs(row, row->source, &r, res);
    if (st || !arm_whole(row, &r, res, 0, 2)) return st;
    double ratio = med(r.v[2], r.n) / med(r.v[0], r.n);
    claim_set_value(row, res, ratio);
    claim_judge(row, res, GATE_GE, ratio);
    return CS_OK;
}

cs_status claim_main_noise(const claim_row *row, claim_result *res)
{
    double v;
    cs_status st =
        claim_main_baseline_mean(row->source, "noise_floor_w1", "unseen", 0, &v, res->where, sizeof res->where);
    if (st) return st;
    claim_set_value(row, res, v);
    return CS_OK;
}

cs_status claim_main_iso(const claim_row *row, claim_result *res)
{
    double v;
    cs_status st =
        claim_main_baseline_mean(row->source, "direction_blind_w1", "unseen", 0, &v, res->where, sizeof res->where);
    if (st) return st;
    claim_set_value(row, res, v);
    /* precondition: m_J <= 0.5 x direction-blind error (needs the runs) */
    main_runs r;
    claim_result tmp = *res;
    char runs[200];
    reading_path(row->source, "runs.tsv", runs, sizeof runs);
    tmp.status = VERDICT_PASS;
    if (read_runs(row, runs, &r, &tmp) != CS_OK) {
        res->gate = VERDICT_PENDING;
        snprintf(res->gate_detail, sizeof res->gate_detail, "needs %s: %s", runs, cs_errmsg());
    } else if (tmp.status == VERDICT_PENDING) {
        res->gate = VERDICT_PENDING;
        snprintf(res->gate_detail, sizeof res->gate_detail, "precondition pending: %.230s", tmp.why);
    } else
        claim_judge(row, res, GATE_LE, med(r.v[0], r.n) / v);
    return CS_OK;
}

/* The probes added after the first verdict (kind "probe", never
 * gated): medians over seeds of an arm's error under the shuffled or the
 * rotation probe (stat=median), or their ratio to the arm's own error
 * (stat=ratio: median of the probe error / median of the error, as
 * MainGeomRatio). */
cs_status claim_main_probe(const claim_row *row, claim_result *res)
{
    int k;
    cs_status st = claim_param_need(row, PARAM_PROBE | PARAM_STAT);
    if (!st) st = claim_param_seed_column(row, &k);
    if (st) return st;
    if (row->param.stat != STAT_MEDIAN && row->param.stat != STAT_RATIO)
        return claim_param_bad(row, "stat", "median or ratio");
    const int ratio_of = row->param.stat == STAT_RATIO ? k % 2 : -1;
    main_runs r;
    if ((st = read_runs(row, row->source, &r, res))) return st;
    if (!arm_whole(row, &r, res, k, ratio_of)) return CS_OK;
    if (!r.has[k]) return cs_err(CS_EINPUT, "%s: no %s rows (runs made without the probes)", row->source, kind_name(k));
    double v = med(r.v[k], r.n);
    if (ratio_of >= 0) v /= med(r.v[ratio_of], r.n);
    claim_set_value(row, res, v);
    return CS_OK;
}

/* The teacher's own crowns under a probe: mean over the unseen spacings of
 * W1(teacher under the probe, teacher) from baselines.tsv. */
cs_status claim_main_teach_probe(const claim_row *row, claim_result *res)
{
    double v;
    char col[40];
    cs_status st = claim_param_need(row, PARAM_PROBE);
    if (st) return st;
    snprintf(col, sizeof col, "teacher_%s_w1", param_probe_name(row->param.probe));
    if ((st = claim_main_baseline_mean(row->source, col, "unseen", 0, &v, res->where, sizeof res->where))) return st;
    claim_set_value(row, res, v);
    return CS_OK;
}

/* The folder of a reading's run tables named by a source (a unit set, a
 * main/runs.tsv or a baselines table beside them). */
static void runs_dir(const char *source, char *dir, size_t n)
{
    if (mainruns_unit_set(source, dir, n)) return;
    reading_path(source, "", dir, n);
    size_t l = strlen(dir);
    if (l && dir[l - 1] == '/') dir[l - 1] = '\0';
}

/* The readings table's descriptive columns (design.md §8): quantity=params,
 * the parameter count on the `# model:` line of the seed-1 joint run; and
 * quantity=steps_per_s, the median over the reading's frozen units of the training
 * speed on their `# train_time:` line (a wall-clock figure of the machine
 * that trained them; pending when no unit recorded one). */
cs_status claim_main_meta(const claim_row *row, claim_result *res)
{
    char dir[300], p[400];
    cs_status st = claim_param_need(row, PARAM_QUANTITY);
    if (st) return st;
    const int params = !strcmp(row->param.quantity, "params");
    if (!params && strcmp(row->param.quantity, "steps_per_s"))
        return claim_param_bad(row, "quantity", "params or steps_per_s");
    runs_dir(row->source, dir, sizeof dir);
    int want;
    if ((st = claim_param_seeds(row, &want))) return st;
    double v[2 * MAXSEED];
    size_t nv = 0, units = 0;
    for (int s = 1; s <= want && !(params && units); s++)
        for (int a = 0; a < 2 && !(params && units); a++) {
            snprintf(p, sizeof p, "%s/run_s%02d_%s.tsv", dir, s, a ? "indep" : "joint");
            if (access(p, F_OK) != 0) continue;
            tsv *t;
            if ((st = tsv_read(p, &t))) return st;
            units++;
            const char *m = tsv_meta(t, params ? "model" : "train_time");
            const char *q = m ? strstr(m, params ? "params " : "steps_per_s ") : NULL;
            if (q) v[nv++] = atof(q + (params ? 7 : 12));
            else if (params) st = cs_err(CS_EINPUT, "%s: its '# model:' line names no parameter count", p);
            tsv_free(t);
            if (st) return st;
        }
    if (!units) {
        claim_pending(res, "%s: no unit of the reading frozen yet (%d seeds x 2 arms to run)", dir, want);
        return CS_OK;
    }
    if (!nv) {
        claim_pending(res, "%s: none of its %zu frozen units recorded a training speed (a '# train_time:' line): "
                      "they were trained before the speed was written, and re-evaluated from their weights since",
                      dir, units);
        return CS_OK;
    }
    snprintf(res->where, sizeof res->where,
             params ? "%s/run_s01_joint.tsv (# model: params)"
                    : "%s/run_s*_*.tsv (# train_time: steps_per_s, median over %zu units)",
             dir, nv);
    claim_set_value(row, res, med(v, (int)nv));
    return CS_OK;
}

/* The paper reading over the seeds frozen so far (descriptive, never gated,
 * never a verdict), by quantity: seeds, the seeds with both arms frozen
 * (text); over them the medians joint and indep, rel (%), geom_ratio (median
 * shuffled / median joint), rot_ratio (median turned-geometry / median joint)
 * and iso_ratio (median joint / the direction-blind level of the reading's
 * baselines). When every seed is frozen they equal the gated claims' values. */
cs_status claim_main_sofar(const claim_row *row, claim_result *res)
{
    char dir[300];
    cs_status st = claim_param_need(row, PARAM_QUANTITY);
    if (st) return st;
    static const char *const known[] = {"seeds", "joint", "indep", "rel", "geom_ratio", "rot_ratio", "iso_ratio"};
    const char *what = row->param.quantity;
    size_t q = 0;
    while (q < sizeof known / sizeof *known && strcmp(known[q], what)) q++;
    if (q == sizeof known / sizeof *known)
        return claim_param_bad(row, "quantity", "seeds, joint, indep, rel, geom_ratio, rot_ratio or iso_ratio");
    if (!mainruns_unit_set(row->source, dir, sizeof dir))
        return cs_err(CS_EINPUT, "%s: claim_main_sofar reads a unit set <dir>/run_s*_*.tsv", row->source);
    static mainruns m;
    int want;
    st = claim_param_seeds(row, &want);
    if (!st) st = mainruns_load(dir, want, &m);
    if (st) return st;
    double j[MAXSEED], i[MAXSEED], sh[MAXSEED], ro[MAXSEED];
    int n = 0;
    for (int s = 0; s < want; s++)
        if (m.seed_ok[s]) {
            j[n] = m.err[0][0][s];
            i[n] = m.err[1][0][s];
            sh[n] = m.err[0][1][s];
            ro[n] = m.err[0][2][s];
            n++;
        }
    snprintf(res->where, sizeof res->where, "%s/run_s*_*.tsv (%d of %d seeds frozen, both arms)", dir, n, want);
    /* a count of frozen units, not a measured quantity: text, so the typed
     * spacings of the write-up (4.0, 5.0, 6.0 m) are never read as rounding it */
    if (!strcmp(what, "seeds")) { snprintf(res->text, sizeof res->text, "%d", n); return CS_OK; }
    if (!n) { claim_pending(res, "%s: no seed of the reading has both arms frozen yet", dir); return CS_OK; }
    double mj = med(j, n), mi = med(i, n);
    if (!strcmp(what, "joint")) claim_set_value(row, res, mj);
    else if (!strcmp(what, "indep")) claim_set_value(row, res, mi);
    else if (!strcmp(what, "rel")) claim_set_value(row, res, 100.0 * (mi - mj) / mi);
    else if (!strcmp(what, "geom_ratio")) claim_set_value(row, res, med(sh, n) / mj);
    else if (!strcmp(what, "rot_ratio")) claim_set_value(row, res, med(ro, n) / mj);
    else {
        double blind;
        if ((st = claim_main_baseline_mean(row->source, "direction_blind_w1", "unseen", 0, &blind, NULL, 0))) return st;
        claim_set_value(row, res, mj / blind);
    }
    return CS_OK;
}

/* extrapolation: per spacing, median over seeds of each arm's W1 */
typedef struct { int n; double d[4]; double joint[4][MAXSEED], indep[4][MAXSEED]; int nj[4], ni[4]; } extrap_runs;

static cs_status read_extrap_units(const claim_row *row, const char *dir, extrap_runs *e, claim_result *res)
{
    static mainruns m;
    cs_status st = load_units(row, dir, &m, res);
    if (st || res->status == VERDICT_PENDING) return st;
    if (!m.nex) return cs_err(CS_EINPUT, "%s: no extrapolation rows in its run tables", dir);
    e->n = m.nex;
    for (int k = 0; k < m.nex; k++) {
        e->d[k] = m.exd[k];
        e->nj[k] = e->ni[k] = m.want;
        memcpy(e->joint[k], m.ex[0][k], sizeof e->joint[k]);
        memcpy(e->indep[k], m.ex[1][k], sizeof e->indep[k]);
    }
    return CS_OK;
}

static cs_status read_extrap(const claim_row *row, const char *path, extrap_runs *e, claim_result *res)
{
    memset(e, 0, sizeof *e);
    char dir[300];
    if (mainruns_unit_set(path, dir, sizeof dir)) return read_extrap_units(row, dir, e, res);
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    for (size_t i = 0; i < tsv_nrows(t) && !st; i++) {
        long s;
        double d, w1;
        if ((st = tsv_long(t, i, "seed", &s)) || (st = tsv_double(t, i, "spacing", &d)) ||
            (st = tsv_double(t, i, "w1", &w1)))
            break;
        const char *arm = tsv_str(t, i, "arm");
        int k = 0;
        while (k < e->n && fabs(e->d[k] - d) > 1e-9) k++;
        if (k == e->n) {
            if (e->n == 4) {
                st = cs_err(CS_EINPUT, "%s:%d: more than 4 spacings", path, tsv_line(t, i));
                break;
            }
            e->d[e->n++] = d;
        }
        if (s < 1 || s > MAXSEED || !arm) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'seed' or 'arm' invalid", path, tsv_line(t, i));
            break;
        }
        if (!strcmp(arm, "joint")) e->joint[k][e->nj[k]++] = w1;
        else if (!strcmp(arm, "indep")) e->indep[k][e->ni[k]++] = w1;
        else { st = cs_err(CS_EINPUT, "%s:%d: field 'arm': '%s'", path, tsv_line(t, i), arm); break; }
    }
    for (int k = 0; k < e->n && !st; k++)
        if (e->nj[k] != e->ni[k] || e->nj[k] < 1)
            st = cs_err(CS_EINPUT, "%s: spacing %.1f has %d joint and %d indep runs", path, e->d[k], e->nj[k],
                        e->ni[k]);
    snprintf(res->where, sizeof res->where, "%s", path);
    tsv_free(t);
    return st;
}

cs_status claim_extrap_rel(const claim_row *row, claim_result *res)
{
    extrap_runs e;
    cs_status st = claim_param_need(row, PARAM_BOUND);
    if (!st) st = read_extrap(row, row->source, &e, res);
    if (st || res->status == VERDICT_PENDING) return st;
    gate *g;
    if ((st = claim_gate_load("extrapolation.gate", &g))) return st;
    double dlo, dhi;
    st = gate_value(g, "spacings_m", 0, &dlo);
    if (!st) st = gate_value(g, "spacings_m", 1, &dhi);
    gate_free(g);
    if (st) return st;
    /* bound: the lower (first) or the higher of the gate's two spacings */
    double want = row->param.bound == BOUND_LO ? dlo : dhi;
    int k = 0;
    while (k < e.n && fabs(e.d[k] - want) > 1e-9) k++;
    if (k == e.n) return cs_err(CS_EINPUT, "%s: no runs at %.1f m", row->source, want);
    double mj = med(e.joint[k], e.nj[k]), mi = med(e.indep[k], e.ni[k]);
    double rel = (mi - mj) / mi;
    claim_set_value(row, res, 100.0 * rel);
    claim_judge(row, res, GATE_GE, rel);
    /* judged per spacing, together with: the joint arm below the direction-blind error there */
    double blind;
    if ((st = claim_main_baseline_mean(row->source, "direction_blind_w1", "extrap", want, &blind, NULL, 0))) {
        char bp[200];
        reading_path(row->source, "baselines.tsv", bp, sizeof bp);
        res->gate = VERDICT_PENDING;
        snprintf(res->gate_detail, sizeof res->gate_detail, "needs %s: %s", bp, cs_errmsg());
        return CS_OK;
    }
    if (res->gate == VERDICT_PASS && !(mj < blind)) res->gate = VERDICT_FAIL;
    size_t l = strlen(res->gate_detail);
    snprintf(res->gate_detail + l, sizeof res->gate_detail - l, "; joint %.4g %s direction-blind %.4g at %.1f m", mj,
             mj < blind ? "<" : ">=", blind, want);
    return CS_OK;
}

cs_status claim_extrap_p(const claim_row *row, claim_result *res)
{
    extrap_runs e;
    cs_status st = read_extrap(row, row->source, &e, res);
    if (st || res->status == VERDICT_PENDING) return st;
    /* Pooled over the extrapolation spacings at the level of the seed: the two
     * spacings of one seed share one trained model, so the independent unit of
     * the paired test is the seed (mean W1 over the spacings per arm). Rows are
     * written seed by seed, so index i is the same seed at every spacing. */
    double a[MAXSEED], b[MAXSEED];
    int n = e.nj[0];
    for (int k = 1; k < e.n; k++)
        if (e.nj[k] != n) return cs_err(CS_EINPUT, "%s: spacings have different seed counts", row->source);
    for (int i = 0; i < n; i++) {
        a[i] = b[i] = 0;
        for (int k = 0; k < e.n; k++) { a[i] += e.indep[k][i] / e.n; b[i] += e.joint[k][i] / e.n; }
    }
    double p;
    if ((st = stats_wilcoxon_exact(a, b, (size_t)n, &p, NULL, NULL))) return st;
    snprintf(res->where, sizeof res->where, "%s (%d seeds, mean over %d spacings per seed)", row->source, n, e.n);
    claim_set_value(row, res, p);
    claim_judge(row, res, GATE_LT, p);
    return CS_OK;
}
