/* exp_main: E3 main experiment and E4 extrapolation (reference paper
 * §4.3-§5.2; SPEC §7 E3/E4, §8). See exp_main.h for the data plan.
 * The error of a run at one spacing is W1 (est_w1, the pinned estimator)
 * between the focal nearest-neighbour clearances of generated patches and of
 * the teacher's patches at that spacing; the run's error is the mean over the
 * unseen spacings. Clearances on patches come from the batched estimator
 * (patch_focal_clearances), checked against est_clearance to 1e-6 m before
 * every run (paper §4.3); a mismatch aborts the run. */
#include "exp_main.h"
#include "afile.h"
#include "estimator.h"
#include "gate.h"
#include "paths.h"
#include "model.h"
#include "opts.h"
#include "patch.h"
#include "prov.h"
#include "seed.h"
#include "stand.h"
#include "stats.h"
#include "stand_grow.h"
#include "train.h"
#include "tsv.h"
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define MAXSP 8

typedef struct {
    double beta, jitter, tol;
    double train_d[MAXSP], unseen_d[MAXSP], extrap_d[MAXSP];
    size_t ntrain, nunseen, nextrap;
} main_design;

static cs_status design_get(main_design *d)
{
    cs_status st;
    if ((st = gate_read_value(PATHS_GATE("mechanism"), "dieback_train", 0, &d->beta))) return st;
    if ((st = gate_read_value(PATHS_GATE("anisotropy"), "canonical_jitter", 0, &d->jitter))) return st;
    if ((st = gate_read_value(PATHS_GATE("main"), "estimator_agreement_tol_m", 0, &d->tol))) return st;
    if ((st = gate_read_values(PATHS_GATE("main"), "train_spacings_m", d->train_d, MAXSP, &d->ntrain))) return st;
    if ((st = gate_read_values(PATHS_GATE("main"), "unseen_spacings_m", d->unseen_d, MAXSP, &d->nunseen))) return st;
    if ((st = gate_read_values(PATHS_GATE("extrapolation"), "spacings_m", d->extrap_d, MAXSP, &d->nextrap))) return st;
    return CS_OK;
}

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
        p->train_stands = 8;   /* x 4 spacings x ~64 interior stems = ~2048 patches */
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

/* Teacher stand k of experiment `exp` at spacing d; every interior stem
 * becomes one patch in ps. stand_count (may be NULL) gets the patches added. */
static cs_status add_stand_patches(const main_design *ds, const char *exp, double d, unsigned k,
                                   patch_set *ps, int *added, double *worst)
{
    stand *sd;
    cs_status st = stand_alloc(&sd, STAND_LATTICE, d, 12.0 * d, ds->jitter, exp, k);
    if (st) return st;
    size_t n = sd->s->n;
    double *r = malloc(n * CROWN_NSEC * sizeof *r);
    if (!r) { stand_free(sd); return cs_err(CS_ENOMEM, "out of memory"); }
    teacher_params tp;
    teacher_params_default(&tp);
    tp.beta = ds->beta;
    st = stand_grow(sd, &tp, NULL, r, NULL, worst);
    patch_stand pst;
    if (!st) st = patch_stand_init(&pst, (int)n, sd->s->x, sd->s->y, r, sd->h, d);
    int cnt = 0;
    for (size_t i = 0; i < n && !st; i++) {
        if (!stems_interior(sd->s, i)) continue;
        patch p;
        st = patch_build(&pst, (int)i, &p);
        if (!st) st = patch_set_add(ps, &p);
        cnt++;
    }
    if (added) *added = cnt;
    free(r);
    stand_free(sd);
    return st;
}

typedef struct {
    double d;
    patch_set *ps;
    int nstands;
    int *per_stand; /* patches contributed by each stand, in order */
    double *teach;  /* focal NN clearance of every patch (teacher crowns) */
} eval_set;

static void eval_free(eval_set *e)
{
    if (e->ps) patch_set_free(e->ps);
    free(e->per_stand);
    free(e->teach);
    memset(e, 0, sizeof *e);
}

/* Focal NN clearances of patches [k0, k0+b) of ps with standardised
 * deviations x (b*T*P); rbuf holds b*T*P radii. */
static cs_status focal_nn(const patch_set *ps, int k0, int b, const float *x, double *rbuf, double *out)
{
    for (int k = 0; k < b; k++)
        patch_set_radii(ps, k0 + k, x + (size_t)k * PATCH_T * PATCH_P, rbuf + (size_t)k * PATCH_T * PATCH_P);
    return patch_focal_clearances(ps->px + (size_t)k0 * PATCH_T, ps->py + (size_t)k0 * PATCH_T, rbuf, b, 1, out);
}

static cs_status eval_build(const main_design *ds, const exp_main_plan *pl, double d, double scale,
                            eval_set *e, double *worst, double *maxdiff)
{
    memset(e, 0, sizeof *e);
    e->d = d;
    e->nstands = pl->eval_stands;
    cs_status st = patch_set_alloc(&e->ps, pl->eval_stands * 100);
    if (st) return st;
    e->per_stand = calloc((size_t)pl->eval_stands, sizeof *e->per_stand);
    if (!e->per_stand) return cs_err(CS_ENOMEM, "out of memory");
    for (int k = 0; k < pl->eval_stands && !st; k++)
        st = add_stand_patches(ds, "main-eval", d, (unsigned)k, e->ps, &e->per_stand[k], worst);
    if (!st) st = patch_set_standardise(e->ps, scale);
    if (st) return st;
    int n = e->ps->n;
    e->teach = malloc((size_t)n * sizeof *e->teach);
    double *rbuf = malloc((size_t)64 * PATCH_T * PATCH_P * sizeof *rbuf);
    if (!e->teach || !rbuf) { free(rbuf); return cs_err(CS_ENOMEM, "out of memory"); }
    for (int k0 = 0; k0 < n && !st; k0 += 64) {
        int b = n - k0 < 64 ? n - k0 : 64;
        st = focal_nn(e->ps, k0, b, e->ps->x1 + (size_t)k0 * PATCH_T * PATCH_P, rbuf, e->teach + k0);
        /* The instrument guard of paper §4.3: the batched estimator must agree
         * with the canonical one on every pair of the first batch. */
        if (!st && k0 == 0) {
            double md;
            st = patch_clearance_check(est_clearance, e->ps->px, e->ps->py, rbuf, b, &md);
            if (!st && md > *maxdiff) *maxdiff = md;
            if (!st && md > ds->tol)
                st = cs_err(CS_EINVARIANT, "batched estimator differs from est_clearance by %.3g m > %.3g m at d = %.1f", md, ds->tol, d);
        }
    }
    free(rbuf);
    return st;
}

static int file_exists(const char *p)
{
    struct stat sb;
    return stat(p, &sb) == 0;
}

static int fail_with(cs_status st)
{
    fprintf(stderr, "crownshy: %s\n", cs_errmsg());
    return cs_exit_code(st);
}

static cs_status build_train(const main_design *ds, const exp_main_plan *pl, patch_set **out, double *worst)
{
    cs_status st = patch_set_alloc(out, (int)ds->ntrain * pl->train_stands * 100);
    for (size_t s = 0; s < ds->ntrain && !st; s++)
        for (int k = 0; k < pl->train_stands && !st; k++)
            st = add_stand_patches(ds, "main-train", ds->train_d[s], (unsigned)k, *out, NULL, worst);
    return st;
}

/* Generate pl->gen_patches (or fewer) patches of e with model m; shuffle != 0
 * permutes the position features among the tokens of each patch (the
 * shuffled-geometry probe), evaluation keeps the true positions. */
static cs_status generate(model *m, int Bmax, const exp_main_plan *pl, const eval_set *e, unsigned seed,
                          int shuffle, double *gen, int *ngen)
{
    int G = e->ps->n < pl->gen_patches ? e->ps->n : pl->gen_patches;
    double *r = malloc((size_t)G * PATCH_T * PATCH_P * sizeof *r);
    gsl_rng *noise = gsl_rng_alloc(gsl_rng_mt19937), *perm = gsl_rng_alloc(gsl_rng_mt19937);
    cs_status st = r && noise && perm ? CS_OK : cs_err(CS_ENOMEM, "out of memory");
    if (!st) {
        gsl_rng_set(noise, (unsigned long)seed_derive(shuffle ? "main-model-shuffled" : "main-model", e->d, seed, "sample"));
        gsl_rng_set(perm, (unsigned long)seed_derive("main-model", e->d, seed, "shuffle"));
        st = model_sample_radii(m, Bmax, e->ps, G, pl->euler, noise, shuffle ? perm : NULL, r);
    }
    if (!st) st = patch_focal_clearances(e->ps->px, e->ps->py, r, G, 1, gen);
    *ngen = G;
    free(r);
    if (noise) gsl_rng_free(noise);
    if (perm) gsl_rng_free(perm);
    return st;
}

int exp_main_cmd_run(int argc, char **argv)
{
    long seedl = 0, epochs = 0, train_stands = 0, pairl = 0;
    const char *arm = NULL, *out = NULL, *scale = "full", *ckpt = NULL;
    const opt_spec spec[] = {
        {"seed", OPT_LONG, &seedl, 1, 4294967295.0, "model seed (required; zero-padded 01 is 1)"},
        {"arm", OPT_STR, &arm, 0, 0, "joint or indep (required)"},
        {"out", OPT_STR, &out, 0, 0, "output table FILE.tsv (required)"},
        {"scale", OPT_STR, &scale, 0, 0, "full or smoke (default full)"},
        {"ckpt", OPT_STR, &ckpt, 0, 0, "checkpoint FILE, resumed from when it exists (default none)"},
        {"epochs", OPT_LONG, &epochs, 1, 1000000, "exploration override of the plan's epochs (default: the plan's)"},
        {"train-stands", OPT_LONG, &train_stands, 1, 10000, "exploration override of the plan's stands per training spacing (default: the plan's)"},
        {"pair", OPT_LONG, &pairl, 0, 1, "1: the pair-aware model of SPEC §8 revision 2; both arms then run the shuffled probe (default 0)"},
    };
    const opts_cmd c = {"main-run", "--seed S --arm joint|indep --out FILE.tsv [--scale full|smoke] [--ckpt FILE]",
                        "One (seed, arm) unit of E3/E4: build teacher data, train the flow model (resuming from\n"
                        "--ckpt if it exists), evaluate W1 of focal nearest-neighbour clearances at the unseen and\n"
                        "extrapolation spacings (joint arm: also the shuffled-geometry probe), write FILE.tsv.",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int rc = opts_parse(&c, argc, argv, NULL, NULL);
    if (rc) return opts_exit_code(rc);
    if (!seedl) { opts_usage_error("main-run", "--seed is required"); return 2; }
    if (!arm) { opts_usage_error("main-run", "--arm is required"); return 2; }
    if (strcmp(arm, "joint") && strcmp(arm, "indep")) { opts_usage_error("main-run", "--arm: must be joint or indep, not '%s'", arm); return 2; }
    if (!out) { opts_usage_error("main-run", "--out is required"); return 2; }
    if (strcmp(scale, "full") && strcmp(scale, "smoke")) { opts_usage_error("main-run", "--scale: must be full or smoke, not '%s'", scale); return 2; }
    unsigned seed = (unsigned)seedl;
    int joint = !strcmp(arm, "joint");
    prov pv;
    prov_begin(&pv, "main", argc, argv);
    main_design ds;
    exp_main_plan pl;
    cs_status st = design_get(&ds);
    if (!st) st = exp_main_plan_get(scale, &pl);
    if (st) return fail_with(st);
    /* exploration overrides (recorded in the provenance command line) */
    if (epochs) pl.epochs = (int)epochs;
    if (train_stands) pl.train_stands = (int)train_stands;
    if (pl.epochs < 1) { opts_usage_error("main-run", "the plan's epochs must be >= 1"); return 2; }
    /* --pair 1: the revision-2 model (SPEC §8 "Pair awareness"); both arms then
     * also run the shuffled-geometry probe (the independent arm as its control) */
    const int pair = (int)pairl;
    double worst = 0.0, maxdiff = 0.0;
    patch_set *tr = NULL;
    if ((st = build_train(&ds, &pl, &tr, &worst))) return fail_with(st);
    double data_scale = patch_set_rms(tr);
    if ((st = patch_set_standardise(tr, data_scale))) { patch_set_free(tr); return fail_with(st); }

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
    if (ckpt && (st = afile_mkdir_parents(ckpt))) { patch_set_free(tr); return fail_with(st); }
    train *t = NULL;
    if ((st = train_alloc(&t, &cfg, tr, &o))) { patch_set_free(tr); return fail_with(st); }
    if (ckpt && file_exists(ckpt)) {
        st = train_load(t, ckpt);
        if (st) {
            fprintf(stderr, "crownshy: %s (delete the checkpoint to restart this run)\n", cs_errmsg());
            train_free(t); patch_set_free(tr);
            return cs_exit_code(st);
        }
        fprintf(stderr, "main-run s%u %s: resuming at step %ld of %ld\n", seed, arm, t->step, o.steps);
    }
    long every = o.steps / 50 > 0 ? o.steps / 50 : 1;
    st = train_run(t, o.steps, ckpt, ckpt ? every : 0, stderr);
    double final_loss = t->loss;
    if (st) { train_free(t); patch_set_free(tr); return fail_with(st); }

    typedef struct { double d, w1; int unseen, probe, ng, nt; } row_t;
    size_t nall = ds.nunseen + ds.nextrap;
    row_t rows[2 * 2 * MAXSP];
    size_t nrows = 0;
    double *gen = malloc((size_t)pl.gen_patches * sizeof *gen);
    if (!gen) st = cs_err(CS_ENOMEM, "out of memory");
    for (size_t si = 0; si < nall && !st; si++) {
        double d = si < ds.nunseen ? ds.unseen_d[si] : ds.extrap_d[si - ds.nunseen];
        eval_set e;
        st = eval_build(&ds, &pl, d, data_scale, &e, &worst, &maxdiff);
        for (int probe = 0; probe < (joint || pair ? 2 : 1) && !st; probe++) {
            int ng = 0;
            double w1 = 0;
            st = generate(t->m, t->B, &pl, &e, seed, probe, gen, &ng);
            if (!st) st = est_w1(gen, (size_t)ng, e.teach, (size_t)e.ps->n, &w1);
            if (st) break;
            rows[nrows++] = (row_t){d, w1, si < ds.nunseen, probe, ng, e.ps->n};
            fprintf(stderr, "main-run s%u %s: d = %.1f %s W1 = %.4f m\n", seed, arm, d, probe ? "shuffled" : "generated", w1);
        }
        eval_free(&e);
    }
    free(gen);
    tsv_writer *w = NULL;
    if (!st) st = tsv_writer_open(&w, out);
    if (!st) {
        snprintf(pv.seeds, sizeof pv.seeds,
                 "stands seed_derive(main-train|main-eval, d, k, stems|crowns); model seed_derive(main-model, 0, %u, init|batch|noise); sampling seed_derive(main-model[-shuffled], d, %u, sample)",
                 seed, seed);
        pv.worst_overlap_m = worst;
        st = prov_write(w, &pv);
    }
    if (!st) {
        tsv_writer_meta(w, "scale", "%s", pl.scale);
        if (cfg.pair)
            tsv_writer_meta(w, "model", "T %d P %d width %d blocks %d heads %d mlp %d joint %d pair %d params %zu",
                            cfg.T, cfg.P, cfg.C, cfg.L, cfg.H, cfg.F, cfg.joint, cfg.pair, model_nparams(&cfg));
        else
            tsv_writer_meta(w, "model", "T %d P %d width %d blocks %d heads %d mlp %d joint %d params %zu",
                            cfg.T, cfg.P, cfg.C, cfg.L, cfg.H, cfg.F, cfg.joint, model_nparams(&cfg));
        tsv_writer_meta(w, "training", "%d patches, batch %d, %d epochs = %ld steps, lr %g, final loss %.6g, deviation scale %.17g m",
                        tr->n, o.batch, pl.epochs, o.steps, o.lr, final_loss, data_scale);
        tsv_writer_meta(w, "eval", "%d teacher stands per spacing, up to %d generated patches, %d Euler steps",
                        pl.eval_stands, pl.gen_patches, pl.euler);
        tsv_writer_meta(w, "estimator_check", "max |batched - est_clearance| = %.3g m (tolerance %.3g m)", maxdiff, ds.tol);
        tsv_writer_columns(w, "seed\tarm\tspacing\tsplit\tprobe\tw1\tn_gen\tn_teacher");
        for (size_t i = 0; i < nrows; i++) {
            tsv_writer_long(w, (long)seed);
            tsv_writer_str(w, arm);
            tsv_writer_dbl(w, rows[i].d);
            tsv_writer_str(w, rows[i].unseen ? "unseen" : "extrap");
            tsv_writer_str(w, rows[i].probe ? "shuffled" : "generated");
            tsv_writer_dbl(w, rows[i].w1);
            tsv_writer_long(w, rows[i].ng);
            tsv_writer_long(w, rows[i].nt);
            tsv_writer_endrow(w);
        }
        st = tsv_writer_commit(w);
        w = NULL;
    }
    if (w) tsv_writer_abort(w);
    train_free(t);
    patch_set_free(tr);
    if (st) return fail_with(st);
    return 0;
}

int exp_main_cmd_baselines(int argc, char **argv)
{
    const char *out = NULL, *scale = "full";
    const opt_spec spec[] = {
        {"out", OPT_STR, &out, 0, 0, "output table FILE.tsv (required)"},
        {"scale", OPT_STR, &scale, 0, 0, "full or smoke (default full)"},
    };
    const opts_cmd c = {"main-baselines", "--out FILE.tsv [--scale full|smoke]",
                        "Direction-blind baseline (every crown replaced by its circular mean) and split-half\n"
                        "noise floor of the teacher, as W1 of focal nearest-neighbour clearances per eval spacing.",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int rc = opts_parse(&c, argc, argv, NULL, NULL);
    if (rc) return opts_exit_code(rc);
    if (!out) { opts_usage_error("main-baselines", "--out is required"); return 2; }
    if (strcmp(scale, "full") && strcmp(scale, "smoke")) { opts_usage_error("main-baselines", "--scale: must be full or smoke, not '%s'", scale); return 2; }
    prov pv;
    prov_begin(&pv, "main", argc, argv);
    main_design ds;
    exp_main_plan pl;
    cs_status st = design_get(&ds);
    if (!st) st = exp_main_plan_get(scale, &pl);
    if (st) return fail_with(st);
    double worst = 0.0, maxdiff = 0.0;
    size_t nall = ds.nunseen + ds.nextrap;
    double blind[2 * MAXSP], noise[2 * MAXSP], dd[2 * MAXSP];
    int nt[2 * MAXSP];
    for (size_t si = 0; si < nall && !st; si++) {
        double d = si < ds.nunseen ? ds.unseen_d[si] : ds.extrap_d[si - ds.nunseen];
        eval_set e;
        st = eval_build(&ds, &pl, d, 1.0, &e, &worst, &maxdiff);
        int n = st ? 0 : e.ps->n;
        double *b = malloc((size_t)(n ? n : 1) * sizeof *b);
        float *zero = calloc((size_t)64 * PATCH_T * PATCH_P, sizeof *zero);
        double *rbuf = malloc((size_t)64 * PATCH_T * PATCH_P * sizeof *rbuf);
        if (!st && (!b || !zero || !rbuf)) st = cs_err(CS_ENOMEM, "out of memory");
        for (int k0 = 0; k0 < n && !st; k0 += 64) {
            int bb = n - k0 < 64 ? n - k0 : 64;
            st = focal_nn(e.ps, k0, bb, zero, rbuf, b + k0);
        }
        if (!st) st = est_w1(b, (size_t)n, e.teach, (size_t)n, &blind[si]);
        int half = 0;
        for (int k = 0; k < e.nstands / 2 && !st; k++) half += e.per_stand[k];
        if (!st && (half == 0 || half == n)) st = cs_err(CS_EINPUT, "noise floor needs at least 2 eval stands");
        if (!st) st = est_w1(e.teach, (size_t)half, e.teach + half, (size_t)(n - half), &noise[si]);
        dd[si] = d;
        nt[si] = n;
        free(b); free(zero); free(rbuf);
        eval_free(&e);
    }
    tsv_writer *w = NULL;
    if (!st) st = tsv_writer_open(&w, out);
    if (!st) {
        snprintf(pv.seeds, sizeof pv.seeds, "stands seed_derive(main-eval, d, k, stems|crowns), k < %d", pl.eval_stands);
        pv.worst_overlap_m = worst;
        st = prov_write(w, &pv);
    }
    if (!st) {
        tsv_writer_meta(w, "scale", "%s", pl.scale);
        tsv_writer_meta(w, "noise_floor", "W1 between the teacher clearances of the first and second half of the eval stands");
        tsv_writer_meta(w, "direction_blind", "W1 between clearances with every crown replaced by its circular mean and the teacher's");
        tsv_writer_columns(w, "spacing\tsplit\tdirection_blind_w1\tnoise_floor_w1\tn_teacher");
        for (size_t si = 0; si < nall; si++) {
            tsv_writer_dbl(w, dd[si]);
            tsv_writer_str(w, si < ds.nunseen ? "unseen" : "extrap");
            tsv_writer_dbl(w, blind[si]);
            tsv_writer_dbl(w, noise[si]);
            tsv_writer_long(w, nt[si]);
            tsv_writer_endrow(w);
        }
        st = tsv_writer_commit(w);
        w = NULL;
    }
    if (w) tsv_writer_abort(w);
    return st ? fail_with(st) : 0;
}

/* Gather the per-run tables into main/runs.tsv (error on unseen spacings and
 * the shuffled probe, per seed and arm) and extrapolation/runs.tsv. */
int exp_main_cmd_summary(int argc, char **argv)
{
    const char *dir = NULL;
    long ns = 0;
    const opt_spec spec[] = {
        {"dir", OPT_STR, &dir, 0, 0, "results root RESULTS (required)"},
        {"seeds", OPT_LONG, &ns, 1, 64, "seeds 1..N to gather (required)"},
    };
    const opts_cmd c = {"main-summary", "--dir RESULTS --seeds N",
                        "Read RESULTS/main/run_s<seed>_<arm>.tsv for seeds 1..N and both arms; write\n"
                        "RESULTS/main/runs.tsv (per-run errors) and RESULTS/extrapolation/runs.tsv.",
                        spec, sizeof spec / sizeof *spec, 0, 0};
    int rc = opts_parse(&c, argc, argv, NULL, NULL);
    if (rc) return opts_exit_code(rc);
    if (!dir) { opts_usage_error("main-summary", "--dir is required"); return 2; }
    if (!ns) { opts_usage_error("main-summary", "--seeds is required"); return 2; }
    int nseeds = (int)ns;
    prov pv;
    prov_begin(&pv, "main", argc, argv);
    const char *arms[2] = {"joint", "indep"};
    typedef struct { double unseen, shuffled, ex[MAXSP], exd[MAXSP]; int nex; } runres;
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
            double su = 0, ss = 0;
            int nu = 0, nsh = 0;
            const char *wo = tsv_meta(t, "worst_overlap_m");
            if (wo && atof(wo) > worst) worst = atof(wo);
            for (size_t i = 0; i < tsv_nrows(t) && !st; i++) {
                double w1, d;
                if ((st = tsv_double(t, i, "w1", &w1)) || (st = tsv_double(t, i, "spacing", &d))) break;
                const char *split = tsv_str(t, i, "split"), *probe = tsv_str(t, i, "probe");
                if (!split || !probe) { st = cs_err(CS_EINPUT, "%s:%d: field 'split'/'probe' missing", p, tsv_line(t, i)); break; }
                if (!strcmp(split, "unseen") && !strcmp(probe, "generated")) { su += w1; nu++; }
                else if (!strcmp(split, "unseen") && !strcmp(probe, "shuffled")) { ss += w1; nsh++; }
                else if (!strcmp(split, "extrap") && !strcmp(probe, "generated") && r->nex < MAXSP) { r->ex[r->nex] = w1; r->exd[r->nex] = d; r->nex++; }
            }
            if (!st && nu == 0) st = cs_err(CS_EINPUT, "%s: no unseen-spacing rows", p);
            if (!st && a == 0 && nsh != nu) st = cs_err(CS_EINPUT, "%s: joint run lacks the shuffled probe at some unseen spacing", p);
            if (!st) { r->unseen = su / nu; r->shuffled = nsh ? ss / nsh : NAN; }
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
                                         : "mean over the unseen spacings of W1 (m) of focal nearest-neighbour clearances; shuffled = joint model with positions permuted within patches");
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
                    tsv_writer_long(w, s); tsv_writer_str(w, arms[a]); tsv_writer_str(w, "generated"); tsv_writer_dbl(w, r->unseen);
                    tsv_writer_endrow(w);
                    if (a == 0) {
                        tsv_writer_long(w, s); tsv_writer_str(w, arms[a]); tsv_writer_str(w, "shuffled"); tsv_writer_dbl(w, r->shuffled);
                        tsv_writer_endrow(w);
                    }
                }
            }
        st = tsv_writer_commit(w);
    }
    free(rr);
    return st ? fail_with(st) : 0;
}
