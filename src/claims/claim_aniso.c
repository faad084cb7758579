/* claim_aniso: computing functions for the E6 claims (reference paper §5.4;
 * design.md §7 E6). Each reads its frozen summary, checks it against the per-tree
 * table beside it (fs_load_checked), and recomputes with the library code the
 * experiment used (fs_group medians, stats_spearman, fs_jitter_star). */
#include "claims.h"
#include "fieldsim.h"
#include "stats.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Coupled summary row (first one) of a checked summary table. */
static cs_status coupled_row(const char *path, tsv **t, size_t *row)
{
    fs_trees tr;
    cs_status st = fs_load_checked(path, t, &tr);
    if (st) return st;
    fs_trees_free(&tr);
    long r = tsv_find(*t, "arm", "coupled");
    if (r < 0) { tsv_free(*t); *t = NULL; return cs_err(CS_EINPUT, "%s: field 'arm': no coupled row", path); }
    *row = (size_t)r;
    return CS_OK;
}

cs_status claim_aniso_lattice(const claim_row *row, claim_result *res)
{
    tsv *t;
    size_t r;
    cs_status st = coupled_row(row->source, &t, &r);
    if (st) return st;
    double v;
    st = tsv_double(t, r, "aniso_median", &v);
    if (!st) {
        snprintf(res->where, sizeof res->where, "%s:%d (aniso_median)", row->source, tsv_line(t, r));
        claim_set_value(row, res, v);
    }
    tsv_free(t);
    return st;
}

/* A count of the coupled row (column): aniso_trees, the trees entering the
 * median (anisotropy defined), or stands. */
cs_status claim_aniso_lattice_counts(const claim_row *row, claim_result *res)
{
    tsv *t;
    size_t r;
    cs_status st = claim_param_need(row, PARAM_COLUMN);
    if (st) return st;
    const char *col = row->param.column;
    if (strcmp(col, "aniso_trees") && strcmp(col, "stands"))
        return claim_param_bad(row, "column", "aniso_trees or stands");
    if ((st = coupled_row(row->source, &t, &r))) return st;
    long v;
    st = tsv_long(t, r, col, &v);
    if (!st) {
        snprintf(res->where, sizeof res->where, "%s:%d (%s)", row->source, tsv_line(t, r), col);
        claim_set_value(row, res, (double)v);
    }
    tsv_free(t);
    return st;
}

/* The calibrated jitter a*, times the row's scale when it gives one (100: a percent). */
cs_status claim_jitter_star(const claim_row *row, claim_result *res)
{
    fs_calibration c;
    cs_status st = fs_jitter_star(row->source, &c);
    if (st) return st;
    snprintf(res->where, sizeof res->where, "%s:%d (interpolated %.4f%s)", row->source, c.line_lo, c.interp,
             c.bracketed ? "" : "; FIELD MEDIAN NOT BRACKETED by the sweep: nearest end");
    claim_set_value(row, res, row->param.set & PARAM_SCALE ? row->param.scale * c.value : c.value);
    return CS_OK;
}

/* Held-out at a*, the coupled row's column: aniso_median or elong_median
 * (judged IN the row's gate band), or stands (those built; the failed ones
 * named). */
cs_status claim_jitter_heldout(const claim_row *row, claim_result *res)
{
    tsv *t;
    size_t r;
    cs_status st = claim_param_need(row, PARAM_COLUMN);
    if (st) return st;
    const char *col = row->param.column;
    const int stands = !strcmp(col, "stands");
    if (!stands && strcmp(col, "aniso_median") && strcmp(col, "elong_median"))
        return claim_param_bad(row, "column", "aniso_median, elong_median or stands");
    if ((st = coupled_row(row->source, &t, &r))) return st;
    int line = tsv_line(t, r);
    if (stands) {
        long built, failed;
        st = tsv_long(t, r, "stands", &built);
        if (!st) st = tsv_long(t, r, "stands_failed", &failed);
        if (!st) {
            snprintf(res->where, sizeof res->where, "%s:%d (stands built; %ld failed%s)", row->source, line, failed,
                     failed ? ": NOT every stand built" : "");
            claim_set_value(row, res, (double)built);
        }
    } else {
        double v;
        st = tsv_double(t, r, col, &v);
        if (!st) {
            snprintf(res->where, sizeof res->where, "%s:%d (%s)", row->source, line, col);
            claim_set_value(row, res, v);
            claim_judge(row, res, GATE_IN, v);
        }
    }
    tsv_free(t);
    return st;
}

/* Buildable levels (trees > 0) and their median anisotropy, in file order. */
static cs_status family_curve(const char *path, double *lv, double *an, size_t max, size_t *n, size_t *unbuildable,
                              int *last_line)
{
    tsv *t;
    fs_trees tr;
    cs_status st = fs_load_checked(path, &t, &tr);
    if (st) return st;
    fs_trees_free(&tr);
    *n = 0;
    *unbuildable = 0;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        const char *arm;
        if ((st = tsv_text(t, r, "arm", &arm))) break;
        if (strcmp(arm, "coupled")) continue;
        long trees;
        if ((st = tsv_long(t, r, "trees", &trees))) break;
        if (trees == 0) { (*unbuildable)++; continue; }
        if (*n == max) { st = cs_err(CS_EINPUT, "%s: more than %zu levels", path, max); break; }
        if ((st = tsv_double(t, r, "level", &lv[*n]))) break;
        if ((st = tsv_double(t, r, "aniso_median", &an[*n]))) break;
        *last_line = tsv_line(t, r);
        (*n)++;
    }
    tsv_free(t);
    return st;
}

/* HardcoreRho, JitterRho: Spearman rho(level, median anisotropy) over the
 * buildable levels, shown as an exact fraction; gate by the row's key. */
cs_status claim_aniso_rho(const claim_row *row, claim_result *res)
{
    double lv[32], an[32], rho;
    size_t n, unb;
    int last = 0;
    cs_status st = family_curve(row->source, lv, an, 32, &n, &unb, &last);
    if (st) return st;
    if (n < 2) {
        claim_pending(res, "%s: only %zu buildable level(s), rho undefined (%zu unbuildable)", row->source, n, unb);
        return CS_OK;
    }
    if ((st = stats_spearman(lv, an, n, &rho))) return st;
    res->value = rho;
    fs_fraction_text(rho, res->text, sizeof res->text);
    snprintf(res->where, sizeof res->where, "%s (%zu buildable levels, %zu unbuildable)", row->source, n, unb);
    claim_judge(row, res, strstr(row->gate, "_max") ? GATE_LE : GATE_GE, rho);
    return CS_OK;
}

/* HardcoreOvershoot: median anisotropy at the tightest buildable hard-core level. */
cs_status claim_aniso_hardcore_overshoot(const claim_row *row, claim_result *res)
{
    double lv[32], an[32];
    size_t n, unb;
    int last = 0;
    cs_status st = family_curve(row->source, lv, an, 32, &n, &unb, &last);
    if (st) return st;
    if (n == 0) { claim_pending(res, "%s: no buildable hard-core level", row->source); return CS_OK; }
    size_t k = 0;
    for (size_t i = 1; i < n; i++) if (lv[i] > lv[k]) k = i;
    snprintf(res->where, sizeof res->where, "%s (aniso_median at c = %.2f, the tightest buildable level)", row->source,
             lv[k]);
    claim_set_value(row, res, an[k]);
    return CS_OK;
}
