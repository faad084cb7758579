/* claim_probe: claims of what a generator uses (design.md §8.4; reference
 * paper §5.1), from the probe tables of src/exp/genprobe.c (probes named in src/base/probekind.h). A reading's
 * claim reads one arm's unit set, source
 * "<root>/generator-probes/<reading>/probes_s*_<arm>.tsv" with seeds
 * 1..N (the row's seeds=N): per seed the mean W1 over the unseen spacings
 * under the probe and without it; the claim is the median over seeds of the
 * probed error over the median of the unprobed one (as MainGeomRatio), so 1
 * means the generator does not use what the probe takes away. Pending, naming
 * the missing seeds, until the set is whole. The teacher's claims read
 * teacher/probes.tsv: the teacher's own crowns under the probe (a perfect
 * generator), mean W1 over the unseen spacings. Descriptive, never gated. */
#include "claim_probe.h"
#include "claims.h"
#include "probekind.h"
#include "prov.h"
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
        if (!p || probekind_parse(p, &q)) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'probe': missing or unknown", path, tsv_line(t, i));
            break;
        }
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

/* The ratio of probe k over a reading's unit set of seeds 1..want. */
static cs_status ratio_over(const claim_row *row, claim_result *res, probekind k, int want)
{
    const char *star = strstr(row->source, "_s*_");
    if (!star) return cs_err(CS_EINPUT, "%s: the source must be a unit set <dir>/probes_s*_<arm>.tsv", row->source);
    if (want < 1 || want > MAINRUNS_MAXSEED)
        return cs_err(CS_EUSAGE, "%s: %d seeds (1..%d)", row->source, want, MAINRUNS_MAXSEED);
    double pr[MAINRUNS_MAXSEED], un[MAINRUNS_MAXSEED];
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
        snprintf(res->why, sizeof res->why, "%s: %d of %d seeds frozen; missing%s", row->source, want - nmiss, want,
                 missing);
        return CS_OK;
    }
    double mp, mu;
    if ((st = stats_median(pr, (size_t)want, &mp)) || (st = stats_median(un, (size_t)want, &mu))) return st;
    snprintf(res->where, sizeof res->where, "%.300s (%d seeds; median %s error over median unprobed error)",
             row->source, want, probekind_name(k));
    claim_set_value(row, res, mp / mu);
    return CS_OK;
}

/* The ratio claim of probe k over the row's seeds. */
static cs_status reading_ratio(const claim_row *row, claim_result *res, probekind k)
{
    int want;
    cs_status st = claim_param_seeds(row, &want);
    return st ? st : ratio_over(row, res, k, want);
}

/* The teacher's own crowns under probe k: mean W1 over the unseen spacings. */
static cs_status teacher_level(const claim_row *row, claim_result *res, probekind k)
{
    double v;
    cs_status st = probe_mean(row->source, k, &v);
    if (st) return st;
    snprintf(res->where, sizeof res->where, "%.300s (%s, mean over the unseen spacings)", row->source,
             probekind_name(k));
    claim_set_value(row, res, v);
    return CS_OK;
}

cs_status claim_probe_self(const claim_row *row, claim_result *res) { return reading_ratio(row, res, PROBEKIND_SELF); }
cs_status claim_probe_rot15(const claim_row *row, claim_result *res)
{
    return reading_ratio(row, res, PROBEKIND_ROT15);
}
cs_status claim_probe_rot45(const claim_row *row, claim_result *res)
{
    return reading_ratio(row, res, PROBEKIND_ROT45);
}
cs_status claim_probe_rot90(const claim_row *row, claim_result *res)
{
    return reading_ratio(row, res, PROBEKIND_ROT90);
}
cs_status claim_probe_nnswap(const claim_row *row, claim_result *res)
{
    return reading_ratio(row, res, PROBEKIND_NNSWAP);
}
cs_status claim_probe_dejitter(const claim_row *row, claim_result *res)
{
    return reading_ratio(row, res, PROBEKIND_DEJITTER);
}
cs_status claim_probe_sizes(const claim_row *row, claim_result *res)
{
    return reading_ratio(row, res, PROBEKIND_SIZES);
}
cs_status claim_probe_teacher_rot15(const claim_row *row, claim_result *res)
{
    return teacher_level(row, res, PROBEKIND_ROT15);
}
cs_status claim_probe_teacher_rot45(const claim_row *row, claim_result *res)
{
    return teacher_level(row, res, PROBEKIND_ROT45);
}
cs_status claim_probe_teacher_rot90(const claim_row *row, claim_result *res)
{
    return teacher_level(row, res, PROBEKIND_ROT90);
}
cs_status claim_probe_teacher_nnswap(const claim_row *row, claim_result *res)
{
    return teacher_level(row, res, PROBEKIND_NNSWAP);
}

/* ---- the summary table (generator-probes-summary) ---- */

static const char *const SUM_READINGS[] = {"paper", "paper-fourier", "plain", "pair"};

cs_status claim_probe_summary_write(const char *root, const char *out, int seeds, int argc, char **argv)
{
    tsv_writer *w;
    cs_status st = tsv_writer_open(&w, out);
    if (st) return st;
    prov pv;
    prov_begin(&pv, "generator-probes", argc, argv);
    snprintf(pv.seeds, sizeof pv.seeds, "those of each probe table under %.200s/generator-probes/", root);
    pv.worst_overlap_m = -1;
    if ((st = prov_write(w, &pv))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "what",
                    "per reading, arm and probe: the median over seeds 1-%d of the mean W1 over the unseen spacings "
                    "under the probe, over the same without it "
                    "(the Probe* claims, design.md §8.4); 1 = the reading does not use what the probe removes",
                    seeds);
    tsv_writer_columns(w, "reading\tarm\tprobe\tratio");
    for (size_t r = 0; r < sizeof SUM_READINGS / sizeof *SUM_READINGS && !st; r++)
        for (int a = 0; a < 2 && !st; a++)
            for (int k = PROBEKIND_SELF; k < PROBEKIND_N && !st; k++) {
                claim_row row;
                memset(&row, 0, sizeof row);
                snprintf(row.source, sizeof row.source, "%.150s/generator-probes/%s/probes_s*_%s.tsv", root,
                         SUM_READINGS[r], a ? "indep" : "joint");
                snprintf(row.format, sizeof row.format, "%%.17g");
                claim_result res;
                memset(&res, 0, sizeof res);
                res.status = VERDICT_PASS;
                if ((st = ratio_over(&row, &res, (probekind)k, seeds))) break;
                if (res.status != VERDICT_PASS) { st = cs_err(CS_EINPUT, "%s", res.why); break; }
                tsv_writer_str(w, SUM_READINGS[r]);
                tsv_writer_str(w, a ? "indep" : "joint");
                tsv_writer_str(w, probekind_name((probekind)k));
                tsv_writer_dbl(w, res.value);
                tsv_writer_endrow(w);
            }
    if (st) { tsv_writer_abort(w); return st; }
    return tsv_writer_commit(w);
}
