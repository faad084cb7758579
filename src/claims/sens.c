/* sens: the E0 sensitivity table; see sens.h. */
#include "sens.h"
#include "afile.h"
#include "prov.h"
#include "tsv.h"
#include "unstated.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The cheap teacher numbers (design.md §7 E0 sensitivity): E1 ablation on
 * the figure stand and hits, E2 at both operating points, E5, E6, E8, and
 * the E3 reference levels from the teacher alone. Counts fixed by
 * construction (hero and point-cloud stems, spacings) are left out. */
static const char *const QUANT[] = {
    "MechCoupOff",
    "MechCoupOffKTwo",
    "MechCoupOffKThree",
    "MechAbrOff",
    "MechOn",
    "MechOnKTwo",
    "MechOnKThree",
    "MechCoverOn",
    "MechHits",
    "IrredRespLo",
    "IrredRespHi",
    "IrredRespShrink",
    "IrredMiss",
    "IrredSteps",
    "IrredTrainRespLo",
    "IrredTrainSteps",
    "IrredTrainShrink",
    "CalibDieback",
    "Elong",
    "AnisoLattice",
    "AnisoTrees",
    "JitterStar",
    "JitterAniso",
    "JitterElong",
    "HardcoreOvershoot",
    "PcCoupled",
    "PcUncoupled",
    "PcContacted",
    "PcOtherAContacted",
    "PcOtherBContacted",
    "MainIso",
    "MainNoise",
    "MainShufTeach",
    "MainRotTeach",
};
#define NQ (sizeof QUANT / sizeof QUANT[0])

size_t sens_units_per_quantity(void)
{
    size_t nc, n = 1;
    const unstated_choice *ch = unstated_list(&nc);
    for (size_t i = 0; i < nc; i++) n += (size_t)ch[i].nvalues;
    return n;
}
size_t sens_count(void) { return NQ * sens_units_per_quantity(); }

/* The reason a table of a unit could not be built (its unit.tsv says
 * "failed": the choice's stands cannot be built or leave the statistic
 * undefined, a finding), or 0 when it was. The figure statistics come with
 * the figure crowns (one step writes both). */
static int unit_failed(const char *dir, const char *folder, const char *rel, char *why, size_t n)
{
    char path[400];
    snprintf(path, sizeof path, "%.200s/%.60s/unit.tsv", dir, folder);
    tsv *t;
    if (tsv_read(path, &t)) { cs_errclear(); return 0; }
    int found = 0;
    for (size_t r = 0; r < tsv_nrows(t) && !found; r++) {
        const char *tab = tsv_str(t, r, "table"), *f = tsv_str(t, r, "folder"), *note = tsv_str(t, r, "note");
        if (!tab || !f || strcmp(f, "failed")) continue;
        int same =
            !strcmp(tab, rel) || (!strncmp(tab, "mechanism/figure_", 17) && !strncmp(rel, "mechanism/figure_", 17));
        if (same) { snprintf(why, n, "%s", note ? note : "failed"); found = 1; }
    }
    tsv_free(t);
    return found;
}

/* Quantity q in the unit of choice c at value x (c NULL: the centre run). */
static cs_status one(const claims *cl, const char *dir, const unstated_choice *c, double x, const char *q,
                     sens_row *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->quantity, sizeof out->quantity, "%s", q);
    snprintf(out->choice, sizeof out->choice, "%s", c ? c->name : UNSTATED_CENTRE);
    out->x = c ? x : NAN;
    const claim_row *reg = claims_find(cl, q);
    if (!reg) return cs_err(CS_EINPUT, "sensitivity: quantity %s has no row in the claim registry", q);
    claim_row row = *reg;
    snprintf(row.gate, sizeof row.gate, "-");
    const char *rel = strncmp(reg->source, "frozen/", 7) ? reg->source : reg->source + 7;
    /* the E3 reference levels are the teacher's alone, the same under every
     * generator reading (design.md §8): a unit keeps them at main/ */
    if (!strncmp(rel, "paper-reading/", 14)) rel += 14;
    char folder[64];
    if (c && unstated_touches(c, rel)) unstated_dirname(c, x, folder, sizeof folder);
    else snprintf(folder, sizeof folder, "%s", UNSTATED_CENTRE);
    snprintf(out->source, sizeof out->source, "%.60s/%.180s", folder, rel);
    snprintf(row.source, sizeof row.source, "%.60s/%.190s", dir, out->source);
    char *end;
    out->paper = strtod(reg->reference, &end);
    if (end == reg->reference) out->paper = NAN;
    char why[300];
    if (unit_failed(dir, folder, rel, why, sizeof why)) {
        /* not computable under this choice: a finding, reported with its reason */
        out->value = NAN;
        out->rel_diff = NAN;
        size_t l = strlen(out->source);
        snprintf(out->source + l, sizeof out->source - l, " (not computable: %.150s)", why);
        return CS_OK;
    }
    claim_fn fn = claims_lookup_fn(row.function);
    if (!fn) return cs_err(CS_EINPUT, "sensitivity: %s: computing function %s unknown", q, row.function);
    claim_result res;
    memset(&res, 0, sizeof res);
    res.value = NAN;
    cs_errclear();
    cs_status st = fn(&row, &res);
    if (!st && res.status != VERDICT_PASS) st = cs_err(CS_EINPUT, "sensitivity: %s in %s: %s", q, folder, res.why);
    if (st) return st;
    out->value = res.value;
    out->rel_diff = (isfinite(out->paper) && out->paper != 0.0) ? (out->value - out->paper) / fabs(out->paper) : NAN;
    return CS_OK;
}

cs_status sens_compute(const claims *c, const char *dir, sens_row *rows)
{
    size_t nc, per = sens_units_per_quantity();
    const unstated_choice *ch = unstated_list(&nc);
    for (size_t q = 0; q < NQ; q++) {
        sens_row *r = rows + q * per;
        cs_status st = one(c, dir, NULL, NAN, QUANT[q], r++);
        for (size_t i = 0; i < nc && !st; i++)
            for (int k = 0; k < ch[i].nvalues && !st; k++) st = one(c, dir, &ch[i], ch[i].values[k], QUANT[q], r++);
        if (st) return st;
    }
    return CS_OK;
}

#define COLS "quantity\tchoice\tx\tvalue\tpaper\trel_diff\tsource"

cs_status sens_write(const char *path, const char *dir, const sens_row *rows, size_t n)
{
    tsv_writer *w;
    cs_status st = tsv_writer_open(&w, path);
    if (st) return st;
    prov p;
    char *argv[] = {"sensitivity-summary", "--dir", (char *)dir, "--out", (char *)path};
    prov_begin(&p, "sensitivity", 5, argv);
    snprintf(p.seeds, sizeof p.seeds, "those of each unit's tables under %s/<unit>/", dir);
    p.worst_overlap_m = -1;
    if ((st = prov_write(w, &p))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(
        w, "what",
        "E0 sensitivity (design.md §7 E0): each quantity in the centre run (the design's choices) and with one "
        "unstated choice at each of its values, everything else pinned; recomputed from the units' tables by the "
        "registry's computing functions; paper = audit/claims.tsv reference; rel_diff = (value - paper) / |paper|; "
        "source relative to the sensitivity folder (a table the choice cannot change is the centre's)");
    size_t nc;
    const unstated_choice *ch = unstated_list(&nc);
    for (size_t i = 0; i < nc; i++)
    {
        char vals[96] = "";
        for (int k = 0; k < ch[i].nvalues; k++)
            snprintf(vals + strlen(vals), sizeof vals - strlen(vals), " %g", ch[i].values[k]);
        tsv_writer_meta(w, ch[i].name, "ours %g; values%s: %s", ch[i].ours, vals, ch[i].what);
    }
    tsv_writer_columns(w, COLS);
    for (size_t i = 0; i < n; i++) {
        tsv_writer_str(w, rows[i].quantity);
        tsv_writer_str(w, rows[i].choice);
        tsv_writer_dbl(w, rows[i].x);
        tsv_writer_dbl(w, rows[i].value);
        tsv_writer_dbl(w, rows[i].paper);
        tsv_writer_dbl(w, rows[i].rel_diff);
        tsv_writer_str(w, rows[i].source);
        tsv_writer_endrow(w);
    }
    return tsv_writer_commit(w);
}

static int same(double a, double b) { return a == b || (isnan(a) && isnan(b)); }

cs_status sens_check(const char *path, const sens_row *rows, size_t n)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    if (tsv_nrows(t) != n)
        st = cs_err(CS_EINPUT, "%s: %zu rows, the sensitivity units give %zu", path, tsv_nrows(t), n);
    static const char *col[4] = {"x", "value", "paper", "rel_diff"};
    for (size_t i = 0; i < n && !st; i++) {
        const char *q = tsv_str(t, i, "quantity"), *c = tsv_str(t, i, "choice");
        if (!q || !c || strcmp(q, rows[i].quantity) || strcmp(c, rows[i].choice)) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'quantity'/'choice': expected %s %s", path, tsv_line(t, i),
                        rows[i].quantity, rows[i].choice);
            break;
        }
        double want[4] = {rows[i].x, rows[i].value, rows[i].paper, rows[i].rel_diff};
        for (int k = 0; k < 4 && !st; k++) {
            double v;
            if ((st = tsv_double_nf(t, i, col[k], &v))) break;
            if (!same(v, want[k]))
                st = cs_err(CS_EINPUT, "%s:%d: field '%s': says %.17g but the unit tables give %.17g (%s, %s)", path,
                            tsv_line(t, i), col[k], v, want[k], rows[i].quantity, rows[i].choice);
        }
    }
    tsv_free(t);
    return st;
}

int sens_span(const sens_row *rows, size_t n, const char *q, const char *ch, double *lo, double *hi)
{
    int found = 0;
    *lo = INFINITY;
    *hi = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        if (strcmp(rows[i].quantity, q)) continue;
        if (strcmp(rows[i].choice, UNSTATED_CENTRE) && strcmp(rows[i].choice, ch)) continue;
        if (!isfinite(rows[i].value)) continue;
        if (rows[i].value < *lo) *lo = rows[i].value;
        if (rows[i].value > *hi) *hi = rows[i].value;
        found = 1;
    }
    return found;
}

/* A number for the table: 3 significant digits, counts as integers. */
static void cell(char *buf, size_t n, double v)
{
    if (!isfinite(v)) snprintf(buf, n, "--");
    else if (fabs(v) >= 100.0 || v == floor(v)) snprintf(buf, n, "%.0f", v);
    else snprintf(buf, n, "%.3g", v);
}

/* paper/sensitivity.tex: one row per quantity: the paper's value, the centre
 * run, and per choice the span [lowest, highest] over the centre and the
 * choice's values; a span that contains the paper's value in bold (not for
 * the categorical die-back rules). */
cs_status sens_write_tex(const char *path, const sens_row *rows, size_t n)
{
    afile a;
    cs_status st = afile_open(&a, path);
    if (st) return st;
    FILE *f = a.f;
    size_t nc, per = sens_units_per_quantity();
    const unstated_choice *ch = unstated_list(&nc);
    fprintf(f, "%% generated by `crownshy numbers` from frozen/sensitivity/ (src/claims/sens.c): never edit by hand.\n"
               "%% Per quantity: the reference paper's value, our centre run, and per unstated choice the span of its "
               "values.\n"
               "\\begin{tabular}{lrr");
    for (size_t i = 0; i < nc; i++) fprintf(f, "c");
    fprintf(f, "}\n\\toprule\nquantity & paper & ours");
    for (size_t i = 0; i < nc; i++) {
        char name[64];
        size_t o = 0;
        for (const char *p = ch[i].name; *p && o + 2 < sizeof name; p++) {
            if (*p == '_') name[o++] = '\\';
            name[o++] = *p;
        }
        name[o] = '\0';
        fprintf(f, " & \\texttt{%s}", name);
    }
    fprintf(f, "\\\\\n\\midrule\n");
    for (size_t q = 0; q < NQ && (q + 1) * per <= n; q++) {
        const sens_row *c0 = rows + q * per;
        char p[32], o[32];
        cell(p, sizeof p, c0->paper);
        cell(o, sizeof o, c0->value);
        fprintf(f, "\\texttt{%s} & $%s$ & $%s$", QUANT[q], p, o);
        for (size_t i = 0; i < nc; i++) {
            double lo, hi;
            char l[32], h[32];
            if (!sens_span(rows, n, QUANT[q], ch[i].name, &lo, &hi)) { fprintf(f, " & --"); continue; }
            cell(l, sizeof l, lo);
            cell(h, sizeof h, hi);
            /* a categorical choice (the die-back rules) has no value between its values */
            int reach = isfinite(c0->paper) && lo <= c0->paper && c0->paper <= hi && !ch[i].categorical;
            if (!strcmp(l, h)) fprintf(f, reach ? " & $\\mathbf{%s}$" : " & $%s$", l);
            else fprintf(f, reach ? " & $\\mathbf{[%s,\\,%s]}$" : " & $[%s,\\,%s]$", l, h);
        }
        fprintf(f, "\\\\\n");
    }
    fprintf(f, "\\bottomrule\n\\end{tabular}\n");
    return afile_commit(&a);
}
