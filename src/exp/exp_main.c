/* exp_main: E3 main experiment and E4 extrapolation (reference paper
 * §4.3-§5.2; design.md §7 E3/E4, §8). See exp_main.h for the data plan and
 * mainset.h for the data, the generation and the probes.
 * The error of a run at one spacing is W1 (est_w1, the pinned estimator)
 * between the focal nearest-neighbour clearances of generated patches and of
 * the teacher's patches at that spacing; the run's error is the mean over the
 * unseen spacings. Clearances on patches come from the batched estimator
 * (patch_focal_clearances), checked against est_clearance to 1e-6 m before
 * every run (paper §4.3); a mismatch aborts the run. Each unit also writes the
 * clearance samples behind every W1 and its final weights; main-redraw draws
 * the samples again from the weights alone. */
#include "exp_main.h"
#include "afile.h"
#include "estimator.h"
#include "mainset.h"
#include "model.h"
#include "opts.h"
#include "patch.h"
#include "paths.h"
#include "prov.h"
#include "seed.h"
#include "sha256.h"
#include "stats.h"
#include "gate.h"
#include "train.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define MAXSP MAINSET_MAXSP

cs_status exp_main_plan_get(const char *scale, exp_main_plan *p)
{
    double epochs, euler;
    cs_status st;
    if ((st = gate_read_value(PATHS_GATE("main"), "epochs", 0, &epochs))) return st;
    if ((st = gate_read_value(PATHS_GATE("main"), "euler_steps", 0, &euler))) return st;
    memset(p, 0, sizeof *p);
    p->euler = (int)euler;
    p->batch = 64;
    p->lr = 2e-3;
    if (!strcmp(scale, "full")) {
        p->scale = "full";
        p->train_stands = EXP_MAIN_TRAIN_STANDS; /* x 4 spacings x ~64 interior stems */
        p->eval_stands = 16;   /* ~1024 teacher clearances per eval spacing */
        p->gen_patches = 256;
        p->epochs = (int)epochs;
    } else if (!strcmp(scale, "smoke")) {
        p->scale = "smoke";
        p->train_stands = 1;
        p->eval_stands = 2;
        p->gen_patches = 32;
        p->epochs = 4;
        p->euler = 10;
    } else return cs_err(CS_EUSAGE, "unknown scale '%s' (full or smoke)", scale);
    return CS_OK;
}

static int file_exists(const char *p)
{
    struct stat sb;
    return stat(p, &sb) == 0;
}

static cs_status file_sha256(const char *path, char hex[65])
{
    FILE *f = fopen(path, "rb");
    if (!f) return cs_err(CS_EIO, "%s: cannot open to hash", path);
    sha256_ctx c;
    sha256_init(&c);
    unsigned char b[65536];
    size_t n;
    while ((n = fread(b, 1, sizeof b, f)) > 0) sha256_update(&c, b, n);
    int bad = ferror(f);
    fclose(f);
    if (bad) return cs_err(CS_EIO, "%s: read error while hashing", path);
    uint8_t d[32];
    sha256_final(&c, d);
    sha256_tohex(d, hex);
    return CS_OK;
}

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

/* One W1 of a run: spacing, probe, the generated clearances behind it, and
 * (on the generated row of a spacing) the teacher's. */
typedef struct {
    double d, w1;
    int unseen, ng, nt;
    mainset_probe probe;
    double *gen, *teach;
} run_row;

static void rows_free(run_row *rows, size_t n)
{
    for (size_t i = 0; i < n; i++) { free(rows[i].gen); free(rows[i].teach); }
}

/* Probes a unit runs: the pair model (revision 2) every probe on both arms;
 * the revision-1 model as it did (joint: shuffled; independent: none). */
static int unit_nprobe(int pair, int joint)
{
    return pair ? MAINSET_NPROBE : joint ? 2 : 1;
}

/* Every evaluation spacing x probe of one model: the rows of a run table and
 * the samples behind them. main-run and main-redraw both come through here. */
static cs_status evaluate(model *m, int Bmax, const mainset_design *ds, const exp_main_plan *pl, double scale,
                          unsigned seed, const char *arm, int nprobe, run_row *rows, size_t *nrows,
                          double *worst, double *maxdiff)
{
    cs_status st = CS_OK;
    *nrows = 0;
    for (size_t si = 0; si < ds->nunseen + ds->nextrap && !st; si++) {
        int unseen;
        double d = mainset_eval_spacing(ds, si, &unseen);
        mainset_eval e;
        st = mainset_eval_build(ds, pl->eval_stands, d, scale, &e, worst, maxdiff);
        for (int probe = 0; probe < nprobe && !st; probe++) {
            run_row *r = &rows[(*nrows)++];
            memset(r, 0, sizeof *r);
            r->d = d; r->unseen = unseen; r->probe = (mainset_probe)probe; r->nt = e.ps->n;
            r->gen = malloc((size_t)pl->gen_patches * sizeof *r->gen);
            if (!probe) r->teach = malloc((size_t)e.ps->n * sizeof *r->teach);
            if (!r->gen || (!probe && !r->teach)) { st = cs_err(CS_ENOMEM, "out of memory"); break; }
            if (!probe) memcpy(r->teach, e.teach, (size_t)e.ps->n * sizeof *r->teach);
            st = mainset_generate(m, Bmax, &e, pl->gen_patches, pl->euler, seed, r->probe, r->gen, &r->ng);
            if (!st) st = est_w1(r->gen, (size_t)r->ng, e.teach, (size_t)e.ps->n, &r->w1);
            if (!st) fprintf(stderr, "main-run s%u %s: d = %.1f %s W1 = %.4f m\n", seed, arm, d, mainset_probe_name(r->probe), r->w1);
        }
        mainset_eval_free(&e);
    }
    return st;
}

/* The samples behind every W1 of a run (README "Frozen samples and weights"):
 * per spacing the teacher's focal NN clearances (which = teacher, probe =
 * none), then the generated ones under each probe (which = generated). */
static cs_status samples_write(const char *path, prov *pv, unsigned seed, const char *arm,
                               const run_row *rows, size_t n)
{
    tsv_writer *w;
    cs_status st = tsv_writer_open(&w, path);
    if (st) return st;
    if ((st = prov_write(w, pv))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "what", "focal nearest-neighbour clearances (m) behind every W1 of run_s%02u_%s.tsv: W1(spacing, probe) = est_w1(generated values of that spacing and probe, teacher values of that spacing), values in drawing order", seed, arm);
    tsv_writer_columns(w, "spacing\tsplit\tprobe\twhich\tvalue");
    for (size_t i = 0; i < n; i++) {
        const run_row *r = &rows[i];
        const char *split = r->unseen ? "unseen" : "extrap";
        for (int k = 0; r->teach && k < r->nt; k++) {
            tsv_writer_dbl(w, r->d); tsv_writer_str(w, split); tsv_writer_str(w, "none"); tsv_writer_str(w, "teacher");
            tsv_writer_dbl(w, r->teach[k]); tsv_writer_endrow(w);
        }
        for (int k = 0; k < r->ng; k++) {
            tsv_writer_dbl(w, r->d); tsv_writer_str(w, split); tsv_writer_str(w, mainset_probe_name(r->probe));
            tsv_writer_str(w, "generated"); tsv_writer_dbl(w, r->gen[k]); tsv_writer_endrow(w);
        }
    }
    return tsv_writer_commit(w);
}

static const char *seeds_text(char *buf, size_t n, unsigned seed)
{
    snprintf(buf, n, "stands seed_derive(main-train|main-eval, d, k, stems|crowns); model seed_derive(main-model, 0, %u, init|batch|noise); "
             "sampling seed_derive(main-model[-shuffled|-rotated], d, %u, sample), permutation seed_derive(main-model, d, %u, shuffle)", seed, seed, seed);
    return buf;
}

cs_status exp_main_run(const exp_main_run_args *a)
{
    const char *arm = a->arm, *out = a->out, *scale = a->scale, *ckpt = a->ckpt, *samples = a->samples, *weights = a->weights;
    const long epochs = a->epochs, train_stands = a->train_stands, pairl = a->pair;
    const int argc = a->argc;
    char **argv = a->argv;
    const unsigned seed = a->seed;
    int joint = !strcmp(arm, "joint");
    prov pv;
    prov_begin(&pv, "main", argc, argv);
    mainset_design ds;
    exp_main_plan pl;
    cs_status st = mainset_design_get(&ds);
    if (!st) st = exp_main_plan_get(scale, &pl);
    if (st) return st;
    /* exploration overrides (recorded in the provenance command line) */
    if (epochs) pl.epochs = (int)epochs;
    if (train_stands) pl.train_stands = (int)train_stands;
    if (pl.epochs < 1) return cs_err(CS_EUSAGE, "main-run: the plan's epochs must be >= 1");
    const int pair = (int)pairl;
    double worst = 0.0, maxdiff = 0.0;
    patch_set *tr = NULL;
    if ((st = mainset_train_build(&ds, pl.train_stands, &tr, &worst))) return st;
    double data_scale = patch_set_rms(tr);
    if ((st = patch_set_standardise(tr, data_scale))) { patch_set_free(tr); return st; }

    model_cfg cfg = model_cfg_reference(PATCH_NCOND);
    cfg.joint = joint;
    cfg.pair = pair;
    train_opts o = train_opts_default();
    o.batch = pl.batch;
    o.lr = pl.lr;
    long spe = (tr->n + o.batch - 1) / o.batch;
    o.steps = (long)pl.epochs * spe;
    o.seed_init = (unsigned long)seed_derive("main-model", 0, seed, "init");
    o.seed_batch = (unsigned long)seed_derive("main-model", 0, seed, "batch");
    o.seed_noise = (unsigned long)seed_derive("main-model", 0, seed, "noise");
    /* the checkpoint's directory must exist before the first atomic write */
    if (ckpt && (st = afile_mkdir_parents(ckpt))) { patch_set_free(tr); return st; }
    train *t = NULL;
    if ((st = train_alloc(&t, &cfg, tr, &o))) { patch_set_free(tr); return st; }
    if (ckpt && file_exists(ckpt)) {
        st = train_load(t, ckpt);
        if (st) {
            char why[512];
            snprintf(why, sizeof why, "%s", cs_errmsg());
            train_free(t); patch_set_free(tr);
            return cs_err(st, "%s (delete the checkpoint to restart this run)", why);
        }
        fprintf(stderr, "main-run s%u %s: resuming at step %ld of %ld\n", seed, arm, t->step, o.steps);
    }
    long every = o.steps / 50 > 0 ? o.steps / 50 : 1;
    st = train_run(t, o.steps, ckpt, ckpt ? every : 0, stderr);
    double final_loss = t->loss;
    char wsha[65] = "", ssha[65] = "", sbuf[256];
    if (!st && weights && !(st = afile_mkdir_parents(weights)) && !(st = train_save_weights(t, weights)))
        st = file_sha256(weights, wsha);
    if (st) { train_free(t); patch_set_free(tr); return st; }

    run_row rows[MAINSET_NPROBE * 2 * MAXSP];
    size_t nrows = 0;
    st = evaluate(t->m, t->B, &ds, &pl, data_scale, seed, arm, unit_nprobe(pair, joint), rows, &nrows, &worst, &maxdiff);
    snprintf(pv.seeds, sizeof pv.seeds, "%s", seeds_text(sbuf, sizeof sbuf, seed));
    pv.worst_overlap_m = worst;
    if (!st && samples && !(st = afile_mkdir_parents(samples)) && !(st = samples_write(samples, &pv, seed, arm, rows, nrows)))
        st = file_sha256(samples, ssha);
    tsv_writer *w = NULL;
    if (!st) st = tsv_writer_open(&w, out);
    if (!st) st = prov_write(w, &pv);
    if (!st) {
        tsv_writer_meta(w, "scale", "%s", pl.scale);
        if (cfg.pair)
            tsv_writer_meta(w, "model", "T %d P %d width %d blocks %d heads %d mlp %d joint %d pair %d params %zu",
                            cfg.T, cfg.P, cfg.C, cfg.L, cfg.H, cfg.F, cfg.joint, cfg.pair, model_nparams(&cfg));
        else
            tsv_writer_meta(w, "model", "T %d P %d width %d blocks %d heads %d mlp %d joint %d params %zu",
                            cfg.T, cfg.P, cfg.C, cfg.L, cfg.H, cfg.F, cfg.joint, model_nparams(&cfg));
        tsv_writer_meta(w, "training", "%d patches (%d stands per training spacing), batch %d, %d epochs = %ld steps, lr %g, final loss %.17g, deviation scale %.17g m",
                        tr->n, pl.train_stands, o.batch, pl.epochs, o.steps, o.lr, final_loss, data_scale);
        tsv_writer_meta(w, "eval", "%d teacher stands per spacing, up to %d generated patches, %d Euler steps; probes: shuffled (preregistered gate)%s",
                        pl.eval_stands, pl.gen_patches, pl.euler,
                        pair ? ", rotated by (1 + g mod 7) x 45 deg about the focal stem (added after the first verdict)" : "");
        tsv_writer_meta(w, "estimator_check", "max |batched - est_clearance| = %.3g m (tolerance %.3g m)", maxdiff, ds.tol);
        if (samples) tsv_writer_meta(w, "samples", "%s sha256 %s", base_name(samples), ssha);
        if (weights) tsv_writer_meta(w, "weights", "%s sha256 %s (weights format 1, README)", base_name(weights), wsha);
        tsv_writer_columns(w, "seed\tarm\tspacing\tsplit\tprobe\tw1\tn_gen\tn_teacher");
        for (size_t i = 0; i < nrows; i++) {
            tsv_writer_long(w, (long)seed);
            tsv_writer_str(w, arm);
            tsv_writer_dbl(w, rows[i].d);
            tsv_writer_str(w, rows[i].unseen ? "unseen" : "extrap");
            tsv_writer_str(w, mainset_probe_name(rows[i].probe));
            tsv_writer_dbl(w, rows[i].w1);
            tsv_writer_long(w, rows[i].ng);
            tsv_writer_long(w, rows[i].nt);
            tsv_writer_endrow(w);
        }
        st = tsv_writer_commit(w);
        w = NULL;
    }
    if (w) tsv_writer_abort(w);
    rows_free(rows, nrows);
    train_free(t);
    patch_set_free(tr);
    return st;
}

/* Redraw the samples of one unit from its frozen weights alone (design.md §9
 * verify-deep): the same evaluation sets, seeds and sampler as main-run. */
cs_status exp_main_redraw(const exp_main_redraw_args *a)
{
    const char *arm = a->arm, *out = a->out, *scale = a->scale, *weights = a->weights;
    const int argc = a->argc;
    char **argv = a->argv;
    const unsigned seed = a->seed;
    prov pv;
    prov_begin(&pv, "main", argc, argv);
    mainset_design ds;
    exp_main_plan pl;
    model *m = NULL;
    double scl = 0, worst = 0, maxdiff = 0;
    cs_status st = mainset_design_get(&ds);
    if (!st) st = exp_main_plan_get(scale, &pl);
    if (!st) st = train_load_model(weights, &m, pl.batch, &scl);
    if (!st && m->cfg.joint != !strcmp(arm, "joint")) st = cs_err(CS_EINPUT, "%s: weights of the %s arm, not %s", weights, m->cfg.joint ? "joint" : "indep", arm);
    run_row rows[MAINSET_NPROBE * 2 * MAXSP];
    size_t nrows = 0;
    char sbuf[256];
    if (!st) st = evaluate(m, pl.batch, &ds, &pl, scl, seed, arm, unit_nprobe(m->cfg.pair, m->cfg.joint), rows, &nrows, &worst, &maxdiff);
    snprintf(pv.seeds, sizeof pv.seeds, "%s", seeds_text(sbuf, sizeof sbuf, seed));
    pv.worst_overlap_m = worst;
    if (!st) st = afile_mkdir_parents(out);
    if (!st) st = samples_write(out, &pv, seed, arm, rows, nrows);
    rows_free(rows, nrows);
    model_free(m);
    return st;
}

cs_status exp_main_baselines(const exp_main_baselines_args *a)
{
    const char *out = a->out, *scale = a->scale, *samples = a->samples;
    const int argc = a->argc;
    char **argv = a->argv;
    prov pv;
    prov_begin(&pv, "main", argc, argv);
    mainset_design ds;
    exp_main_plan pl;
    cs_status st = mainset_design_get(&ds);
    if (!st) st = exp_main_plan_get(scale, &pl);
    if (st) return st;
    double worst = 0.0, maxdiff = 0.0;
    size_t nall = ds.nunseen + ds.nextrap;
    /* per spacing: 0 teacher, 1 teacher shuffled, 2 teacher rotated, 3 direction-blind */
    double blind[2 * MAXSP], noise[2 * MAXSP], tshuf[2 * MAXSP], trot[2 * MAXSP], dd[2 * MAXSP];
    double *smp[2 * MAXSP][4] = {{0}};
    int nt[2 * MAXSP] = {0}, half[2 * MAXSP] = {0}, uns[2 * MAXSP] = {0};
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
        mainset_eval_free(&e);
    }
    snprintf(pv.seeds, sizeof pv.seeds, "stands seed_derive(main-eval, d, k, stems|crowns), k < %d; teacher permutation seed_derive(main-teacher, d, 0, shuffle)", pl.eval_stands);
    pv.worst_overlap_m = worst;
    char ssha[65] = "";
    tsv_writer *w = NULL;
    if (!st && samples) {
        static const char *probe[4] = {"none", "shuffled", "rotated", "none"}, *which[4] = {"teacher", "teacher", "teacher", "blind"};
        if (!(st = afile_mkdir_parents(samples))) st = tsv_writer_open(&w, samples);
        if (!st && (st = prov_write(w, &pv))) { tsv_writer_abort(w); w = NULL; }
        if (!st) {
            tsv_writer_meta(w, "what", "focal nearest-neighbour clearances (m) behind every W1 of baselines.tsv: which = teacher (probe none: the teacher's crowns; "
                            "shuffled, rotated: the teacher's crowns under the probe) or blind (circular crowns); each W1 = est_w1(values, teacher none values); "
                            "noise floor = est_w1(first n_half teacher none values, the rest)");
            tsv_writer_columns(w, "spacing\tsplit\tprobe\twhich\tvalue");
            for (size_t si = 0; si < nall; si++)
                for (int q = 0; q < 4; q++)
                    for (int k = 0; k < nt[si]; k++) {
                        tsv_writer_dbl(w, dd[si]); tsv_writer_str(w, uns[si] ? "unseen" : "extrap");
                        tsv_writer_str(w, probe[q]); tsv_writer_str(w, which[q]); tsv_writer_dbl(w, smp[si][q][k]);
                        tsv_writer_endrow(w);
                    }
            st = tsv_writer_commit(w);
            w = NULL;
        }
        if (!st) st = file_sha256(samples, ssha);
    }
    if (!st) st = tsv_writer_open(&w, out);
    if (!st) st = prov_write(w, &pv);
    if (!st) {
        tsv_writer_meta(w, "scale", "%s", pl.scale);
        tsv_writer_meta(w, "noise_floor", "W1 between the teacher clearances of the first n_half (first half of the eval stands) and the rest");
        tsv_writer_meta(w, "direction_blind", "W1 between clearances with every crown replaced by its circular mean and the teacher's (a rotation leaves it unchanged)");
        tsv_writer_meta(w, "teacher_probes", "added after the first verdict: W1 between the teacher's own crowns under the shuffled-geometry probe "
                        "(token i given the deviation profile of the stem whose position it was given) or the rotation probe (crowns turned by "
                        "(1 + g mod 7) x 45 deg), evaluated at the true positions, and the teacher's: the most a perfect generator degrades");
        if (samples) tsv_writer_meta(w, "samples", "%s sha256 %s", base_name(samples), ssha);
        tsv_writer_columns(w, "spacing\tsplit\tdirection_blind_w1\tnoise_floor_w1\tteacher_shuffled_w1\tteacher_rotated_w1\tn_teacher\tn_half");
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
cs_status exp_main_summary(const exp_main_summary_args *a)
{
    const char *dir = a->dir;
    const int nseeds = a->seeds, argc = a->argc;
    char **argv = a->argv;
    prov pv;
    prov_begin(&pv, "main", argc, argv);
    const char *arms[2] = {"joint", "indep"};
    typedef struct { double probe[MAINSET_NPROBE], ex[MAXSP], exd[MAXSP]; int np[MAINSET_NPROBE], nex; } runres;
    runres *rr = calloc((size_t)nseeds * 2, sizeof *rr);
    double worst = 0.0;
    cs_status st = rr ? CS_OK : cs_err(CS_ENOMEM, "out of memory");
    for (int s = 1; s <= nseeds && !st; s++)
        for (int a = 0; a < 2 && !st; a++) {
            char p[1024];
            snprintf(p, sizeof p, "%s/main/run_s%02d_%s.tsv", dir, s, arms[a]);
            tsv *t;
            if ((st = tsv_read(p, &t))) break;
            runres *r = &rr[(s - 1) * 2 + a];
            const char *wo = tsv_meta(t, "worst_overlap_m");
            if (wo && atof(wo) > worst) worst = atof(wo);
            for (size_t i = 0; i < tsv_nrows(t) && !st; i++) {
                double w1, d;
                if ((st = tsv_double(t, i, "w1", &w1)) || (st = tsv_double(t, i, "spacing", &d))) break;
                const char *split = tsv_str(t, i, "split"), *probe = tsv_str(t, i, "probe");
                if (!split || !probe) { st = cs_err(CS_EINPUT, "%s:%d: field 'split'/'probe' missing", p, tsv_line(t, i)); break; }
                int q = 0;
                while (q < MAINSET_NPROBE && strcmp(probe, mainset_probe_name((mainset_probe)q))) q++;
                if (q == MAINSET_NPROBE) { st = cs_err(CS_EINPUT, "%s:%d: field 'probe': unknown '%s'", p, tsv_line(t, i), probe); break; }
                if (!strcmp(split, "unseen")) { r->probe[q] += w1; r->np[q]++; }
                else if (!strcmp(split, "extrap") && q == MAINSET_GENERATED && r->nex < MAXSP) { r->ex[r->nex] = w1; r->exd[r->nex] = d; r->nex++; }
            }
            if (!st && r->np[0] == 0) st = cs_err(CS_EINPUT, "%s: no unseen-spacing rows", p);
            if (!st && a == 0 && r->np[MAINSET_SHUFFLED] != r->np[0]) st = cs_err(CS_EINPUT, "%s: joint run lacks the shuffled probe at some unseen spacing", p);
            for (int q = 1; q < MAINSET_NPROBE && !st; q++)
                if (r->np[q] && r->np[q] != r->np[0]) st = cs_err(CS_EINPUT, "%s: the %s probe misses some unseen spacing", p, mainset_probe_name((mainset_probe)q));
            for (int q = 0; q < MAINSET_NPROBE && !st; q++) r->probe[q] = r->np[q] ? r->probe[q] / r->np[q] : NAN;
            tsv_free(t);
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
        tsv_writer_meta(w, "error", pass ? "W1 (m) of focal nearest-neighbour clearances at each extrapolation spacing"
                                         : "mean over the unseen spacings of W1 (m) of focal nearest-neighbour clearances; probe shuffled = positions permuted within patches (preregistered), rotated = patch geometry turned about the focal stem (added after the first verdict), both evaluated at the true positions");
        tsv_writer_columns(w, pass ? "seed\tarm\tspacing\tw1" : "seed\tarm\tprobe\terror");
        for (int s = 1; s <= nseeds; s++)
            for (int a = 0; a < 2; a++) {
                runres *r = &rr[(s - 1) * 2 + a];
                if (pass) {
                    for (int k = 0; k < r->nex; k++) {
                        tsv_writer_long(w, s); tsv_writer_str(w, arms[a]); tsv_writer_dbl(w, r->exd[k]); tsv_writer_dbl(w, r->ex[k]);
                        tsv_writer_endrow(w);
                    }
                } else {
                    for (int q = 0; q < MAINSET_NPROBE; q++) {
                        if (!r->np[q]) continue;
                        tsv_writer_long(w, s); tsv_writer_str(w, arms[a]); tsv_writer_str(w, mainset_probe_name((mainset_probe)q));
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
