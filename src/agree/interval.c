/* interval: the statement table, the statistics and the evaluation; see
 * interval.h (design.md §6.1). */
#include "interval.h"
#include "stats.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static cs_status meta_number(const tsv *t, const char *key, double *v)
{
    const char *s = tsv_meta(t, key);
    char *end;
    if (!s) return cs_err(CS_EINPUT, "%s: header line '# %s:' missing", tsv_path(t), key);
    *v = strtod(s, &end);
    if (end == s || *end) return cs_err(CS_EINPUT, "%s: header '# %s: %s' is not a number", tsv_path(t), key, s);
    return CS_OK;
}

cs_status interval_table_load(const char *path, interval_table *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->path, sizeof out->path, "%s", path);
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    double seed, b, level;
    if (!(st = meta_number(t, "seed", &seed)) && !(st = meta_number(t, "resamples", &b)))
        st = meta_number(t, "level", &level);
    if (!st && (seed < 1 || seed != floor(seed) || b < 1 || b != floor(b) || !(level > 0 && level < 1)))
        st = cs_err(CS_EINPUT, "%s: header: seed %g, resamples %g, level %g (need integers >= 1 and a level in (0, 1))",
                    path, seed, b, level);
    size_t n = tsv_nrows(t);
    out->s = calloc(n ? n : 1, sizeof *out->s);
    if (!st && !out->s) st = cs_err(CS_ENOMEM, "%s: out of memory", path);
    for (size_t r = 0; r < n && !st; r++) {
        interval_spec *s = &out->s[r];
        const char *f[4] = {"function", "unit", "method", "replicates"};
        char *dst[4] = {s->function, s->unit, s->method, s->replicates};
        size_t sz[4] = {sizeof s->function, sizeof s->unit, sizeof s->method, sizeof s->replicates};
        for (int k = 0; k < 4 && !st; k++) {
            const char *v = tsv_str(t, r, f[k]);
            if (!v || !v[0] || strlen(v) >= sz[k])
                st = cs_err(CS_EINPUT, "%s:%d: field '%s': %s", path, tsv_line(t, r), f[k],
                            !v     ? "missing"
                            : v[0] ? "too long"
                                   : "empty");
            else strcpy(dst[k], v);
        }
        s->line = tsv_line(t, r);
        if (!st && strcmp(s->method, "bootstrap") && strcmp(s->method, "range") && strcmp(s->method, "none"))
            st = cs_err(CS_EINPUT, "%s:%d: field 'method': '%s' (bootstrap, range or none)", path, s->line, s->method);
        for (size_t q = 0; q < r && !st; q++)
            if (!strcmp(out->s[q].function, s->function))
                st = cs_err(CS_EINPUT, "%s:%d: field 'function': %s stated twice", path, s->line, s->function);
        out->n = r + 1;
    }
    out->plan.seed = (unsigned long)seed;
    out->plan.resamples = (size_t)b;
    out->plan.level = level;
    tsv_free(t);
    if (st) interval_table_free(out);
    return st;
}

void interval_table_free(interval_table *t)
{
    free(t->s);
    t->s = NULL;
    t->n = 0;
}

const interval_spec *interval_table_find(const interval_table *t, const char *function)
{
    for (size_t i = 0; i < t->n; i++) if (!strcmp(t->s[i].function, function)) return &t->s[i];
    return NULL;
}

static cs_status col_median(const double *x, size_t n, size_t m, size_t c, double *out)
{
    return boot_stat_median(x, n, m, &c, out);
}

cs_status iv_stat_eval(const double *x, size_t n, size_t m, const void *ctx, double *out)
{
    const iv_stat *s = ctx;
    if (s->kind == IV_CALLBACK) return s->fn(x, n, m, s->ctx, out);
    if (s->a >= m || ((s->kind == IV_REL || s->kind == IV_RATIO || s->kind == IV_WILCOXON) && s->b >= m))
        return cs_err(CS_EINVARIANT, "interval: statistic column outside %zu columns", m);
    double *ca = malloc(n * sizeof *ca), *cb = malloc(n * sizeof *cb);
    if (!ca || !cb) { free(ca); free(cb); return cs_err(CS_ENOMEM, "interval: out of memory"); }
    for (size_t i = 0; i < n; i++) { ca[i] = x[i * m + s->a]; cb[i] = s->b < m ? x[i * m + s->b] : NAN; }
    cs_status st = CS_OK;
    double ma, mb;
    switch (s->kind) {
    case IV_MEDIAN: st = stats_median(ca, n, out); break;
    case IV_MIN: *out = stats_min(ca, n); break;
    case IV_MAX: *out = stats_max(ca, n); break;
    case IV_MEAN: *out = stats_mean(ca, n); break;
    case IV_REL:
        if (!(st = col_median(x, n, m, s->a, &ma)) && !(st = col_median(x, n, m, s->b, &mb)))
            *out = 100.0 * ((mb - ma) / mb);
        break;
    case IV_RATIO:
        if (!(st = col_median(x, n, m, s->a, &ma)) && !(st = col_median(x, n, m, s->b, &mb))) *out = ma / mb;
        break;
    case IV_WILCOXON: st = stats_wilcoxon_exact(cb, ca, n, out, NULL, NULL); break;
    case IV_QUANTILE: st = stats_quantile(ca, n, s->q, out); break;
    case IV_ZERO_PCT: {
        size_t z = 0;
        for (size_t i = 0; i < n; i++) z += ca[i] == 0;
        *out = 100.0 * ((double)z / (double)n);
        break;
    }
    default: st = cs_err(CS_EINVARIANT, "interval: unknown statistic %d", (int)s->kind);
    }
    free(ca);
    free(cb);
    return st;
}

static void fmt_value(const claim_row *row, double v, char *buf, size_t n)
{
    const char *f = strcmp(row->format, "text") ? row->format : "%.2f";
    snprintf(buf, n, f, v);
    const char *p = buf + (buf[0] == '-' || buf[0] == '+');
    int zero = *p != '\0';
    for (const char *q = p; *q; q++) if (*q != '0' && *q != '.') zero = 0;
    if (zero && buf[0] == '-') memmove(buf, buf + 1, strlen(buf));
}

/* The statistic of the frozen units themselves must be the claim's value. */
static cs_status check_own(const claim_row *row, const claim_result *res, const iv_data *d)
{
    double v;
    if (!strcmp(d->method, "bootstrap")) {
        cs_status st = iv_stat_eval(d->x, d->n, d->m, &d->stat, &v);
        if (st) return st;
        if (d->has_own_exact) {
            /* the resamples' statistic sums in another order: the same statistic, to rounding */
            if (!(fabs(v - d->own_exact) <= 1e-12 * fabs(d->own_exact)))
                return cs_err(CS_EINVARIANT,
                              "%s: the resample statistic gives %.17g on the frozen units, the claim's own order "
                              "%.17g: it is not the claim's statistic",
                              row->macro, v, d->own_exact);
            v = d->own_exact;
        }
    } else if (d->own >= 0) v = d->x[d->own];
    else return CS_OK;
    if (v != res->value && !(isnan(v) && isnan(res->value)))
        return cs_err(
            CS_EINVARIANT,
            "%s: its replicates (%s) give %.17g, the claim is %.17g: they are not the data the claim rests on",
            row->macro, d->from, v, res->value);
    return CS_OK;
}

static cs_status run_method(const interval_table *t, const claim_row *row, const claim_result *res,
                            const interval_spec *sp, iv_data *d, claim_interval *out)
{
    if (strcmp(sp->unit, d->unit) || strcmp(sp->method, d->method))
        return cs_err(CS_EINVARIANT, "%s:%d: %s is stated as %s over %s; the code computes %s over %s", t->path,
                      sp->line, sp->function, sp->method, sp->unit, d->method, d->unit);
    snprintf(out->from, sizeof out->from, "%s", d->from);
    out->n = d->n;
    if (!strcmp(d->method, "none")) {
        snprintf(out->why, sizeof out->why, "%s", d->why);
        snprintf(out->text, sizeof out->text, "none");
        return CS_OK;
    }
    cs_status st = check_own(row, res, d);
    if (st) return st;
    if (!strcmp(d->method, "bootstrap"))
        st = boot_percentile(d->x, d->n, d->m, iv_stat_eval, &d->stat, &t->plan, &out->lo, &out->hi);
    else st = boot_range(d->x, d->n, t->plan.level, &out->lo, &out->hi);
    if (st) return cs_err(st, "%s: interval over %s: %s", row->macro, d->from, cs_errmsg());
    out->has = 1;
    char a[48], b[48];
    fmt_value(row, out->lo, a, sizeof a);
    fmt_value(row, out->hi, b, sizeof b);
    snprintf(out->text, sizeof out->text, "[%s, %s]", a, b);
    return CS_OK;
}

cs_status interval_eval(const interval_table *t, const claim_row *row, const claim_result *res, claim_interval *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->text, sizeof out->text, "--");
    if (strcmp(row->kind, "measured") && !claims_kind_beside(row->kind)) return CS_OK;
    if (res->status != VERDICT_PASS) { snprintf(out->why, sizeof out->why, "the claim is not computed"); return CS_OK; }
    const interval_spec *sp = interval_table_find(t, row->function);
    if (!sp)
        return cs_err(
            CS_EINPUT,
            "%s: no row for %s (the computing function of measured claim %s): its interval method is not stated",
            t->path, row->function, row->macro);
    snprintf(out->unit, sizeof out->unit, "%s", sp->unit);
    snprintf(out->method, sizeof out->method, "%s", sp->method);
    iv_extract ex = interval_extractor(row->function);
    iv_data d = {0};
    d.own = -1;
    cs_status st;
    if (!ex) {
        d.unit = sp->unit;
        d.method = "none";
        snprintf(d.why, sizeof d.why, "%s", sp->replicates);
        st = CS_OK;
    } else st = ex(row, res, sp, &d);
    if (!st) st = run_method(t, row, res, sp, &d, out);
    free(d.x);
    if (d.cleanup) d.cleanup((void *)d.stat.ctx);
    return st;
}
