/* mainsum: the E3/E4 units that need no model (reference paper §4.3,
 * §5.1-§5.2; design.md §7 E3/E4): the baselines of an evaluation volume
 * (direction-blind level, split-half noise floor, the teacher's own crowns under
 * the probes) and the summary of a reading's per-run tables into its
 * main/runs.tsv and extrapolation/runs.tsv. See exp_main.c for the units. */
#include "mainsum.h"
#include "afile.h"
#include "estimator.h"
#include "exp_common.h"
#include "mainrun.h"
#include "mainset.h"
#include "prov.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXSP MAINSET_MAXSP

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

/* The samples behind baselines.tsv (teacher, teacher under each probe,
 * direction-blind) per spacing; hex receives the file's sha256. */
static cs_status samples_baselines_write(const char *samples, prov *pv, size_t nall, const double *dd, const int *uns,
                                         const int *nt, double *const (*smp)[4], char hex[65])
{
    static const char *probe[4] = {"none", "shuffled", "rotated", "none"},
                      *which[4] = {"teacher", "teacher", "teacher", "blind"};
    tsv_writer *w = NULL;
    cs_status st = afile_mkdir_parents(samples);
    if (!st) st = tsv_writer_open(&w, samples);
    if (!st && (st = prov_write(w, pv))) { tsv_writer_abort(w); return st; }
    if (st) return st;
    tsv_writer_meta(w, "what",
                    "focal nearest-neighbour clearances (m) behind every W1 of baselines.tsv: which = teacher (probe "
                    "none: the teacher's crowns; "
                    "shuffled, rotated: the teacher's crowns under the probe) or blind (circular crowns); each W1 = "
                    "est_w1(values, teacher none values); "
                    "noise floor = est_w1(first n_half teacher none values, the rest)");
    tsv_writer_columns(w, "spacing\tsplit\tprobe\twhich\tvalue");
    for (size_t si = 0; si < nall; si++)
        for (int q = 0; q < 4; q++)
            for (int k = 0; k < nt[si]; k++) {
                tsv_writer_dbl(w, dd[si]); tsv_writer_str(w, uns[si] ? "unseen" : "extrap");
                tsv_writer_str(w, probe[q]); tsv_writer_str(w, which[q]); tsv_writer_dbl(w, smp[si][q][k]);
                tsv_writer_endrow(w);
            }
    if ((st = tsv_writer_commit(w))) return st;
    return prov_sha256_file(samples, hex);
}

/* baselines_stands.tsv beside the table `out`: the patches of each stand. */
static cs_status stand_rows_write(const char *out, prov *pv, size_t nall, const double *dd, const int *uns, int nst,
                                  int *const *per)
{
    char path[1024];
    const char *slash = strrchr(out, '/');
    snprintf(path, sizeof path, "%.*sbaselines_stands.tsv", slash ? (int)(slash - out + 1) : 0, out);
    tsv_writer *w;
    cs_status st = afile_mkdir_parents(path);
    if (!st) st = tsv_writer_open(&w, path);
    if (st) return st;
    if ((st = prov_write(w, pv))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "what",
                    "the evaluation stands behind baselines.tsv: per spacing, how many consecutive patches of "
                    "samples_baselines.tsv each stand gave, "
                    "in order (the replicate units of the stand bootstrap, design.md §6.1)");
    tsv_writer_columns(w, "spacing\tsplit\tstand\tpatches");
    for (size_t si = 0; si < nall; si++)
        for (int k = 0; k < nst; k++) {
            tsv_writer_dbl(w, dd[si]);
            tsv_writer_str(w, uns[si] ? "unseen" : "extrap");
            tsv_writer_long(w, k);
            tsv_writer_long(w, per[si][k]);
            tsv_writer_endrow(w);
        }
    return tsv_writer_commit(w);
}

cs_status mainsum_baselines(const mainsum_baselines_args *a)
{
    const char *out = a->out, *scale = a->scale ? a->scale : "full", *samples = a->samples,
               *volume = a->volume ? a->volume : EVALVOL_SMALL;
    const int argc = a->argc;
    char **argv = a->argv;
    prov pv;
    prov_begin(&pv, "main", argc, argv);
    mainset_design ds;
    mainrun_plan pl;
    exp_reading rd;
    cs_status st = exp_reading_parse(NULL, NULL, &rd);
    if (!st) st = exp_reading_vary(a->vary, &rd);
    if (!st) st = mainset_design_get(&ds);
    if (!st) st = mainrun_plan_get(scale, &pl);
    if (!st) st = mainrun_plan_volume(&pl, volume);
    if (st) return st;
    if (rd.varied) {
        ds.crowns = rd.var.crowns;
        ds.nres = rd.var.nres;
        ds.start_frac = rd.var.start_frac;
        ds.dieback = rd.dieback;
    }
    double worst = 0.0, maxdiff = 0.0;
    size_t nall = ds.nunseen + ds.nextrap;
    /* per spacing: 0 teacher, 1 teacher shuffled, 2 teacher rotated, 3 direction-blind */
    double blind[2 * MAXSP], noise[2 * MAXSP], tshuf[2 * MAXSP], trot[2 * MAXSP], dd[2 * MAXSP];
    double *smp[2 * MAXSP][4] = {{0}};
    int nt[2 * MAXSP] = {0}, half[2 * MAXSP] = {0}, uns[2 * MAXSP] = {0};
    int *per[2 * MAXSP] = {0}, nst = pl.eval_stands;
    for (size_t si = 0; si < nall && !st; si++) {
        dd[si] = mainset_eval_spacing(&ds, si, &uns[si]);
        mainset_eval e;
        st = mainset_eval_build(&ds, pl.eval_stands, dd[si], 1.0, &e, &worst, &maxdiff);
        int n = st ? 0 : e.ps->n;
        for (int q = 0; q < 4 && !st; q++)
            if (!(smp[si][q] = malloc((size_t)(n ? n : 1) * sizeof **smp))) st = cs_err(CS_ENOMEM, "out of memory");
        if (!st) st = mainset_teacher_probe(&e, MAINSET_GENERATED, smp[si][0]);
        if (!st) st = mainset_teacher_probe(&e, MAINSET_SHUFFLED, smp[si][1]);
        if (!st) st = mainset_teacher_probe(&e, MAINSET_ROTATED, smp[si][2]);
        if (!st) st = mainset_blind(&e, smp[si][3]);
        if (!st) st = est_w1(smp[si][3], (size_t)n, e.teach, (size_t)n, &blind[si]);
        if (!st) st = est_w1(smp[si][1], (size_t)n, e.teach, (size_t)n, &tshuf[si]);
        if (!st) st = est_w1(smp[si][2], (size_t)n, e.teach, (size_t)n, &trot[si]);
        for (int k = 0; k < e.nstands / 2 && !st; k++) half[si] += e.per_stand[k];
        if (!st && (half[si] == 0 || half[si] == n)) st = cs_err(CS_EINPUT, "noise floor needs at least 2 eval stands");
        if (!st) st = est_w1(e.teach, (size_t)half[si], e.teach + half[si], (size_t)(n - half[si]), &noise[si]);
        nt[si] = n;
        if (!st && a->stand_rows) {
            if (!(per[si] = malloc((size_t)nst * sizeof *per[si]))) st = cs_err(CS_ENOMEM, "out of memory");
            else memcpy(per[si], e.per_stand, (size_t)nst * sizeof *per[si]);
        }
        mainset_eval_free(&e);
    }
    snprintf(pv.seeds, sizeof pv.seeds,
             "stands seed_derive(main-eval, d, k, stems|crowns), k < %d; teacher permutation seed_derive(main-teacher, "
             "d, 0, shuffle)",
             pl.eval_stands);
    pv.worst_overlap_m = worst;
    char ssha[65] = "";
    tsv_writer *w = NULL;
    if (!st && samples) st = samples_baselines_write(samples, &pv, nall, dd, uns, nt, smp, ssha);
    if (!st && a->stand_rows) st = stand_rows_write(out, &pv, nall, dd, uns, nst, per);
    for (size_t si = 0; si < nall; si++) free(per[si]);
    if (!st) st = tsv_writer_open(&w, out);
    if (!st) st = prov_write(w, &pv);
    if (!st) {
        tsv_writer_meta(w, "scale", "%s", pl.scale);
        exp_variant_meta(w, &rd);
        if (!mainrun_volume_small(&pl))
            tsv_writer_meta(w, "volume", "%s: %d teacher stands per spacing", pl.volume, pl.eval_stands);
        tsv_writer_meta(
            w, "noise_floor",
            "W1 between the teacher clearances of the first n_half (first half of the eval stands) and the rest");
        tsv_writer_meta(w, "direction_blind",
                        "W1 between clearances with every crown replaced by its circular mean and the teacher's (a "
                        "rotation leaves it unchanged)");
        tsv_writer_meta(
            w, "teacher_probes",
            "added after the first verdict: W1 between the teacher's own crowns under the shuffled-geometry probe "
            "(token i given the deviation profile of the stem whose position it was given) or the rotation probe "
            "(crowns turned by "
            "(1 + g mod 7) x 45 deg), evaluated at the true positions, and the teacher's: the most a perfect generator "
            "degrades");
        if (samples) tsv_writer_meta(w, "samples", "%s sha256 %s", base_name(samples), ssha);
        tsv_writer_columns(w, "spacing\tsplit\tdirection_blind_w1\tnoise_floor_w1\tteacher_shuffled_w1\tteacher_"
                              "rotated_w1\tn_teacher\tn_half");
        for (size_t si = 0; si < nall; si++) {
            tsv_writer_dbl(w, dd[si]);
            tsv_writer_str(w, uns[si] ? "unseen" : "extrap");
            tsv_writer_dbl(w, blind[si]);
            tsv_writer_dbl(w, noise[si]);
            tsv_writer_dbl(w, tshuf[si]);
            tsv_writer_dbl(w, trot[si]);
            tsv_writer_long(w, nt[si]);
            tsv_writer_long(w, half[si]);
            tsv_writer_endrow(w);
        }
        st = tsv_writer_commit(w);
        w = NULL;
    }
    if (w) tsv_writer_abort(w);
    for (size_t si = 0; si < nall; si++)
        for (int q = 0; q < 4; q++) free(smp[si][q]);
    return st;
}

/* Gather the per-run tables into main/runs.tsv (error on unseen spacings and
 * the shuffled probe, per seed and arm) and extrapolation/runs.tsv. */
/* The per-spacing rows of one run table, reduced to its per-probe means over
 * the unseen spacings and its extrapolation errors; worst overlap carried. */
typedef struct { double probe[MAINSET_NPROBE], ex[MAXSP], exd[MAXSP]; int np[MAINSET_NPROBE], nex; } runres;

static cs_status read_run(const char *p, runres *r, int joint, double *worst)
{
    tsv *t;
    cs_status st = tsv_read(p, &t);
    if (st) return st;
    const char *wo = tsv_meta(t, "worst_overlap_m");
    if (wo && atof(wo) > *worst) *worst = atof(wo);
    for (size_t i = 0; i < tsv_nrows(t) && !st; i++) {
        double w1, d;
        if ((st = tsv_double(t, i, "w1", &w1)) || (st = tsv_double(t, i, "spacing", &d))) break;
        const char *split = tsv_str(t, i, "split"), *probe = tsv_str(t, i, "probe");
        if (!split || !probe) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'split'/'probe' missing", p, tsv_line(t, i));
            break;
        }
        int q = 0;
        while (q < MAINSET_NPROBE && strcmp(probe, mainset_probe_name((mainset_probe)q))) q++;
        if (q == MAINSET_NPROBE) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'probe': unknown '%s'", p, tsv_line(t, i), probe);
            break;
        }
        if (!strcmp(split, "unseen")) {
            r->probe[q] += w1;
            r->np[q]++;
        } else if (!strcmp(split, "extrap") && q == MAINSET_GENERATED && r->nex < MAXSP) {
            r->ex[r->nex] = w1;
            r->exd[r->nex] = d;
            r->nex++;
        }
    }
    if (!st && r->np[0] == 0) st = cs_err(CS_EINPUT, "%s: no unseen-spacing rows", p);
    if (!st && joint && r->np[MAINSET_SHUFFLED] != r->np[0])
        st = cs_err(CS_EINPUT, "%s: joint run lacks the shuffled probe at some unseen spacing", p);
    for (int q = 1; q < MAINSET_NPROBE && !st; q++)
        if (r->np[q] && r->np[q] != r->np[0])
            st = cs_err(CS_EINPUT, "%s: the %s probe misses some unseen spacing", p,
                        mainset_probe_name((mainset_probe)q));
    for (int q = 0; q < MAINSET_NPROBE && !st; q++) r->probe[q] = r->np[q] ? r->probe[q] / r->np[q] : NAN;
    tsv_free(t);
    return st;
}

cs_status mainsum_summary(const mainsum_summary_args *a)
{
    const char *dir = a->dir;
    const int nseeds = a->seeds, argc = a->argc;
    char **argv = a->argv;
    prov pv;
    prov_begin(&pv, "main", argc, argv);
    const char *arms[2] = {"joint", "indep"};
    runres *rr = calloc((size_t)nseeds * 2, sizeof *rr);
    double worst = 0.0;
    cs_status st = rr ? CS_OK : cs_err(CS_ENOMEM, "out of memory");
    for (int s = 1; s <= nseeds && !st; s++)
        for (int a = 0; a < 2 && !st; a++) {
            char p[1024];
            snprintf(p, sizeof p, "%s/main/run_s%02d_%s.tsv", dir, s, arms[a]);
            if ((st = read_run(p, &rr[(s - 1) * 2 + a], a == 0, &worst))) break;
        }
    for (int pass = 0; pass < 2 && !st; pass++) {
        char p[1024];
        snprintf(p, sizeof p, pass ? "%s/extrapolation/runs.tsv" : "%s/main/runs.tsv", dir);
        tsv_writer *w;
        if ((st = tsv_writer_open(&w, p))) break;
        prov_begin(&pv, pass ? "extrapolation" : "main", argc, argv);
        snprintf(pv.seeds, sizeof pv.seeds, "model seeds 1..%d (see each run_s*_*.tsv)", nseeds);
        pv.worst_overlap_m = worst;
        if ((st = prov_write(w, &pv))) { tsv_writer_abort(w); break; }
        tsv_writer_meta(
            w, "error",
            pass ? "W1 (m) of focal nearest-neighbour clearances at each extrapolation spacing"
                 : "mean over the unseen spacings of W1 (m) of focal nearest-neighbour clearances; probe shuffled = "
                   "positions permuted within patches (preregistered), rotated = patch geometry turned about the focal "
                   "stem (added after the first verdict), both evaluated at the true positions");
        tsv_writer_columns(w, pass ? "seed\tarm\tspacing\tw1" : "seed\tarm\tprobe\terror");
        for (int s = 1; s <= nseeds; s++)
            for (int a = 0; a < 2; a++) {
                runres *r = &rr[(s - 1) * 2 + a];
                if (pass) {
                    for (int k = 0; k < r->nex; k++) {
                        tsv_writer_long(w, s);
                        tsv_writer_str(w, arms[a]);
                        tsv_writer_dbl(w, r->exd[k]);
                        tsv_writer_dbl(w, r->ex[k]);
                        tsv_writer_endrow(w);
                    }
                } else {
                    for (int q = 0; q < MAINSET_NPROBE; q++) {
                        if (!r->np[q]) continue;
                        tsv_writer_long(w, s);
                        tsv_writer_str(w, arms[a]);
                        tsv_writer_str(w, mainset_probe_name((mainset_probe)q));
                        tsv_writer_dbl(w, r->probe[q]);
                        tsv_writer_endrow(w);
                    }
                }
            }
        st = tsv_writer_commit(w);
    }
    free(rr);
    return st;
}
