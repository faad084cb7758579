/* attrib: the explained / unexplained column of the comparison; see attrib.h. */
#include "attrib.h"
#include "afile.h"
#include "interval.h"
#include "tsv.h"
#include "study.h"
#include "unstated.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define REACH 0.10 /* "reaches": within 10 % of the paper's value */

/* Whether a summary value is of the claim row: the summaries name a claim by
 * its whole name, the registry's key. */
static int measures(const attrib_value *a, const claim_row *row)
{
    return !strcmp(a->quantity, row->macro);
}

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
        if (!q || !u) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'quantity'/'%s' missing", path, tsv_line(t, r), unitcol);
            break;
        }
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
        if (a->sens == 1 || !measures(a, row)) continue;
        tested = 1;
        if (fabs(a->value - p) <= REACH * fabs(p)) {
            char s[64];
            snprintf(s, sizeof s, a->sens ? "%s" : "reading %s", a->unit);
            add_by(out, s);
        }
    }
    /* the unstated choices: a value within 10 %, or the span over the centre
     * run and the choice's values brackets the paper's value */
    char seen[1024] = "";
    for (size_t i = 0; i < d->n; i++) {
        const attrib_value *a = &d->v[i];
        if (a->sens != 1 || !measures(a, row) || !strcmp(a->unit, "centre")) continue;
        tested = 1;
        char key[48];
        snprintf(key, sizeof key, "|%s|", a->unit);
        if (strstr(seen, key)) continue;
        if (strlen(seen) + strlen(key) < sizeof seen) strcat(seen, key);
        double lo = INFINITY, hi = -INFINITY, best = NAN;
        for (size_t j = 0; j < d->n; j++) {
            const attrib_value *b = &d->v[j];
            if (b->sens != 1 || !measures(b, row)) continue;
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

double attrib_half_unit(const char *ref)
{
    const char *dot = strchr(ref, '.');
    int dec = 0;
    if (dot) for (const char *q = dot + 1; *q >= '0' && *q <= '9'; q++) dec++;
    return 0.5 * pow(10.0, -dec);
}

#define GENSENS_DIR "generator-sensitivity/"
#define READING_DIR "paper-reading/"

/* The claim row r stands for under a training choice: the row its params
 * name (of), when r's source is a choice's unit set and that row is computed
 * by the same function on the paper reading's unit set the choice varies;
 * -1 when r is no training choice's value. */
static long gensens_base(const claims *c, size_t r, char *choice, size_t n)
{
    const claim_row *g = &c->rows[r];
    const char *at = strstr(g->source, GENSENS_DIR);
    if (!at || !(g->param.set & PARAM_OF)) return -1;
    const char *ch = at + strlen(GENSENS_DIR), *rest = strchr(ch, '/');
    if (!rest) return -1;
    char want[300];
    snprintf(want, sizeof want, "%.*s" READING_DIR "%s", (int)(at - g->source), g->source, rest + 1);
    snprintf(choice, n, "%.*s", (int)(rest - ch), ch);
    const claim_row *q = claims_find(c, g->param.of);
    return q && q != g && !strcmp(q->function, g->function) && !strcmp(q->source, want) ? (long)(q - c->rows) : -1;
}

void attrib_bind(attrib_data *d, const claims *c, const claim_result *res, const struct claim_interval *ci)
{
    d->c = c;
    d->res = res;
    d->ci = ci;
    if (d->have_gensens) return;
    d->have_gensens = 1;
    for (size_t r = 0; r < c->n; r++) {
        char choice[30], unit[40];
        const long q = gensens_base(c, r, choice, sizeof choice);
        if (q < 0 || res[r].status != VERDICT_PASS || !isfinite(res[r].value)) continue;
        snprintf(unit, sizeof unit, "training %s", choice);
        if (push(d, c->rows[q].macro, unit, NAN, res[r].value, 2)) return; /* out of memory: fewer alternatives */
    }
}

/* The t in [0, 1] (only t = 1 for a categorical alternative) at which the
 * interval [lo, hi] moved by t s holds p: [*a, *b], 0 when there is none. */
static int t_range(double lo, double hi, double p, double s, int cont, double *a, double *b)
{
    double ta = -INFINITY, tb = INFINITY;
    if (!isfinite(s)) return 0; /* the alternative could not compute the number */
    if (s != 0) { ta = fmin((p - hi) / s, (p - lo) / s); tb = fmax((p - hi) / s, (p - lo) / s); }
    else if (p < lo || p > hi) return 0;
    if (!cont) { *a = *b = 1; return ta <= 1 && 1 <= tb; }
    *a = fmax(ta, 0);
    *b = fmin(tb, 1);
    return *a <= *b;
}

/* The t in [0, 1] (only t = 1 for a categorical alternative) at which v
 * moved by t s is no further from p than v is: [*a, *b], 0 when none. */
static int t_closer(double v, double p, double s, int cont, double *a, double *b)
{
    if (!isfinite(s)) return 0;
    const double far = s != 0 ? 2 * (p - v) / s : 0; /* the other t as far from p as t = 0 */
    const double ta = s != 0 ? fmin(0, far) : -INFINITY, tb = s != 0 ? fmax(0, far) : INFINITY;
    if (!cont) { *a = *b = 1; return ta <= 1 && 1 <= tb; }
    *a = fmax(ta, 0);
    *b = fmin(tb, 1);
    return *a <= *b;
}

/* The centre run's value of a quantity (v when the centre did not measure it). */
static double centre_of(const attrib_data *d, const claim_row *row, double v)
{
    for (size_t i = 0; i < d->n; i++)
        if (d->v[i].sens == 1 && measures(&d->v[i], row) && !strcmp(d->v[i].unit, "centre"))
            return d->v[i].value;
    return v;
}

/* The experiment a claim belongs to (its frozen folder's code), or its section. */
static const char *experiment_of(const claim_row *row)
{
    const study_experiment *e = study_of_path(row->source);
    return e ? e->code : row->section;
}

/* Alternative a (a reading, or one value of an unstated choice) moves every
 * other number of the claim's experiment by the same fraction t of its own
 * shift; keep in *ta, *tb the t at which each that agrees today (the paper's
 * value inside our interval) stays inside and each that does not comes no
 * further from the paper's value, and name the first that cannot in
 * blocker. 0 when none is left. */
static int consistent(const attrib_data *d, const claim_row *row, const attrib_value *a, int cont, double *ta,
                      double *tb, char *blocker, size_t n)
{
    const char *ex = experiment_of(row);
    const claim_row *self = claims_find(d->c, row->macro); /* row may be a copy */
    for (size_t i = 0; i < d->c->n; i++) {
        const claim_row *q = &d->c->rows[i];
        const claim_result *qr = &d->res[i];
        const claim_interval *qi = &d->ci[i];
        double p, rel;
        if (q == self || !qi->has || !claims_rel_diff(q, qr, &p, &rel) || strcmp(experiment_of(q), ex)) continue;
        const double h = attrib_half_unit(q->reference), lo = qi->lo - h, hi = qi->hi + h;
        const int agrees = lo <= p && p <= hi;
        for (size_t j = 0; j < d->n; j++) {
            const attrib_value *b = &d->v[j];
            if (b->sens != a->sens || strcmp(b->unit, a->unit) || !measures(b, q)) continue;
            if ((a->sens == 1 && !(b->x == a->x)) || !isfinite(b->value))
                continue; /* not computable there: not measured */
            double s = b->value - (b->sens == 1 ? centre_of(d, q, qr->value) : qr->value), qa, qb;
            /* one in agreement stays in it; one outside may not move further from the paper */
            const int ok = agrees ? t_range(lo, hi, p, s, cont, &qa, &qb) : t_closer(qr->value, p, s, cont, &qa, &qb);
            if (!ok || fmax(*ta, qa) > fmin(*tb, qb)) {
                snprintf(blocker, n, "%s %s", q->macro, agrees ? "out" : "further off");
                return 0;
            }
            *ta = fmax(*ta, qa);
            *tb = fmin(*tb, qb);
        }
    }
    return 1;
}

int attrib_reached(const attrib_data *d, const claim_row *row, const claim_result *res, double lo, double hi,
                   char *by, size_t n, int *tested)
{
    by[0] = '\0';
    *tested = 0;
    double p, rel;
    if (!claims_rel_diff(row, res, &p, &rel)) return 0;
    const double v = res->value, centre = centre_of(d, row, v);
    char blocked[240] = "";
    for (size_t i = 0; i < d->n; i++) {
        const attrib_value *a = &d->v[i];
        if (!measures(a, row) || (a->sens == 1 && !strcmp(a->unit, "centre"))) continue;
        *tested = 1;
        const unstated_choice *uc = a->sens == 1 ? unstated_find(a->unit) : NULL;
        /* a reading or a categorical choice moves by its whole shift; a numeric choice by a fraction */
        const int cont = (a->sens == 1 && !(uc && uc->categorical)) || a->sens == 2;
        double ta, tb;
        if (!t_range(lo, hi, p, a->value - (a->sens == 1 ? centre : v), cont, &ta, &tb)) continue;
        char s[64], blocker[96] = "";
        if (a->sens == 1) snprintf(s, sizeof s, "%s %g", a->unit, a->x);
        else snprintf(s, sizeof s, a->sens ? "%s" : "reading %s", a->unit);
        if (d->c && !consistent(d, row, a, cont, &ta, &tb, blocker, sizeof blocker)) {
            char b[140];
            snprintf(b, sizeof b, "%s (moves %s)", s, blocker);
            if (!strstr(blocked, b)) by_add(blocked, sizeof blocked, b);
            continue;
        }
        if (!strstr(by, s)) by_add(by, n, s);
    }
    const int reached = by[0] != '\0';
    if (!reached && blocked[0]) snprintf(by, n, "only by moving another number: %s", blocked);
    return reached;
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
    snprintf(
        buf, n,
        "%zu of %zu measured numbers within 10%s / %zu within 25%s of the reference paper; of the %zu beyond 10%s, "
        "%zu attributed (a reading or an unstated choice reaches the paper's value) and %zu unexplained (%zu of them "
        "measured under no reading or choice)",
        k->in10, k->measured, pc, k->in25, pc, k->measured - k->in10, pc, k->attributed, k->unexplained, k->untested);
}
