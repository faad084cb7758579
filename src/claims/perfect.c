/* perfect: what the reference paper's shuffled-geometry numbers require of a
 * teacher (design.md §8.3; reference paper §5.1). The probe is judged by the
 * ratio of a generator's shuffled error to its error. A perfect generator
 * (the teacher's own crowns) degrades under the shuffle to the teacher's
 * shuffled level L (MainShufTeach). A generator at error m_J that responds to
 * the shuffle as the teacher does, give or take its own error, has a shuffled
 * error of at most L + m_J (triangle inequality of W1), so a ratio of at most
 * 1 + L / m_J. At the paper's joint error m_J = 0.415 m its ratio 2.50 needs
 * L >= (2.50 - 1) x 0.415 m. L is measured under every teacher the sensitivity
 * experiment runs (the adopted one, each unstated choice either side of ours,
 * and the die-back readings), from frozen/sensitivity/summary.tsv, the
 * paper's values from the registry's reference column. Descriptive, never
 * gated; extremes over teachers, not sampling statistics (each level's
 * sampling error is of the order of MainNoise). */
#include "claims.h"
#include "paths.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PERFECT_LEVEL "MainShufTeach"
#define PERFECT_MAXUNITS 256

typedef struct {
    double level[PERFECT_MAXUNITS];
    int n;
    double paper_joint, paper_ratio;
} perfect_data;

/* The paper's value of a registry row, as a number. */
static cs_status paper_value(const claims *c, const char *macro, double *out)
{
    const claim_row *r = claims_find(c, macro);
    char *end = NULL;
    if (r) *out = strtod(r->reference, &end);
    if (!r || end == r->reference || !isfinite(*out) || *out <= 0)
        return cs_err(CS_EINPUT, "%s: no positive reference value for %s", PATHS_CLAIMS, macro);
    return CS_OK;
}

/* The teacher's shuffled level of every unit of the sensitivity table. */
static cs_status perfect_load(const claim_row *row, claim_result *res, perfect_data *d)
{
    memset(d, 0, sizeof *d);
    claims c;
    cs_status st = claims_registry(&c);
    if (st) return st;
    if (!(st = paper_value(&c, "MainJoint", &d->paper_joint))) st = paper_value(&c, "MainGeomRatio", &d->paper_ratio);
    claims_free(&c);
    if (st) return st;
    tsv *t;
    if ((st = tsv_read(row->source, &t))) return st;
    for (size_t i = 0; i < tsv_nrows(t) && !st; i++) {
        const char *q = tsv_str(t, i, "quantity");
        if (!q) { st = cs_err(CS_EINPUT, "%s:%d: field 'quantity' missing", row->source, tsv_line(t, i)); break; }
        if (strcmp(q, PERFECT_LEVEL)) continue;
        double v;
        if ((st = tsv_double(t, i, "value", &v))) break;
        if (!isfinite(v) || v <= 0) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'value': %g is not a level", row->source, tsv_line(t, i), v);
            break;
        }
        if (d->n == PERFECT_MAXUNITS) {
            st = cs_err(CS_EINPUT, "%s: more than %d units", row->source, PERFECT_MAXUNITS);
            break;
        }
        d->level[d->n++] = v;
    }
    tsv_free(t);
    if (!st && !d->n) st = cs_err(CS_EINPUT, "%s: no %s rows", row->source, PERFECT_LEVEL);
    if (!st)
        snprintf(res->where, sizeof res->where, "%.300s (%s, %d teachers); paper values from %s", row->source,
                 PERFECT_LEVEL, d->n, PATHS_CLAIMS);
    return st;
}

static double extreme(const perfect_data *d, int hi)
{
    double m = d->level[0];
    for (int i = 1; i < d->n; i++) m = hi ? fmax(m, d->level[i]) : fmin(m, d->level[i]);
    return m;
}

static int reaching(const perfect_data *d)
{
    int n = 0;
    for (int i = 0; i < d->n; i++) n += 1.0 + d->level[i] / d->paper_joint >= d->paper_ratio;
    return n;
}

/* Each claim: the levels loaded, one number of them. */
static cs_status perfect_claim(const claim_row *row, claim_result *res, double (*of)(const perfect_data *))
{
    perfect_data d;
    cs_status st = perfect_load(row, res, &d);
    if (!st) claim_set_value(row, res, of(&d));
    return st;
}

static double shuf_lo(const perfect_data *d) { return extreme(d, 0); }
static double shuf_hi(const perfect_data *d) { return extreme(d, 1); }
/* the shuffled level the paper's ratio needs at the paper's joint error */
static double shuf_needed(const perfect_data *d) { return (d->paper_ratio - 1.0) * d->paper_joint; }
/* the largest ratio a generator at the paper's joint error reaches on any teacher */
static double bound_max(const perfect_data *d) { return 1.0 + extreme(d, 1) / d->paper_joint; }
/* how many teachers let it reach the paper's ratio, and how many were run */
static double n_reaching(const perfect_data *d) { return (double)reaching(d); }
static double n_teachers(const perfect_data *d) { return (double)d->n; }

cs_status claim_perfect_shuf_lo(const claim_row *row, claim_result *res) { return perfect_claim(row, res, shuf_lo); }
cs_status claim_perfect_shuf_hi(const claim_row *row, claim_result *res) { return perfect_claim(row, res, shuf_hi); }
cs_status claim_perfect_shuf_needed(const claim_row *row, claim_result *res)
{
    return perfect_claim(row, res, shuf_needed);
}
cs_status claim_perfect_bound_max(const claim_row *row, claim_result *res)
{
    return perfect_claim(row, res, bound_max);
}
cs_status claim_perfect_reaching(const claim_row *row, claim_result *res)
{
    return perfect_claim(row, res, n_reaching);
}
cs_status claim_perfect_teachers(const claim_row *row, claim_result *res)
{
    return perfect_claim(row, res, n_teachers);
}
