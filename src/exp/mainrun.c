/* mainrun: one E3/E4 unit's evaluation and tables (see mainrun.h). */
#include "mainrun.h"
#include "speed.h"
#include "estimator.h"
#include "gate.h"
#include "paths.h"
#include "tsv.h"
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>

cs_status mainrun_plan_get(const char *scale, mainrun_plan *p)
{
    double epochs, euler;
    cs_status st;
    if ((st = gate_read_value(PATHS_GATE("main"), "epochs", 0, &epochs))) return st;
    if ((st = gate_read_value(PATHS_GATE("main"), "euler_steps", 0, &euler))) return st;
    memset(p, 0, sizeof *p);
    p->euler = (int)euler;
    p->batch = 64;
    p->lr = 2e-3;
    p->volume = EVALVOL_SMALL;
    if (!strcmp(scale, "full")) {
        p->scale = "full";
        p->train_stands = MAINRUN_TRAIN_STANDS; /* x 4 spacings x ~64 interior stems */
        p->eval_stands = EVALVOL_SMALL_EVAL_STANDS; /* ~1024 teacher clearances per eval spacing */
        p->gen_patches = EVALVOL_SMALL_GEN_PATCHES;
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

cs_status mainrun_plan_volume(mainrun_plan *p, const char *volume)
{
    const int full = !strcmp(p->scale, "full");
    if (!strcmp(volume, EVALVOL_SMALL)) {
        p->volume = EVALVOL_SMALL;
        p->eval_stands = full ? EVALVOL_SMALL_EVAL_STANDS : 2;
        p->gen_patches = full ? EVALVOL_SMALL_GEN_PATCHES : 32;
    } else if (!strcmp(volume, EVALVOL_LARGE)) {
        p->volume = EVALVOL_LARGE;
        p->eval_stands = full ? EVALVOL_LARGE_EVAL_STANDS : 4;
        p->gen_patches = full ? EVALVOL_LARGE_GEN_PATCHES : 64;
    } else return cs_err(CS_EUSAGE, "unknown evaluation volume '%s' (" EVALVOL_SMALL " or " EVALVOL_LARGE ")", volume);
    return CS_OK;
}

int mainrun_volume_small(const mainrun_plan *p) { return !strcmp(p->volume, EVALVOL_SMALL); }

void mainrun_rows_free(mainrun_row *rows, size_t n)
{
    for (size_t i = 0; i < n; i++) { free(rows[i].gen); free(rows[i].teach); }
}

int mainrun_nprobe(const mainrun_plan *pl, const model_cfg *cfg, int unseen)
{
    if (mainrun_volume_small(pl)) return cfg->pair ? MAINSET_NPROBE : cfg->joint ? 2 : 1;
    return unseen ? MAINSET_NPROBE : 1;
}

long mainrun_train_patches(const mainset_design *ds, const mainrun_plan *pl)
{
    return 64L * pl->train_stands * (long)ds->ntrain;
}

double mainrun_eval_flops(const model_cfg *cfg, int Bmax, const mainset_design *ds, const mainrun_plan *pl)
{
    const int full = pl->gen_patches / Bmax, rest = pl->gen_patches % Bmax;
    const double per = full * speed_forward_flops(cfg, Bmax) + (rest ? speed_forward_flops(cfg, rest) : 0);
    double f = 0;
    for (size_t si = 0; si < ds->nunseen + ds->nextrap; si++) {
        int unseen;
        mainset_eval_spacing(ds, si, &unseen);
        f += mainrun_nprobe(pl, cfg, unseen) * (double)pl->euler * per;
    }
    return f;
}

cs_status mainrun_evaluate(model *m, int Bmax, const mainset_design *ds, const mainrun_plan *pl, double scale,
                           unsigned seed, const char *arm, mainrun_row *rows, size_t *nrows,
                           double *worst, double *maxdiff)
{
    return mainrun_evaluate_slice(m, Bmax, ds, pl, scale, seed, arm, NAN, -1, rows, nrows, worst, maxdiff);
}

cs_status mainrun_evaluate_slice(model *m, int Bmax, const mainset_design *ds, const mainrun_plan *pl, double scale,
                                 unsigned seed, const char *arm, double only_d, int only_probe, mainrun_row *rows,
                                 size_t *nrows, double *worst, double *maxdiff)
{
    cs_status st = CS_OK;
    *nrows = 0;
    for (size_t si = 0; si < ds->nunseen + ds->nextrap && !st; si++) {
        int unseen;
        double d = mainset_eval_spacing(ds, si, &unseen);
        if (!isnan(only_d) && fabs(d - only_d) > 1e-9) continue;
        mainset_eval e;
        st = mainset_eval_build(ds, pl->eval_stands, d, scale, &e, worst, maxdiff);
        const int nprobe = mainrun_nprobe(pl, &m->cfg, unseen);
        /* each (spacing, probe) draws from its own stream: a slice equals those rows of the whole */
        for (int probe = 0; probe < nprobe && !st; probe++) {
            if (only_probe >= 0 && probe != only_probe) continue;
            const int first = *nrows == 0 || rows[*nrows - 1].d != d;
            mainrun_row *r = &rows[(*nrows)++];
            memset(r, 0, sizeof *r);
            r->d = d; r->unseen = unseen; r->probe = (mainset_probe)probe; r->nt = e.ps->n;
            r->gen = malloc((size_t)pl->gen_patches * sizeof *r->gen);
            if (first) r->teach = malloc((size_t)e.ps->n * sizeof *r->teach);
            if (!r->gen || (first && !r->teach)) { st = cs_err(CS_ENOMEM, "out of memory"); break; }
            if (first) memcpy(r->teach, e.teach, (size_t)e.ps->n * sizeof *r->teach);
            st = mainset_generate(m, Bmax, &e, pl->gen_patches, pl->euler, seed, r->probe, r->gen, &r->ng);
            if (!st) st = est_w1(r->gen, (size_t)r->ng, e.teach, (size_t)e.ps->n, &r->w1);
            if (!st)
                fprintf(stderr, "main s%u %s: d = %.1f %s W1 = %.4f m\n", seed, arm, d, mainset_probe_name(r->probe),
                        r->w1);
        }
        mainset_eval_free(&e);
    }
    return st;
}

cs_status mainrun_samples_write(const char *path, prov *pv, unsigned seed, const char *arm,
                                const mainrun_row *rows, size_t n)
{
    tsv_writer *w;
    cs_status st = tsv_writer_open(&w, path);
    if (st) return st;
    if ((st = prov_write(w, pv))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(
        w, "what",
        "focal nearest-neighbour clearances (m) behind every W1 of run_s%02u_%s.tsv: W1(spacing, probe) = "
        "est_w1(generated values of that spacing and probe, teacher values of that spacing), values in drawing order",
        seed, arm);
    tsv_writer_columns(w, "spacing\tsplit\tprobe\twhich\tvalue");
    for (size_t i = 0; i < n; i++) {
        const mainrun_row *r = &rows[i];
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

cs_status mainrun_table_write(const char *path, prov *pv, unsigned seed, const char *arm,
                              const char *const (*meta)[2], int nmeta, const mainrun_row *rows, size_t n)
{
    tsv_writer *w = NULL;
    cs_status st = tsv_writer_open(&w, path);
    if (!st) st = prov_write(w, pv);
    if (st) { if (w) tsv_writer_abort(w); return st; }
    for (int k = 0; k < nmeta; k++) tsv_writer_meta(w, meta[k][0], "%s", meta[k][1]);
    tsv_writer_columns(w, "seed\tarm\tspacing\tsplit\tprobe\tw1\tn_gen\tn_teacher");
    for (size_t i = 0; i < n; i++) {
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
    return tsv_writer_commit(w);
}

const char *mainrun_seeds_text(char *buf, size_t n, unsigned seed)
{
    snprintf(buf, n,
             "stands seed_derive(main-train|main-eval, d, k, stems|crowns); model seed_derive(main-model, 0, %u, "
             "init|batch|noise); "
             "sampling seed_derive(main-model[-shuffled|-rotated], d, %u, sample), permutation seed_derive(main-model, "
             "d, %u, shuffle)",
             seed, seed, seed);
    return buf;
}
