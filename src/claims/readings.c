/* readings: the E0 readings table; see readings.h. */
#include "readings.h"
#include "fieldsim.h"
#include "afile.h"
#include "prov.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const readings_def READINGS[] = {
    {"cardinal-one-sided-60m", "one-sided-60m", 0, 0, "teacher-1 (one-sided die-back), layout 5m-on-60m, cardinal elongation, Mech* on the lattice"},
    {"cardinal-mutual-60m", "mutual-60m", 0, 0, "teacher-2 (mutual abrasion), layout 5m-on-60m, cardinal elongation, Mech* on the lattice"},
    {"mutual-60m", "mutual-60m", 1, 1, "teacher-2, layout 5m-on-60m, all-axis elongation, Mech* on the figure stand"},
    {"one-sided-36m", "one-sided-36m", 1, 1, "teacher-1 (one-sided die-back), layout 4m-on-36m, all-axis elongation, Mech* on the figure stand"},
    {"mutual-36m", "mutual-36m", 1, 1, "the adopted reading: teacher-2, layout 4m-on-36m, all-axis elongation, Mech* on the figure stand"},
    {"arc", "arc-36m", 1, 1, "mutual-36m with the contact arc s-1..s+1 dying back too (teacher-2-arc; measured, not adopted)"},
};
#define NREAD (sizeof READINGS / sizeof READINGS[0])

/* Quantities: registry macros (values by their computing functions). */
static const char *const QUANT[] = {
    "MechCoupOff", "MechCoupOffKTwo", "MechCoupOffKThree", "MechAbrOff", "MechOn", "MechOnKTwo", "MechOnKThree",
    "MechCoverOn", "MechHits", "CalibDieback", "Elong", "AnisoLattice", "JitterStar", "JitterAniso", "JitterElong",
    "HardcoreOvershoot", "PcCoupled", "PcUncoupled",
};
#define NQ (sizeof QUANT / sizeof QUANT[0])

const readings_def *readings_list(size_t *n) { *n = NREAD; return READINGS; }
size_t readings_count(void) { return NREAD * NQ; }

/* The cardinal elongation median of the coupled row of a
 * held-out summary, recomputed from its per-tree table (fieldsim). */
static cs_status elong_cardinal(const char *path, double *v)
{
    tsv *t;
    fs_trees tr;
    cs_status st = fs_load_checked(path, &t, &tr);
    if (st) return st;
    long r = tsv_find(t, "arm", "coupled");
    double level = 0;
    if (r < 0) st = cs_err(CS_EINPUT, "%s: field 'arm': no coupled row", path);
    if (!st) st = tsv_double(t, (size_t)r, "level", &level);
    fs_summary s;
    if (!st) st = fs_group(&tr, 1, level, &s);
    if (!st) *v = s.elong_card_median;
    fs_trees_free(&tr);
    tsv_free(t);
    return st;
}

static cs_status one(const claims *c, const char *dir, const readings_def *d, const char *q, readings_row *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->quantity, sizeof out->quantity, "%s", q);
    snprintf(out->reading, sizeof out->reading, "%s", d->name);
    const claim_row *reg = claims_find(c, q);
    if (!reg) return cs_err(CS_EINPUT, "readings: quantity %s has no row in the claim registry", q);
    claim_row row = *reg;
    snprintf(row.gate, sizeof row.gate, "-");
    const char *rel = strncmp(reg->source, "frozen/", 7) ? reg->source : reg->source + 7;
    /* a claim of the mechanism's figure stand reads the reading's figure stand, or its lattice ablation */
    if (!strcmp(rel, "mechanism/figure_stats.tsv"))
        snprintf(row.source, sizeof row.source, "%.120s/%s/mechanism/%s", dir, d->run,
                 d->figure_stand ? "figure_stats.tsv" : "ablation.tsv");
    else snprintf(row.source, sizeof row.source, "%.120s/%s/%.100s", dir, d->run, rel);
    char *end;
    out->paper = strtod(reg->reference, &end);
    if (end == reg->reference) out->paper = NAN;
    /* relative to the readings folder, so the table does not depend on where
     * the results were written (a local run and a cluster run agree) */
    snprintf(out->source, sizeof out->source, "%s", row.source + strlen(dir) + 1);
    cs_status st;
    /* an elongation claim of a reading without all-axis elongation: the cardinal median */
    const int elong = !strcmp(row.function, "claim_field_elong") ||
                      (!strcmp(row.function, "claim_jitter_heldout") && !strcmp(row.param.column, "elong_median"));
    if (!d->elong_all_axes && elong) {
        st = elong_cardinal(row.source, &out->value);
        size_t l = strlen(out->source);
        snprintf(out->source + l, sizeof out->source - l, " (elong_card)");
    } else {
        claim_fn fn = claims_lookup_fn(row.function);
        if (!fn) return cs_err(CS_EINPUT, "readings: %s: computing function %s unknown", q, row.function);
        claim_result res;
        memset(&res, 0, sizeof res);
        res.value = NAN;
        cs_errclear();
        st = fn(&row, &res);
        if (!st && res.status != VERDICT_PASS) st = cs_err(CS_EINPUT, "readings: %s under %s: %s", q, d->name, res.why);
        out->value = res.value;
    }
    if (st) return st;
    out->rel_diff = (isfinite(out->paper) && out->paper != 0.0) ? (out->value - out->paper) / fabs(out->paper) : NAN;
    return CS_OK;
}

cs_status readings_compute(const claims *c, const char *dir, readings_row *rows)
{
    for (size_t k = 0; k < NREAD; k++)
        for (size_t q = 0; q < NQ; q++) {
            cs_status st = one(c, dir, &READINGS[k], QUANT[q], &rows[q * NREAD + k]);
            if (st) return st;
        }
    return CS_OK;
}

#define COLS "quantity\treading\tvalue\tpaper\trel_diff\tsource"

cs_status readings_write(const char *path, const char *dir, const readings_row *rows, size_t n)
{
    tsv_writer *w;
    cs_status st = tsv_writer_open(&w, path);
    if (st) return st;
    prov p;
    char *argv[] = {"readings-summary", "--dir", (char *)dir, "--out", (char *)path};
    prov_begin(&p, "readings", 5, argv);
    snprintf(p.teacher_version, sizeof p.teacher_version, "per run");
    snprintf(p.seeds, sizeof p.seeds, "those of each run's tables under %s/<run>/", dir);
    p.worst_overlap_m = -1;
    if ((st = prov_write(w, &p))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "what",
                    "E0 readings (design.md §7 E0): each quantity under each reading, recomputed from the run tables "
                    "by the registry's computing functions; paper = audit/claims.tsv reference; rel_diff = (value - "
                    "paper) / |paper|; source relative to the readings folder");
    for (size_t k = 0; k < NREAD; k++)
        tsv_writer_meta(w, READINGS[k].name, "run %s, elongation %s, Mech* on %s: %s", READINGS[k].run,
                        READINGS[k].elong_all_axes ? "all axes" : "cardinal",
                        READINGS[k].figure_stand ? "the figure stand" : "the lattice", READINGS[k].what);
    tsv_writer_columns(w, COLS);
    for (size_t i = 0; i < n; i++) {
        tsv_writer_str(w, rows[i].quantity);
        tsv_writer_str(w, rows[i].reading);
        tsv_writer_dbl(w, rows[i].value);
        tsv_writer_dbl(w, rows[i].paper);
        tsv_writer_dbl(w, rows[i].rel_diff);
        tsv_writer_str(w, rows[i].source);
        tsv_writer_endrow(w);
    }
    return tsv_writer_commit(w);
}

static int same(double a, double b) { return a == b || (isnan(a) && isnan(b)); }

cs_status readings_check(const char *path, const readings_row *rows, size_t n)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    if (tsv_nrows(t) != n) st = cs_err(CS_EINPUT, "%s: %zu rows, the readings give %zu", path, tsv_nrows(t), n);
    static const char *col[3] = {"value", "paper", "rel_diff"};
    for (size_t i = 0; i < n && !st; i++) {
        const char *q = tsv_str(t, i, "quantity"), *r = tsv_str(t, i, "reading");
        if (!q || !r || strcmp(q, rows[i].quantity) || strcmp(r, rows[i].reading)) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'quantity'/'reading': expected %s %s", path, tsv_line(t, i),
                        rows[i].quantity, rows[i].reading);
            break;
        }
        double want[3] = {rows[i].value, rows[i].paper, rows[i].rel_diff};
        for (int c = 0; c < 3 && !st; c++) {
            double v;
            if ((st = tsv_double_nf(t, i, col[c], &v))) break;
            if (!same(v, want[c]))
                st = cs_err(CS_EINPUT, "%s:%d: field '%s': says %.17g but the run tables give %.17g (%s, %s)", path,
                            tsv_line(t, i), col[c], v, want[c], rows[i].quantity, rows[i].reading);
        }
    }
    tsv_free(t);
    return st;
}

void readings_within(const readings_row *rows, size_t n, const char *reading, size_t *m, size_t *in10, size_t *in25)
{
    *m = *in10 = *in25 = 0;
    for (size_t i = 0; i < n; i++) {
        if (strcmp(rows[i].reading, reading) || !isfinite(rows[i].rel_diff)) continue;
        (*m)++;
        *in10 += fabs(rows[i].rel_diff) <= 0.10;
        *in25 += fabs(rows[i].rel_diff) <= 0.25;
    }
}

/* paper/readings.tex: one row per quantity, one column per reading (value and
 * relative difference to the paper), the paper's value, and the within-10 %/
 * 25 % counts per reading. GENERATED (the audit skips it; numbers regenerates it). */
cs_status readings_write_tex(const char *path, const readings_row *rows, size_t n)
{
    afile a;
    cs_status st = afile_open(&a, path);
    if (st) return st;
    FILE *f = a.f;
    fprintf(f, "%% GENERATED by `crownshy numbers` from frozen/readings/ (src/claims/readings.c): never edit by hand.\n"
               "%% Each quantity under each reading (design.md \\S7 E0); in brackets the relative difference to the "
               "reference paper.\n"
               "\\begin{tabular}{l");
    for (size_t k = 0; k < NREAD; k++) fprintf(f, "r");
    fprintf(f, "r}\n\\toprule\nquantity");
    for (size_t k = 0; k < NREAD; k++) fprintf(f, " & \\texttt{%s}", READINGS[k].name);
    fprintf(f, " & paper\\\\\n\\midrule\n");
    for (size_t q = 0; q < NQ; q++) {
        fprintf(f, "\\texttt{%s}", QUANT[q]);
        double paper = NAN;
        for (size_t k = 0; k < NREAD; k++) {
            size_t i = q * NREAD + k;
            if (i >= n) break;
            paper = rows[i].paper;
            double pct = 100.0 * rows[i].rel_diff;
            if (fabs(pct) < 0.5) pct = 0.0; /* no "-0 %" */
            if (isfinite(rows[i].rel_diff)) fprintf(f, " & %.3g {\\scriptsize(%+.0f\\,\\%%)}", rows[i].value, pct);
            else fprintf(f, " & %.3g", rows[i].value);
        }
        fprintf(f, " & %.4g\\\\\n", paper);
    }
    fprintf(f, "\\midrule\nwithin 10\\,\\%% / 25\\,\\%%");
    for (size_t k = 0; k < NREAD; k++) {
        size_t m, a10, a25;
        readings_within(rows, n, READINGS[k].name, &m, &a10, &a25);
        fprintf(f, " & %zu / %zu of %zu", a10, a25, m);
    }
    fprintf(f, " & \\\\\n\\bottomrule\n\\end{tabular}\n");
    return afile_commit(&a);
}
