/* claim_probe: claims of what a generator uses (design.md §8.4; reference
 * paper §5.1), from the probe tables of src/exp/genprobe.c (probes named in src/base/probekind.h). A reading's
 * claim reads one arm's unit set, source
 * "<root>/generator-probes/<reading>/probes_s*_<arm>.tsv" with seeds
 * 1..MAINRUNS_READING_SEEDS: per seed the mean W1 over the unseen spacings
 * under the probe and without it; the claim is the median over seeds of the
 * probed error over the median of the unprobed one (as MainGeomRatio), so 1
 * means the generator does not use what the probe takes away. Pending, naming
 * the missing seeds, until the set is whole. The teacher's claims read
 * teacher/probes.tsv: the teacher's own crowns under the probe (a perfect
 * generator), mean W1 over the unseen spacings. Descriptive, never gated. */
#include "claims.h"
#include "probekind.h"
#include "mainruns.h"
#include "stats.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* Mean over the table's rows of probe k (the unseen spacings), or an error. */
static cs_status probe_mean(const char *path, probekind k, double *out)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    double s = 0;
    int n = 0;
    for (size_t i = 0; i < tsv_nrows(t) && !st; i++) {
        const char *p = tsv_str(t, i, "probe");
        probekind q;
        if (!p || probekind_parse(p, &q)) { st = cs_err(CS_EINPUT, "%s:%d: field 'probe': missing or unknown", path, tsv_line(t, i)); break; }
        if (q != k) continue;
        double w;
        if ((st = tsv_double(t, i, "w1", &w))) break;
        s += w;
        n++;
    }
    tsv_free(t);
    if (!st && !n) st = cs_err(CS_EINPUT, "%s: no rows of the %s probe", path, probekind_name(k));
    if (!st) *out = s / n;
    return st;
}

/* The ratio claim of probe k over a reading's unit set. */
static cs_status reading_ratio(const claim_row *row, claim_result *res, probekind k)
{
    const char *star = strstr(row->source, "_s*_");
    if (!star) return cs_err(CS_EINPUT, "%s: the source must be a unit set <dir>/probes_s*_<arm>.tsv", row->source);
    const int want = MAINRUNS_READING_SEEDS;
    double pr[MAINRUNS_READING_SEEDS], un[MAINRUNS_READING_SEEDS];
    char missing[256] = "";
    int nmiss = 0;
    cs_status st = CS_OK;
    for (int s = 1; s <= want && !st; s++) {
        char p[400];
        snprintf(p, sizeof p, "%.*s_s%02d_%.100s", (int)(star - row->source), row->source, s, star + 4);
        if (access(p, F_OK) != 0) {
            snprintf(missing + strlen(missing), sizeof missing - strlen(missing), " s%02d", s);
            nmiss++;
            continue;
        }
        if (!(st = probe_mean(p, k, &pr[s - 1]))) st = probe_mean(p, PROBEKIND_NONE, &un[s - 1]);
    }
    if (st) return st;
    if (nmiss) {
        res->status = VERDICT_PENDING;
        snprintf(res->why, sizeof res->why, "%s: %d of %d seeds frozen; missing%s", row->source, want - nmiss, want, missing);
        return CS_OK;
    }
    double mp, mu;
    if ((st = stats_median(pr, (size_t)want, &mp)) || (st = stats_median(un, (size_t)want, &mu))) return st;
    snprintf(res->where, sizeof res->where, "%.300s (%d seeds; median %s error over median unprobed error)", row->source, want, probekind_name(k));
    claim_set_value(row, res, mp / mu);
    return CS_OK;
}

/* The teacher's own crowns under probe k: mean W1 over the unseen spacings. */
static cs_status teacher_level(const claim_row *row, claim_result *res, probekind k)
{
    double v;
    cs_status st = probe_mean(row->source, k, &v);
    if (st) return st;
    snprintf(res->where, sizeof res->where, "%.300s (%s, mean over the unseen spacings)", row->source, probekind_name(k));
    claim_set_value(row, res, v);
    return CS_OK;
}

cs_status claim_probe_self(const claim_row *row, claim_result *res) { return reading_ratio(row, res, PROBEKIND_SELF); }
cs_status claim_probe_rot15(const claim_row *row, claim_result *res) { return reading_ratio(row, res, PROBEKIND_ROT15); }
cs_status claim_probe_rot45(const claim_row *row, claim_result *res) { return reading_ratio(row, res, PROBEKIND_ROT45); }
cs_status claim_probe_rot90(const claim_row *row, claim_result *res) { return reading_ratio(row, res, PROBEKIND_ROT90); }
cs_status claim_probe_nnswap(const claim_row *row, claim_result *res) { return reading_ratio(row, res, PROBEKIND_NNSWAP); }
cs_status claim_probe_dejitter(const claim_row *row, claim_result *res) { return reading_ratio(row, res, PROBEKIND_DEJITTER); }
cs_status claim_probe_sizes(const claim_row *row, claim_result *res) { return reading_ratio(row, res, PROBEKIND_SIZES); }
cs_status claim_probe_teacher_rot15(const claim_row *row, claim_result *res) { return teacher_level(row, res, PROBEKIND_ROT15); }
cs_status claim_probe_teacher_rot45(const claim_row *row, claim_result *res) { return teacher_level(row, res, PROBEKIND_ROT45); }
cs_status claim_probe_teacher_rot90(const claim_row *row, claim_result *res) { return teacher_level(row, res, PROBEKIND_ROT90); }
cs_status claim_probe_teacher_nnswap(const claim_row *row, claim_result *res) { return teacher_level(row, res, PROBEKIND_NNSWAP); }
