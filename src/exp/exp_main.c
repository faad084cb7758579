/* exp_main: E3 main experiment and E4 extrapolation (reference paper
 * §4.3-§5.2; design.md §7 E3/E4, §8). See exp_main.h for the data plan,
 * mainset.h for the data, the generation and the probes, and mainrun.h for a
 * unit's evaluation and tables.
 * The error of a run at one spacing is W1 (est_w1, the pinned estimator)
 * between the focal nearest-neighbour clearances of generated patches and of
 * the teacher's patches at that spacing; the run's error is the mean over the
 * unseen spacings. Clearances on patches come from the batched estimator
 * (patch_focal_clearances), checked against est_clearance to 1e-6 m before
 * every evaluation (paper §4.3); a mismatch aborts the run.
 * Units: main-run trains and evaluates; main-train trains only (weights and a
 * training table); main-eval evaluates weights without training (the run
 * table and samples); main-redraw draws the samples again from weights.
 * Step plan: `epochs` x ceil(patches / batch) steps, while an epoch of the
 * batch order holds floor(patches / batch) whole batches (train.c reshuffles
 * when the next batch would run past the data): 300 epochs of the full plan
 * are 14 700 steps = 306.25 passes over the data. The same for every reading,
 * so the frozen pair-aware runs keep their weights; stated in design.md §8. */
#include "exp_main.h"
#include "speed.h"
#include "exp_common.h"
#include "afile.h"
#include "estimator.h"
#include "mainrun.h"
#include "mainset.h"
#include "model.h"
#include "patch.h"
#include "paths.h"
#include "prov.h"
#include "seed.h"
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

static int file_exists(const char *p)
{
    struct stat sb;
    return stat(p, &sb) == 0;
}

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

/* The arguments every unit entry point shares (exp_main.h). */
typedef exp_main_run_args unit_args;

static cs_status unit_check(const char *cmd, const unit_args *a, int need_weights)
{
    if (need_weights && !a->weights) return cs_err(CS_EUSAGE, "%s: --weights is required", cmd);
    if (!a->seed) return cs_err(CS_EUSAGE, "%s: --seed is required", cmd);
    if (!a->arm || (strcmp(a->arm, "joint") && strcmp(a->arm, "indep")))
        return cs_err(CS_EUSAGE, "%s: --arm must be joint or indep", cmd);
    if (!a->out) return cs_err(CS_EUSAGE, "%s: --out is required", cmd);
    if (!a->scale || (strcmp(a->scale, "full") && strcmp(a->scale, "smoke")))
        return cs_err(CS_EUSAGE, "%s: --scale must be full or smoke", cmd);
    if (a->volume && strcmp(a->volume, EVALVOL_SMALL) && strcmp(a->volume, EVALVOL_LARGE))
        return cs_err(CS_EUSAGE, "%s: --volume must be " EVALVOL_SMALL " or " EVALVOL_LARGE ", not '%s'", cmd,
                      a->volume);
    model_reading r = MODEL_PAIR;
    if (a->reading && model_reading_parse(a->reading, &r))
        return cs_err(CS_EUSAGE, "%s: --reading: %s", cmd, cs_errmsg());
    if (a->reading && a->pair >= 0 && (r == MODEL_PAIR) != (a->pair == 1))
        return cs_err(CS_EUSAGE, "%s: --pair %d contradicts --reading %s", cmd, a->pair, a->reading);
    return CS_OK;
}

/* The reading of a training unit: --reading, else --pair (0 plain, 1 pair), else pair. */
static model_reading unit_reading(const unit_args *a)
{
    model_reading r = MODEL_PAIR;
    if (a->reading) model_reading_parse(a->reading, &r);
    else if (a->pair == 0) r = MODEL_PLAIN;
    return r;
}

/* What a training unit leaves for its tables. */
typedef struct {
    model_cfg cfg;
    int npatches;
    long steps;
    double final_loss, scale, train_s, steps_per_s;
    char wsha[65];
} unit_trained;

/* The model a unit trains: the reference, its arm and reading, and the
 * width or depth the unit overrides. */
static model_cfg unit_cfg(const unit_args *a, model_reading reading)
{
    model_cfg cfg = model_cfg_reference(PATCH_NCOND);
    cfg.joint = !strcmp(a->arm, "joint");
    model_cfg_set_reading(&cfg, reading);
    if (a->width) { cfg.C = (int)a->width; cfg.F = 4 * (int)a->width; } /* the reference keeps MLP = 4 x width */
    if (a->blocks) cfg.L = (int)a->blocks;
    return cfg;
}

/* Build the teacher data, train (resuming from a->ckpt), write the weights;
 * *out owns the trainer, *data its patches. */
static cs_status unit_train(const unit_args *a, const mainset_design *ds, const mainrun_plan *pl,
                            model_reading reading, train **out, patch_set **data, unit_trained *u, double *worst)
{
    *out = NULL;
    memset(u, 0, sizeof *u);
    const unsigned seed = (unsigned)a->seed;
    patch_set *tr = NULL;
    cs_status st = mainset_train_build(ds, pl->train_stands, &tr, worst);
    *data = tr;
    if (st) return st;
    u->scale = patch_set_rms(tr);
    if ((st = patch_set_standardise(tr, u->scale))) return st;
    model_cfg cfg = unit_cfg(a, reading);
    train_opts o = train_opts_default();
    o.batch = pl->batch;
    o.lr = pl->lr;
    long spe = (tr->n + o.batch - 1) / o.batch; /* the step plan (see the top of this file) */
    o.steps = (long)pl->epochs * spe;
    o.seed_init = (unsigned long)seed_derive("main-model", 0, seed, "init");
    o.seed_batch = (unsigned long)seed_derive("main-model", 0, seed, "batch");
    o.seed_noise = (unsigned long)seed_derive("main-model", 0, seed, "noise");
    /* the checkpoint's directory must exist before the first atomic write */
    if (a->ckpt && (st = afile_mkdir_parents(a->ckpt))) return st;
    train *t = NULL;
    if ((st = train_alloc(&t, &cfg, tr, &o))) return st;
    *out = t;
    if (a->ckpt && file_exists(a->ckpt)) {
        if ((st = train_load(t, a->ckpt)))
            return cs_err(st, "%s (delete the checkpoint to restart this run)", cs_errmsg());
        fprintf(stderr, "main s%u %s %s: resuming at step %ld of %ld\n", seed, a->arm, model_reading_name(reading),
                t->step, o.steps);
    }
    const long every = o.steps / 50 > 0 ? o.steps / 50 : 1, from = t->step;
    const double t0 = prov_now();
    st = train_run(t, o.steps, a->ckpt, a->ckpt ? every : 0, stderr);
    u->train_s = prov_now() - t0;
    u->steps_per_s = u->train_s > 0 ? (double)(o.steps - from) / u->train_s : 0;
    u->cfg = cfg;
    u->npatches = tr->n;
    u->steps = o.steps;
    u->final_loss = t->loss;
    if (!st && a->weights && !(st = afile_mkdir_parents(a->weights)) && !(st = train_save_weights(t, a->weights)))
        st = prov_sha256_file(a->weights, u->wsha);
    return st;
}

/* `# model:` and `# training:` texts of a trained unit. */
static void unit_meta_model(char *buf, size_t n, const model_cfg *c)
{
    const model_reading r = model_cfg_reading(c);
    if (c->pair || r != MODEL_PLAIN)
        snprintf(buf, n, "T %d P %d width %d blocks %d heads %d mlp %d joint %d pair %d params %zu%s%s", c->T, c->P,
                 c->C, c->L, c->H, c->F, c->joint, c->pair, model_nparams(c), r == MODEL_PAIR ? "" : " reading ",
                 r == MODEL_PAIR ? "" : model_reading_name(r));
    else
        snprintf(buf, n, "T %d P %d width %d blocks %d heads %d mlp %d joint %d params %zu", c->T, c->P, c->C, c->L,
                 c->H, c->F, c->joint, model_nparams(c));
}

static void unit_meta_training(char *buf, size_t n, const unit_trained *u, const mainrun_plan *pl)
{
    snprintf(buf, n,
             "%d patches (%d stands per training spacing), batch %d, %d epochs = %ld steps, lr %g, final loss %.17g, "
             "deviation scale %.17g m",
             u->npatches, pl->train_stands, pl->batch, pl->epochs, u->steps, pl->lr, u->final_loss, u->scale);
}

static void unit_meta_eval(char *buf, size_t n, const mainrun_plan *pl, const model_cfg *c)
{
    if (mainrun_volume_small(pl))
        snprintf(buf, n,
                 "%d teacher stands per spacing, up to %d generated patches, %d Euler steps; probes: shuffled "
                 "(preregistered gate)%s",
                 pl->eval_stands, pl->gen_patches, pl->euler,
                 c->pair ? ", rotated by (1 + g mod 7) x 45 deg about the focal stem (added after the first verdict)"
                         : "");
    else
        snprintf(buf, n,
                 "volume %s: %d teacher stands per spacing, up to %d generated patches, %d Euler steps; probes at the "
                 "unseen spacings only: "
                 "shuffled (preregistered gate), rotated by (1 + g mod 7) x 45 deg about the focal stem (added after "
                 "the first verdict)",
                 pl->volume, pl->eval_stands, pl->gen_patches, pl->euler);
}

/* Evaluate m, write the samples (if asked) and the run table with meta[0..nmeta)
 * followed by the eval, estimator and samples/weights lines. */
static cs_status unit_evaluate_write(const unit_args *a, prov *pv, model *m, int Bmax, const mainset_design *ds,
                                     const mainrun_plan *pl, double scale, const char *(*meta)[2], int nmeta,
                                     const char *wsha, double *worst)
{
    const unsigned seed = (unsigned)a->seed;
    mainrun_row rows[MAINRUN_MAXROWS];
    size_t nrows = 0;
    double maxdiff = 0;
    char sbuf[256], ssha[65] = "", ev[512], ec[160], sl[160], wl[200];
    cs_status st = mainrun_evaluate(m, Bmax, ds, pl, scale, seed, a->arm, rows, &nrows, worst, &maxdiff);
    snprintf(pv->seeds, sizeof pv->seeds, "%s", mainrun_seeds_text(sbuf, sizeof sbuf, seed));
    pv->worst_overlap_m = *worst;
    if (!st && a->samples && !(st = afile_mkdir_parents(a->samples)) &&
        !(st = mainrun_samples_write(a->samples, pv, seed, a->arm, rows, nrows)))
        st = prov_sha256_file(a->samples, ssha);
    unit_meta_eval(ev, sizeof ev, pl, &m->cfg);
    snprintf(ec, sizeof ec, "max |batched - est_clearance| = %.3g m (tolerance %.3g m)", maxdiff, ds->tol);
    meta[nmeta][0] = "eval"; meta[nmeta++][1] = ev;
    meta[nmeta][0] = "estimator_check"; meta[nmeta++][1] = ec;
    if (a->samples) {
        snprintf(sl, sizeof sl, "%s sha256 %s", base_name(a->samples), ssha);
        meta[nmeta][0] = "samples";
        meta[nmeta++][1] = sl;
    }
    if (a->weights) {
        snprintf(wl, sizeof wl, "%s sha256 %s (weights format 1, README)", base_name(a->weights), wsha);
        meta[nmeta][0] = "weights";
        meta[nmeta++][1] = wl;
    }
    if (!st && !(st = afile_mkdir_parents(a->out)))
        st = mainrun_table_write(a->out, pv, seed, a->arm, (const char *const(*)[2])meta, nmeta, rows, nrows);
    mainrun_rows_free(rows, nrows);
    return st;
}

/* Plan for a unit: scale, volume, exploration overrides. */
static cs_status unit_plan(const unit_args *a, mainset_design *ds, mainrun_plan *pl)
{
    cs_status st = mainset_design_get(ds);
    if (!st) st = mainrun_plan_get(a->scale, pl);
    if (!st && a->volume) st = mainrun_plan_volume(pl, a->volume);
    if (!st && a->epochs) pl->epochs = (int)a->epochs;
    if (!st && a->train_stands) pl->train_stands = (int)a->train_stands;
    if (!st && a->lr > 0) pl->lr = a->lr;
    return st;
}

cs_status exp_main_run(const exp_main_run_args *ap)
{
    const unit_args a = *ap;
    cs_status st0 = unit_check("main-run", &a, 0);
    if (st0) return st0;
    prov pv;
    prov_begin(&pv, "main", a.argc, a.argv);
    mainset_design ds;
    mainrun_plan pl;
    cs_status st = unit_plan(&a, &ds, &pl);
    if (st) return st;
    double worst = 0.0;
    train *t = NULL;
    patch_set *tr = NULL;
    unit_trained u;
    st = unit_train(&a, &ds, &pl, unit_reading(&a), &t, &tr, &u, &worst);
    if (!st) {
        char mm[200], tm[400];
        unit_meta_model(mm, sizeof mm, &u.cfg);
        unit_meta_training(tm, sizeof tm, &u, &pl);
        char tt[200];
        snprintf(tt, sizeof tt,
                 "train_s %.3f steps_per_s %.4g (this invocation; a resumed run counts its last part only)", u.train_s,
                 u.steps_per_s);
        const char *meta[10][2] = {{"scale", pl.scale}, {"model", mm}, {"training", tm}, {"train_time", tt}};
        st = unit_evaluate_write(&a, &pv, t->m, t->B, &ds, &pl, u.scale, meta, 4, u.wsha, &worst);
    }
    train_free(t);
    patch_set_free(tr);
    return st;
}

/* Train only: the weights and a one-row training table (what the readings
 * table reads: parameters, steps, final loss, training time, steps/s). */
cs_status exp_main_train(const exp_main_run_args *ap)
{
    const unit_args a = *ap;
    cs_status st0 = unit_check("main-train", &a, 1);
    if (st0) return st0;
    prov pv;
    prov_begin(&pv, "main", a.argc, a.argv);
    mainset_design ds;
    mainrun_plan pl;
    cs_status st = unit_plan(&a, &ds, &pl);
    if (st) return st;
    double worst = 0.0;
    train *t = NULL;
    patch_set *tr = NULL;
    unit_trained u;
    const model_reading reading = unit_reading(&a);
    st = unit_train(&a, &ds, &pl, reading, &t, &tr, &u, &worst);
    tsv_writer *w = NULL;
    char sbuf[256];
    snprintf(pv.seeds, sizeof pv.seeds, "%s", mainrun_seeds_text(sbuf, sizeof sbuf, (unsigned)a.seed));
    pv.worst_overlap_m = worst;
    if (!st && !(st = afile_mkdir_parents(a.out))) st = tsv_writer_open(&w, a.out);
    if (!st && (st = prov_write(w, &pv))) { tsv_writer_abort(w); w = NULL; }
    if (!st) {
        char mm[200], tm[400];
        unit_meta_model(mm, sizeof mm, &u.cfg);
        unit_meta_training(tm, sizeof tm, &u, &pl);
        tsv_writer_meta(w, "scale", "%s", pl.scale);
        tsv_writer_meta(w, "model", "%s", mm);
        tsv_writer_meta(w, "training", "%s", tm);
        tsv_writer_meta(w, "step_plan",
                        "%d epochs x ceil(%d / %d) = %ld steps; an epoch of the batch order holds %d whole batches, so "
                        "%.17g passes over the data",
                        pl.epochs, u.npatches, pl.batch, u.steps, u.npatches / pl.batch,
                        (double)u.steps / (u.npatches / pl.batch));
        tsv_writer_meta(w, "weights", "%s sha256 %s (weights format 1, README)", base_name(a.weights), u.wsha);
        tsv_writer_meta(
            w, "train_s",
            "training wall time of this invocation (a resumed run counts its last part only); steps_per_s likewise");
        tsv_writer_columns(w, "seed\tarm\treading\tparams\tsteps\tfinal_loss\ttrain_s\tsteps_per_s");
        tsv_writer_long(w, a.seed); tsv_writer_str(w, a.arm); tsv_writer_str(w, model_reading_name(reading));
        tsv_writer_long(w, (long)model_nparams(&u.cfg)); tsv_writer_long(w, u.steps); tsv_writer_dbl(w, u.final_loss);
        tsv_writer_dbl(w, u.train_s); tsv_writer_dbl(w, u.steps_per_s);
        tsv_writer_endrow(w);
        st = tsv_writer_commit(w);
    }
    train_free(t);
    patch_set_free(tr);
    return st;
}

/* Copy the training record of a unit (its training or run table): model and
 * training lines, and the teacher, commit and date it was trained under. */
static cs_status trained_meta(const char *path, const char *(*meta)[2], int *nmeta, char (*buf)[512])
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    static const char *keys[][2] = {{"model", "model"},
                                    {"training", "training"},
                                    {"teacher_sha256", "trained_teacher_sha256"},
                                    {"git_commit", "trained_git_commit"},
                                    {"date", "trained_date"},
                                    {"wall_s", "trained_wall_s"}};
    for (size_t k = 0; k < sizeof keys / sizeof *keys && !st; k++) {
        /* a re-evaluation's table carries the training run's record as trained_*:
         * that one, never the re-evaluation's own time, commit or date */
        const char *v = strncmp(keys[k][1], "trained_", 8) ? NULL : tsv_meta(t, keys[k][1]);
        if (!v) v = tsv_meta(t, keys[k][0]);
        if (!v) {
            st = cs_err(CS_EINPUT, "%s: provenance line '# %s:' missing (need a training or run table)", path,
                        keys[k][0]);
            break;
        }
        snprintf(buf[*nmeta], 512, "%s", v);
        meta[*nmeta][0] = keys[k][1];
        meta[*nmeta][1] = buf[*nmeta];
        (*nmeta)++;
    }
    tsv_free(t);
    char hex[65];
    if (!st) st = prov_sha256_file(path, hex);
    if (!st) {
        snprintf(buf[*nmeta], 512,
                 "sha256 %s of the table the unit's training run wrote (%s; git history at trained_git_commit)", hex,
                 base_name(path));
        meta[*nmeta][0] = "training_record";
        meta[*nmeta][1] = buf[*nmeta];
        (*nmeta)++;
    }
    return st;
}

/* Load weights for a unit: the arm must match. */
static cs_status unit_load(const unit_args *a, const mainrun_plan *pl, model **m, double *scale)
{
    cs_status st = train_load_model(a->weights, m, pl->batch, scale);
    if (!st && (*m)->cfg.joint != !strcmp(a->arm, "joint"))
        st = cs_err(CS_EINPUT, "%s: weights of the %s arm, not %s", a->weights, (*m)->cfg.joint ? "joint" : "indep",
                    a->arm);
    model_reading r;
    if (!st && a->reading && !model_reading_parse(a->reading, &r) && model_cfg_reading(&(*m)->cfg) != r)
        st = cs_err(CS_EINPUT, "%s: weights of the %s reading, not %s", a->weights,
                    model_reading_name(model_cfg_reading(&(*m)->cfg)), a->reading);
    return st;
}

cs_status exp_main_run_cost(const exp_main_run_args *ap, exp_main_cost *c)
{
    const unit_args a = *ap;
    memset(c, 0, sizeof *c);
    cs_status st = unit_check("main-run", &a, 0);
    mainset_design ds;
    mainrun_plan pl;
    if (!st) st = unit_plan(&a, &ds, &pl);
    if (st) return st;
    const model_cfg cfg = unit_cfg(&a, unit_reading(&a));
    const long npatch = mainrun_train_patches(&ds, &pl);
    c->train_flops = (double)pl.epochs * ((npatch + pl.batch - 1) / pl.batch) * model_train_flops(&cfg, pl.batch);
    c->eval_flops = mainrun_eval_flops(&cfg, pl.batch, &ds, &pl);
    return speed_model_gflops(&cfg, pl.batch, 3, &c->train_gflops, &c->sample_gflops);
}

cs_status exp_main_redraw_cost(const exp_main_run_args *ap, double *flops, double *gflops)
{
    unit_args a = *ap;
    if (!a.out) a.out = "-"; /* nothing is written */
    cs_status st = unit_check("main-redraw", &a, 1);
    mainset_design ds;
    mainrun_plan pl;
    model *m = NULL;
    double scl = 0;
    if (!st) st = unit_plan(&a, &ds, &pl);
    if (!st) st = unit_load(&a, &pl, &m, &scl);
    if (!st) *flops = mainrun_eval_flops(&m->cfg, pl.batch, &ds, &pl);
    if (!st) st = speed_sample_gflops(m, pl.batch, 4, gflops);
    model_free(m);
    return st;
}

/* Evaluate frozen weights without training (design.md §9: frozen models are
 * re-evaluated from their weights): the run table and samples of main-run. */
cs_status exp_main_eval(const exp_main_run_args *ap)
{
    const unit_args a = *ap;
    cs_status st0 = unit_check("main-eval", &a, 1);
    if (st0) return st0;
    if (!a.trained) return cs_err(CS_EUSAGE, "main-eval: --trained is required");
    prov pv;
    prov_begin(&pv, "main", a.argc, a.argv);
    mainset_design ds;
    mainrun_plan pl;
    model *m = NULL;
    double scl = 0, worst = 0;
    const char *meta[16][2] = {{"scale", NULL}};
    char buf[10][512];
    int nmeta = 1;
    cs_status st = unit_plan(&a, &ds, &pl);
    meta[0][1] = pl.scale;
    if (!st) st = trained_meta(a.trained, meta, &nmeta, buf);
    if (!st) st = unit_load(&a, &pl, &m, &scl);
    char wsha[65] = "";
    if (!st) st = prov_sha256_file(a.weights, wsha);
    if (!st) st = unit_evaluate_write(&a, &pv, m, pl.batch, &ds, &pl, scl, meta, nmeta, wsha, &worst);
    model_free(m);
    return st;
}

/* Redraw the samples of one unit from its frozen weights alone (design.md §9
 * verify-deep): the same evaluation sets, seeds and sampler as main-run. */
cs_status exp_main_redraw(const exp_main_run_args *ap)
{
    const unit_args a = *ap;
    cs_status st0 = unit_check("main-redraw", &a, 1);
    if (st0) return st0;
    prov pv;
    prov_begin(&pv, "main", a.argc, a.argv);
    mainset_design ds;
    mainrun_plan pl;
    model *m = NULL;
    double scl = 0, worst = 0, maxdiff = 0;
    cs_status st = unit_plan(&a, &ds, &pl);
    /* the patches are drawn batch after batch from one stream: the first k are those of the whole */
    if (!st && a.only_patches > 0 && a.only_patches < pl.gen_patches) pl.gen_patches = (int)a.only_patches;
    if (!st) st = unit_load(&a, &pl, &m, &scl);
    mainrun_row rows[MAINRUN_MAXROWS];
    size_t nrows = 0;
    char sbuf[256];
    const unsigned seed = (unsigned)a.seed;
    int probe = -1;
    for (int p = 0; a.only_probe && p < MAINSET_NPROBE; p++)
        if (!strcmp(a.only_probe, mainset_probe_name((mainset_probe)p))) probe = p;
    if (!st && a.only_probe && probe < 0)
        st = cs_err(CS_EUSAGE, "main-redraw: --probe %s: not a probe (generated, shuffled, rotated)", a.only_probe);
    if (!st)
        st = mainrun_evaluate_slice(m, pl.batch, &ds, &pl, scl, seed, a.arm, a.only_spacing > 0 ? a.only_spacing : NAN,
                                    probe, rows, &nrows, &worst, &maxdiff);
    if (!st && !nrows)
        st = cs_err(CS_EUSAGE, "main-redraw: --spacing %g: not an evaluation spacing of the plan", a.only_spacing);
    snprintf(pv.seeds, sizeof pv.seeds, "%s", mainrun_seeds_text(sbuf, sizeof sbuf, seed));
    pv.worst_overlap_m = worst;
    if (!st) st = afile_mkdir_parents(a.out);
    if (!st) st = mainrun_samples_write(a.out, &pv, seed, a.arm, rows, nrows);
    mainrun_rows_free(rows, nrows);
    model_free(m);
    return st;
}

