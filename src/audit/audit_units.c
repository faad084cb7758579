/* audit_units: every unit table's identity (audit/README.md, "What `make
 * verify` prints"): the seed and arm a run, probes or samples table's name
 * carries against its command line and its rows, its volume against its
 * evaluation line. A consistent fabrication that also rewrites the command
 * line passes here; the spot check and tier 2 redraw it from its weights. */
#include "audit_units.h"
#include "audit_data.h"
#include "evalvol.h"
#include "paths.h"
#include "tsv.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The value after " --name " in a command line, into out; 0 when absent. */
static int cmd_opt(const char *cmd, const char *name, char *out, size_t n)
{
    char key[40];
    snprintf(key, sizeof key, " --%s ", name);
    const char *p = strstr(cmd, key);
    if (!p) return 0;
    p += strlen(key);
    snprintf(out, n, "%.*s", (int)strcspn(p, " "), p);
    return 1;
}

/* One unit table (run_, probes_ or samples_sNN_ARM.tsv): the seed and arm of
 * its name against its command line (--seed, --arm, and the path it wrote),
 * its volume against its evaluation line, and its rows' seed and arm columns.
 * The first disagreement into why; 0 when all agree or it is no unit table. */
static int identity_of(const char *path, char *why, size_t n)
{
    const char *b = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    unsigned seed;
    char kind[16], arm[16];
    int used = 0;
    if (sscanf(b, "%15[a-z]_s%u_%15[a-z].tsv%n", kind, &seed, arm, &used) != 3 || b[used] != '\0') return 0;
    if ((strcmp(kind, "run") && strcmp(kind, "probes") && strcmp(kind, "samples")) ||
        (strcmp(arm, "joint") && strcmp(arm, "indep")))
        return 0;
    tsv *t;
    if (tsv_read(path, &t)) { snprintf(why, n, "%s", cs_errmsg()); return 1; }
    const char *cmd = tsv_meta(t, "command"), *ev = tsv_meta(t, "eval");
    char v[300], want[64];
    int bad = 0;
    if (!cmd) {
        snprintf(why, n, "no # command: line");
        bad = 1;
    } else if (!cmd_opt(cmd, "seed", v, sizeof v) || strtoul(v, NULL, 10) != seed) {
        snprintf(why, n, "its name says seed %u, its command --seed %s", seed,
                 cmd_opt(cmd, "seed", v, sizeof v) ? v : "(none)");
        bad = 1;
    } else if (!cmd_opt(cmd, "arm", v, sizeof v) || strcmp(v, arm)) {
        snprintf(why, n, "its name says arm %s, its command --arm %s", arm,
                 cmd_opt(cmd, "arm", v, sizeof v) ? v : "(none)");
        bad = 1;
    } else if (cmd_opt(cmd, strcmp(kind, "samples") ? "out" : "samples", v, sizeof v) &&
               strcmp(strrchr(v, '/') ? strrchr(v, '/') + 1 : v, b)) {
        snprintf(why, n, "its command wrote %.200s, not a file of this name", v);
        bad = 1;
    } else if (ev && cmd_opt(cmd, "volume", v, sizeof v)) {
        /* an evaluation line that starts "volume NAME:" names the command's
         * volume as the command spelt it; one that names none is the small
         * volume's (mainrun.h: its teacher stands per spacing), which the
         * large volume's command may not claim */
        snprintf(want, sizeof want, "volume %.40s:", v);
        const char *vol = NULL;
        const int named = !strncmp(ev, "volume ", 7);
        if (!named && evalvol_of_eval(ev, &vol)) vol = NULL;
        if (named ? strncmp(ev, want, strlen(want)) != 0
                  : !vol || strcmp(vol, EVALVOL_SMALL) || !strcmp(v, EVALVOL_LARGE)) {
            snprintf(why, n, "its command says --volume %.40s, its # eval: line another volume", v);
            bad = 1;
        }
    }
    for (size_t r = 0; r < tsv_nrows(t) && !bad; r++) {
        const char *rs = tsv_str(t, r, "seed"), *ra = tsv_str(t, r, "arm");
        if (rs && strtoul(rs, NULL, 10) != seed) {
            snprintf(why, n, "line %d: seed %s in a table named seed %u", tsv_line(t, r), rs, seed);
            bad = 1;
        } else if (ra && strcmp(ra, arm)) {
            snprintf(why, n, "line %d: arm %s in a table named arm %s", tsv_line(t, r), ra, arm);
            bad = 1;
        }
    }
    tsv_free(t);
    return bad;
}

void audit_identities(const claims *c, checklist *cl)
{
    paths_list l;
    if (paths_list_every(PATHS_FROZEN_DIR, 1, &l)) {
        checklist_add(cl, VERDICT_FAIL, "unit identities", "%s", cs_errmsg());
        return;
    }
    size_t bad = 0, units = 0;
    for (size_t i = 0; i < l.n; i++) {
        char why[400] = "";
        const size_t len = strlen(l.p[i]);
        if (len < 5 || strcmp(l.p[i] + len - 4, ".tsv")) continue;
        const int r = identity_of(l.p[i], why, sizeof why);
        if (!why[0] && !r) {
            units += strstr(l.p[i], "_s") != NULL &&
                     (strstr(l.p[i], "/run_s") || strstr(l.p[i], "/probes_s") || strstr(l.p[i], "/samples_s"));
            continue;
        }
        char feeds[600];
        audit_feeds(c, l.p[i], feeds, sizeof feeds);
        checklist_add(cl, VERDICT_FAIL, "unit identities",
                      "%s: %s (a unit's name, provenance and rows must agree); claims: %s", l.p[i], why, feeds);
        bad++;
    }
    paths_list_free(&l);
    if (!bad)
        checklist_add(cl, VERDICT_PASS, "unit identities",
                      "%zu unit tables: seed and arm of the name equal the command's and every row's, the volume the "
                      "evaluation's",
                      units);
}
