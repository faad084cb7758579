/* gensens: claims of the generator sensitivity (design.md §8.2): the paper
 * reading trained under one unstated training choice at a time (width,
 * blocks, training stands, epochs, peak learning rate), 4 seeds x 2 arms at
 * the paper reading's evaluation volume. The errors, shuffle and rotation
 * ratios and coupled seeds of a choice come from claim_main.c's functions on
 * its unit set; here are the two numbers that need the paper reading's
 * baselines: an arm's error over the direction-blind error (the joint arm's is
 * the main gate's second precondition, the independent arm's says how much
 * the model learned of a crown from its own tree). Every choice is evaluated
 * on the paper reading's evaluation stands, so its direction-blind level is
 * that reading's: <root>/paper-reading/main/baselines.tsv beside the choice's
 * <root>/generator-sensitivity/ (frozen/ in the registry); the same functions
 * give a reading's own arms over its own baselines. Descriptive: never
 * gated. Pending, naming the missing units, until the arm a claim reads has
 * every seed frozen. */
#include "claims.h"
#include "mainruns.h"
#include "stats.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Median over seeds of arm a's error (0 joint, 1 indep) over the blind level. */
static cs_status over_blind(const claim_row *row, claim_result *res, int a)
{
    char dir[300];
    if (!mainruns_unit_set(row->source, dir, sizeof dir))
        return cs_err(CS_EINPUT, "%s: the source must be a unit set <dir>/run_s*_*.tsv", row->source);
    static mainruns m;
    int want;
    cs_status st = claim_param_seeds(row, &want);
    if (!st) st = mainruns_load(dir, want, &m);
    if (st) return st;
    /* a descriptive row reads its arm once that arm is whole (design.md §8.2) */
    const int arm_only = m.nmissing && !strcmp(row->kind, "probe") && m.has[a][0] == m.want;
    if (m.nmissing && !arm_only) {
        mainruns_pending_text(&m, dir, res->why, sizeof res->why);
        res->status = VERDICT_PENDING;
        return CS_OK;
    }
    char set[400], base[400];
    double blind, med;
    snprintf(set, sizeof set, "%.300s/run_s*_*.tsv", dir);
    if ((st = claim_main_baseline_mean(set, "direction_blind_w1", "unseen", 0, &blind, base, sizeof base))) return st;
    if ((st = stats_median(m.err[a][0], (size_t)m.want, &med))) return st;
    snprintf(res->where, sizeof res->where, "%.200s/run_s*_*.tsv (%d seeds, %s arm) over %.200s", dir, m.want,
             a ? "indep" : "joint", base);
    if (arm_only) {
        size_t l = strlen(res->where);
        snprintf(res->where + l, sizeof res->where - l, "; that arm whole, the other still running");
    }
    claim_set_value(row, res, med / blind);
    /* a choice at the gate's seeds is judged by the direction-blind
     * precondition on this ratio itself (a variant row) */
    if (!a && strcmp(row->gate, "-")) claim_judge(row, res, GATE_LE, med / blind);
    return CS_OK;
}

cs_status claim_gensens_joint_blind(const claim_row *row, claim_result *res) { return over_blind(row, res, 0); }
cs_status claim_gensens_indep_blind(const claim_row *row, claim_result *res) { return over_blind(row, res, 1); }
