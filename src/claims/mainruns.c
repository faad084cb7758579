/* mainruns: a reading's E3/E4 results from its per-run tables; see mainruns.h. */
#include "mainruns.h"
#include "gate.h"
#include "paths.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#define UNITSET "/run_s*_*.tsv"

int mainruns_unit_set(const char *source, char *dir, size_t n)
{
    size_t ls = strlen(source), lu = strlen(UNITSET);
    if (ls <= lu || strcmp(source + ls - lu, UNITSET)) return 0;
    snprintf(dir, n, "%.*s", (int)(ls - lu), source);
    return 1;
}

cs_status mainruns_gate_seeds(int *want)
{
    double w;
    cs_status st = gate_read_value(PATHS_GATE("main"), "seeds", 0, &w);
    if (st) return st;
    if (!(w >= 1 && w <= MAINRUNS_MAXSEED))
        return cs_err(CS_EINPUT, "%s: field 'seeds': %g outside 1..%d", PATHS_GATE("main"), w, MAINRUNS_MAXSEED);
    *want = (int)w;
    return CS_OK;
}

static int probe_index(const char *p)
{
    return !strcmp(p, "generated") ? 0 : !strcmp(p, "shuffled") ? 1 : !strcmp(p, "rotated") ? 2 : -1;
}

/* One unit: per probe the mean over the unseen rows (summed in file order,
 * as main-summary does), and the generated W1 at each extrapolation spacing. */
static cs_status read_unit(const char *path, mainruns *m, int a, int s)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    double sum[3] = {0, 0, 0};
    int cnt[3] = {0, 0, 0};
    for (size_t i = 0; i < tsv_nrows(t) && !st; i++) {
        double w1, d;
        if ((st = tsv_double(t, i, "w1", &w1)) || (st = tsv_double(t, i, "spacing", &d))) break;
        const char *split = tsv_str(t, i, "split"), *probe = tsv_str(t, i, "probe");
        int q = probe ? probe_index(probe) : -1;
        if (!split || q < 0) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'split'/'probe': missing or unknown", path, tsv_line(t, i));
            break;
        }
        if (!strcmp(split, "unseen")) { sum[q] += w1; cnt[q]++; continue; }
        if (strcmp(split, "extrap")) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'split': '%s' (unseen or extrap)", path, tsv_line(t, i), split);
            break;
        }
        if (q) continue;
        int k = 0;
        while (k < m->nex && m->exd[k] != d) k++;
        if (k == m->nex) {
            if (m->nex == MAINRUNS_MAXSP) {
                st = cs_err(CS_EINPUT, "%s:%d: more than %d extrapolation spacings", path, tsv_line(t, i),
                            MAINRUNS_MAXSP);
                break;
            }
            m->exd[m->nex++] = d;
        }
        m->ex[a][k][s - 1] = w1;
    }
    if (!st && !cnt[0]) st = cs_err(CS_EINPUT, "%s: no unseen-spacing rows", path);
    for (int q = 1; q < 3 && !st; q++)
        if (cnt[q] && cnt[q] != cnt[0])
            st =
                cs_err(CS_EINPUT, "%s: the %s probe misses some unseen spacing", path, q == 1 ? "shuffled" : "rotated");
    for (int q = 0; q < 3 && !st; q++)
        if (cnt[q]) { m->err[a][q][s - 1] = sum[q] / cnt[q]; m->has[a][q]++; }
    tsv_free(t);
    return st;
}

static void add_missing(mainruns *m, int s, const char *arm)
{
    size_t l = strlen(m->missing);
    m->nmissing++;
    if (l + 24 >= sizeof m->missing) {
        if (!strstr(m->missing, "...")) snprintf(m->missing + l, sizeof m->missing - l, " ...");
        return;
    }
    snprintf(m->missing + l, sizeof m->missing - l, "%ss%02d_%s", l ? " " : "", s, arm);
}

cs_status mainruns_load(const char *dir, int want, mainruns *m)
{
    static const char *arms[2] = {"joint", "indep"};
    memset(m, 0, sizeof *m);
    if (want < 1 || want > MAINRUNS_MAXSEED)
        return cs_err(CS_EINPUT, "%s: %d seeds asked (1..%d)", dir, want, MAINRUNS_MAXSEED);
    m->want = want;
    for (int a = 0; a < 2; a++)
        for (int k = 0; k < MAINRUNS_MAXSP; k++)
            for (int s = 0; s < MAINRUNS_MAXSEED; s++) m->ex[a][k][s] = NAN;
    cs_status st = CS_OK;
    for (int s = 1; s <= want && !st; s++) {
        int both = 1;
        for (int a = 0; a < 2 && !st; a++) {
            char p[1100];
            snprintf(p, sizeof p, "%s/run_s%02d_%s.tsv", dir, s, arms[a]);
            if (access(p, F_OK) != 0) { add_missing(m, s, arms[a]); both = 0; continue; }
            st = read_unit(p, m, a, s);
        }
        m->complete += both;
        m->seed_ok[s - 1] = both;
    }
    if (st || m->nmissing) return st;
    for (int a = 0; a < 2; a++)
        for (int q = 0; q < 3; q++)
            if (m->has[a][q] && m->has[a][q] != want)
                return cs_err(CS_EINPUT, "%s: %d of %d seeds have the %s %s rows", dir, m->has[a][q], want, arms[a],
                              q == 1   ? "shuffled"
                              : q == 2 ? "rotated"
                                       : "generated");
    if (m->has[0][1] != want)
        return cs_err(CS_EINPUT, "%s: the joint runs lack the shuffled probe (preregistered)", dir);
    for (int k = 0; k < m->nex; k++)
        for (int a = 0; a < 2; a++)
            for (int s = 0; s < want; s++)
                if (isnan(m->ex[a][k][s]))
                    return cs_err(CS_EINPUT, "%s: seed %d %s has no W1 at %.1f m", dir, s + 1, arms[a], m->exd[k]);
    return CS_OK;
}

void mainruns_pending_text(const mainruns *m, const char *dir, char *buf, size_t n)
{
    snprintf(buf, n, "%s: %d of %d seeds frozen (both arms); the claim waits for every unit; missing %d: %s", dir,
             m->complete, m->want, m->nmissing, m->missing);
}
