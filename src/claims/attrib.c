/* attrib: the explained / unexplained column of the comparison; see attrib.h. */
#include "attrib.h"
#include "afile.h"
#include "tsv.h"
#include "unstated.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define REACH 0.10 /* "reaches": within 10 % of the paper's value */

static cs_status push(attrib_data *d, const char *q, const char *unit, double x, double v, int sens)
{
    attrib_value *nv = realloc(d->v, (d->n + 1) * sizeof *nv);
    if (!nv) return cs_err(CS_ENOMEM, "attrib: out of memory");
    d->v = nv;
    attrib_value *a = &d->v[d->n++];
    snprintf(a->quantity, sizeof a->quantity, "%s", q);
    snprintf(a->unit, sizeof a->unit, "%s", unit);
    a->x = x;
    a->value = v;
    a->sens = sens;
    return CS_OK;
}

/* Rows of one summary: quantity, unit column (reading or choice), value, x. */
static cs_status load_one(const char *path, const char *unitcol, int sens, attrib_data *d)
{
    struct stat sb;
    if (!path || stat(path, &sb) != 0) return CS_OK;
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        const char *q = tsv_str(t, r, "quantity"), *u = tsv_str(t, r, unitcol);
        double v, x = NAN;
        if (!q || !u) { st = cs_err(CS_EINPUT, "%s:%d: field 'quantity'/'%s' missing", path, tsv_line(t, r), unitcol); break; }
        if ((st = tsv_double_nf(t, r, "value", &v))) break;
        if (sens && (st = tsv_double_nf(t, r, "x", &x))) break;
        st = push(d, q, u, x, v, sens);
    }
    tsv_free(t);
    if (!st) { if (sens) d->have_sens = 1; else d->have_readings = 1; }
    return st;
}

cs_status attrib_load(const char *readings_summary, const char *sens_summary, attrib_data *d)
{
    memset(d, 0, sizeof *d);
    cs_status st = load_one(readings_summary, "reading", 0, d);
    if (!st) st = load_one(sens_summary, "choice", 1, d);
    if (st) attrib_free(d);
    return st;
}

void attrib_free(attrib_data *d)
{
    free(d->v);
    memset(d, 0, sizeof *d);
}

static void add_by(attrib_result *out, const char *s)
{
    size_t l = strlen(out->by);
    if (l + strlen(s) + 3 < sizeof out->by) snprintf(out->by + l, sizeof out->by - l, "%s%s", l ? ", " : "", s);
}

void attrib_judge(const attrib_data *d, const claim_row *row, const claim_result *res, attrib_result *out)
{
    memset(out, 0, sizeof *out);
    double p, rel;
    if (!claims_rel_diff(row, res, &p, &rel)) return;
    if (fabs(rel) <= REACH) { out->kind = ATTRIB_WITHIN; return; }
    int tested = 0;
    /* the readings: each is one alternative */
    for (size_t i = 0; i < d->n; i++) {
        const attrib_value *a = &d->v[i];
        if (a->sens || strcmp(a->quantity, row->macro)) continue;
        tested = 1;
        if (fabs(a->value - p) <= REACH * fabs(p)) {
            char s[64];
            snprintf(s, sizeof s, "reading %s", a->unit);
            add_by(out, s);
        }
    }
    /* the unstated choices: a value within 10 %, or the span over the centre
     * run and the choice's values brackets the paper's value */
    char seen[1024] = "";
    for (size_t i = 0; i < d->n; i++) {
        const attrib_value *a = &d->v[i];
        if (!a->sens || strcmp(a->quantity, row->macro) || !strcmp(a->unit, "centre")) continue;
        tested = 1;
        char key[48];
        snprintf(key, sizeof key, "|%s|", a->unit);
        if (strstr(seen, key)) continue;
        if (strlen(seen) + strlen(key) < sizeof seen) strcat(seen, key);
        double lo = INFINITY, hi = -INFINITY, best = NAN;
        for (size_t j = 0; j < d->n; j++) {
            const attrib_value *b = &d->v[j];
            if (!b->sens || strcmp(b->quantity, row->macro)) continue;
            if (strcmp(b->unit, a->unit) && strcmp(b->unit, "centre")) continue;
            if (b->value < lo) lo = b->value;
            if (b->value > hi) hi = b->value;
            if (strcmp(b->unit, "centre") && (isnan(best) || fabs(b->value - p) < fabs(best - p))) best = b->value;
        }
        int near = isfinite(best) && fabs(best - p) <= REACH * fabs(p);
        /* a categorical choice (the die-back rules) has nothing between its values */
        const unstated_choice *uc = unstated_find(a->unit);
        int bracket = lo <= p && p <= hi && !(uc && uc->categorical);
        if (near || bracket) add_by(out, a->unit);
    }
    out->kind = out->by[0] ? ATTRIB_EXPLAINED : tested ? ATTRIB_UNEXPLAINED : ATTRIB_UNTESTED;
}

static void by_add(char *by, size_t n, const char *s)
{
    size_t l = strlen(by);
    if (l + strlen(s) + 3 < n) snprintf(by + l, n - l, "%s%s", l ? ", " : "", s);
}

int attrib_reached(const attrib_data *d, const claim_row *row, const claim_result *res, double lo, double hi,
                   char *by, size_t n, int *tested)
{
    by[0] = '\0';
    *tested = 0;
    double p, rel;
    if (!claims_rel_diff(row, res, &p, &rel)) return 0;
    double v = res->value, centre = v;
    for (size_t i = 0; i < d->n; i++)
        if (d->v[i].sens && !strcmp(d->v[i].quantity, row->macro) && !strcmp(d->v[i].unit, "centre")) centre = d->v[i].value;
    for (size_t i = 0; i < d->n; i++) {
        const attrib_value *a = &d->v[i];
        if (strcmp(a->quantity, row->macro) || (a->sens && !strcmp(a->unit, "centre"))) continue;
        *tested = 1;
        double shift = a->value - (a->sens ? centre : v);
        int inside = lo + shift <= p && p <= hi + shift;
        const unstated_choice *uc = a->sens ? unstated_find(a->unit) : NULL;
        int between = a->sens && !(uc && uc->categorical) && fmin(v, v + shift) <= p && p <= fmax(v, v + shift);
        if (!inside && !between) continue;
        char s[64];
        snprintf(s, sizeof s, a->sens ? "%s" : "reading %s", a->unit);
        if (!strstr(by, s)) by_add(by, n, s);
    }
    return by[0] != '\0';
}

void attrib_count(const attrib_data *d, const claims *c, const claim_result *res, attrib_counts *k)
{
    memset(k, 0, sizeof *k);
    for (size_t i = 0; i < c->n; i++) {
        double p, rel;
        if (!claims_rel_diff(&c->rows[i], &res[i], &p, &rel)) continue;
        k->measured++;
        k->in10 += fabs(rel) <= 0.10;
        k->in25 += fabs(rel) <= 0.25;
        attrib_result a;
        attrib_judge(d, &c->rows[i], &res[i], &a);
        k->attributed += a.kind == ATTRIB_EXPLAINED;
        k->unexplained += a.kind == ATTRIB_UNEXPLAINED || a.kind == ATTRIB_UNTESTED;
        k->untested += a.kind == ATTRIB_UNTESTED;
    }
}

void attrib_line(const attrib_counts *k, int tex, char *buf, size_t n)
{
    const char *pc = tex ? "\\,\\%" : " %";
    snprintf(buf, n, "%zu of %zu measured numbers within 10%s / %zu within 25%s of the reference paper; of the %zu beyond 10%s, "
                     "%zu attributed (a reading or an unstated choice reaches the paper's value) and %zu unexplained (%zu of them "
                     "measured under no reading or choice)",
             k->in10, k->measured, pc, k->in25, pc, k->measured - k->in10, pc, k->attributed, k->unexplained, k->untested);
}
