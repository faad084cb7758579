/* spot: one random slice of a frozen generator unit redrawn; see spot.h. */
#include "spot.h"
#include "audit_data.h"
#include "evalvol.h"
#include "paths.h"
#include "tsv.h"
#include <errno.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* generated patches per slice: the first batch of the spacing and probe,
 * bit for bit a prefix of the whole (the patches are drawn batch by batch
 * from one stream); the teacher's evaluation stands of the spacing are
 * regrown whole */
enum { SPOT_PATCHES = 64 };

typedef struct {
    char dir[300], arm[8], probe[16], volume[16], outdir[64], out[128];
    unsigned seed;
    double d;
    unsigned long pick;
    size_t units, rows;
    char why[400];
} spot_state;

static spot_state g;
static pid_t g_pid = -1;

/* A frozen unit at path ".../weights_sNN_ARM.ckpt" with its samples and run
 * table beside it: dir, seed and arm; 0 when path is none. */
static int unit_of(const char *path, char *dir, size_t dn, unsigned *seed, char arm[8])
{
    const char *b = strrchr(path, '/');
    if (!b) return 0;
    char a[16];
    int used = 0;
    if (sscanf(b + 1, "weights_s%u_%15[a-z].ckpt%n", seed, a, &used) != 2 || b[1 + used] != '\0') return 0;
    if (strcmp(a, "joint") && strcmp(a, "indep")) return 0;
    snprintf(arm, 8, "%.7s", a);
    snprintf(dir, dn, "%.*s", (int)(b - path), path);
    char p[400];
    struct stat sb;
    snprintf(p, sizeof p, "%s/samples_s%02u_%s.tsv", dir, *seed, a);
    if (stat(p, &sb) != 0) return 0;
    snprintf(p, sizeof p, "%s/run_s%02u_%s.tsv", dir, *seed, a);
    return stat(p, &sb) == 0;
}

/* The slice: row j of the unit's run table (spacing, probe) and its volume. */
static int pick_row(gsl_rng *r)
{
    char p[400];
    snprintf(p, sizeof p, "%s/run_s%02u_%s.tsv", g.dir, g.seed, g.arm);
    tsv *t;
    if (tsv_read(p, &t)) { snprintf(g.why, sizeof g.why, "%s", cs_errmsg()); return 0; }
    /* the volume by the teacher stands per spacing its evaluation line states */
    const char *vol;
    if (evalvol_of_eval(tsv_meta(t, "eval"), &vol)) {
        snprintf(g.why, sizeof g.why, "%.300s: %s", p, cs_errmsg());
        tsv_free(t);
        return 0;
    }
    snprintf(g.volume, sizeof g.volume, "%s", vol);
    g.rows = tsv_nrows(t);
    int ok = g.rows > 0;
    if (ok) {
        size_t j = gsl_rng_uniform_int(r, g.rows);
        const char *pr = tsv_str(t, j, "probe");
        ok = pr && !tsv_double(t, j, "spacing", &g.d);
        if (ok) snprintf(g.probe, sizeof g.probe, "%s", pr);
        else snprintf(g.why, sizeof g.why, "%.300s: row %zu unreadable", p, j + 1);
    } else snprintf(g.why, sizeof g.why, "%.300s: no rows", p);
    tsv_free(t);
    return ok;
}

void spot_launch(unsigned long seed)
{
    memset(&g, 0, sizeof g);
    g_pid = -1;
    g.pick = seed ? seed : ((unsigned long)time(NULL) ^ ((unsigned long)getpid() << 16)) % 1000000000UL;
    paths_list l;
    if (paths_list_every(PATHS_FROZEN_DIR, 1, &l)) { snprintf(g.why, sizeof g.why, "%s", cs_errmsg()); return; }
    char dir[300], arm[8];
    unsigned s;
    for (size_t i = 0; i < l.n; i++) g.units += (size_t)unit_of(l.p[i], dir, sizeof dir, &s, arm);
    if (!g.units) {
        paths_list_free(&l);
        snprintf(g.why, sizeof g.why, "no frozen generator unit (weights with samples and run table)");
        return;
    }
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    if (!r) { paths_list_free(&l); snprintf(g.why, sizeof g.why, "out of memory"); return; }
    gsl_rng_set(r, g.pick);
    size_t k = gsl_rng_uniform_int(r, g.units), seen = 0;
    for (size_t i = 0; i < l.n; i++)
        if (unit_of(l.p[i], dir, sizeof dir, &s, arm) && seen++ == k) {
            snprintf(g.dir, sizeof g.dir, "%s", dir);
            snprintf(g.arm, sizeof g.arm, "%s", arm);
            g.seed = s;
        }
    paths_list_free(&l);
    int ok = pick_row(r);
    gsl_rng_free(r);
    if (!ok) return;
    snprintf(g.outdir, sizeof g.outdir, "build/spot.%ld", (long)getpid());
    snprintf(g.out, sizeof g.out, "%s/slice.tsv", g.outdir);
    if (mkdir(g.outdir, 0777) && errno != EEXIST) {
        snprintf(g.why, sizeof g.why, "%s: cannot create: %s", g.outdir, strerror(errno));
        return;
    }
    char w[400], sd[32], sseed[16], log[160], sp[16];
    snprintf(sp, sizeof sp, "%d", SPOT_PATCHES);
    snprintf(w, sizeof w, "%s/weights_s%02u_%s.ckpt", g.dir, g.seed, g.arm);
    snprintf(sd, sizeof sd, "%.17g", g.d);
    snprintf(sseed, sizeof sseed, "%u", g.seed);
    snprintf(log, sizeof log, "%s/slice.log", g.outdir);
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        FILE *lf = freopen(log, "w", stderr);
        if (lf && !freopen("/dev/null", "w", stdout)) _exit(126);
        setenv("OPENBLAS_NUM_THREADS", "1", 1);
        execl("/proc/self/exe", "crownshy", "main-redraw", "--weights", w, "--seed", sseed, "--arm", g.arm, "--volume",
              g.volume, "--spacing", sd, "--probe", g.probe, "--patches", sp, "--out", g.out, (char *)NULL);
        _exit(127);
    }
    if (pid < 0) snprintf(g.why, sizeof g.why, "fork: %s", strerror(errno));
    else g_pid = pid;
}

/* The next data line of f (comment lines and the column line skipped); 0 at the end. */
static int next_data(FILE *f, char *buf, size_t n, int *seen_columns)
{
    while (fgets(buf, (int)n, f)) {
        if (buf[0] == '#') continue;
        if (!*seen_columns) { *seen_columns = 1; continue; }
        return 1;
    }
    return 0;
}

/* The data lines of the frozen samples in the slice (the spacing's teacher
 * rows, the probe's generated rows) against the redraw's, in order: 0 when
 * equal; else the first differing row of the slice into *at. */
static int compare(const char *frozen, const char *redraw, size_t *n, size_t *at)
{
    FILE *a = fopen(frozen, "r"), *b = fopen(redraw, "r");
    int differ = !a || !b, ca = 0, cb = 0;
    char la[256], lb[256];
    *n = *at = 0;
    size_t gen = 0;
    while (!differ && next_data(a, la, sizeof la, &ca)) {
        char probe[16], which[16];
        double d;
        if (sscanf(la, "%lf\t%*s\t%15s\t%15s", &d, probe, which) != 3 || fabs(d - g.d) > 1e-9) continue;
        const int teacher = !strcmp(which, "teacher");
        if (!teacher && strcmp(probe, g.probe)) continue;
        /* the redraw holds every teacher row and the first SPOT_PATCHES generated ones */
        if (!teacher && gen == SPOT_PATCHES) break;
        ++*n;
        gen += !teacher;
        if (!next_data(b, lb, sizeof lb, &cb) || strcmp(la, lb)) { differ = 1; *at = *n; }
    }
    if (!differ && (!gen || next_data(b, lb, sizeof lb, &cb))) { differ = 1; *at = *n + 1; }
    if (a) fclose(a);
    if (b) fclose(b);
    return differ;
}

void spot_check(checklist *cl, const claims *c)
{
    if (g_pid > 0) {
        int ws;
        while (waitpid(g_pid, &ws, 0) < 0 && errno == EINTR) {}
        g_pid = -1;
        if (!WIFEXITED(ws) || WEXITSTATUS(ws) != 0)
            snprintf(g.why, sizeof g.why, "crownshy main-redraw failed (see %s/slice.log)", g.outdir);
    }
    char item[64];
    snprintf(item, sizeof item, "spot check SEED=%lu", g.pick);
    if (g.why[0]) { checklist_add(cl, VERDICT_FAIL, item, "%s (repeat: make verify SEED=%lu)", g.why, g.pick); return; }
    char fz[400], feeds[600] = "(no claim)";
    snprintf(fz, sizeof fz, "%s/samples_s%02u_%s.tsv", g.dir, g.seed, g.arm);
    if (c) audit_feeds(c, fz, feeds, sizeof feeds);
    size_t n, at;
    const double p1 = 1.0 / (double)g.units;
    if (compare(fz, g.out, &n, &at))
        checklist_add(cl, VERDICT_FAIL, item,
                      "%s, spacing %g, probe %s: the redraw from its weights differs at slice row %zu (%s); claims: %s",
                      fz, g.d, g.probe, at, g.out, feeds);
    else {
        checklist_add(
            cl, VERDICT_PASS, item,
            "%s, spacing %g, probe %s (volume %s): %zu rows redrawn from its weights, bit-identical; "
            "a unit fabricated whole is caught by one verify with probability 1/%zu = %.3f, by 100 verifies %.2f",
            fz, g.d, g.probe, g.volume, n, g.units, p1, 1.0 - pow(1.0 - p1, 100));
        char cmd[96];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", g.outdir);
        if (system(cmd) != 0) { /* a leftover folder under build/ is harmless */ }
    }
}
