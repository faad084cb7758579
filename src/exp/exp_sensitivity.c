/* exp_sensitivity: the steps of a sensitivity unit, the unit's record
 * unit.tsv and the loop that builds them; see exp_sensitivity.h (design.md §7
 * E0 "sensitivity"). E1 and E2 run at the unit's --stands per cell (fewer
 * than the full run: the centre run uses the same counts, so the columns
 * compare), E5/E6 at the full run's counts. Every table the choice cannot
 * change is the centre run's, identical by construction; unit.tsv, written
 * last, says where each lives. */
#include "exp_sensitivity.h"
#include "fieldsim.h"
#include "prov.h"
#include "tsv.h"
#include "unstated.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* The unit's steps in order: the table each writes (relative to DIR) and the
 * command that writes it. Placeholders: %D the unit folder, %S E1/E2 stands,
 * %F field stands, %W sweep stands, %B beta_field (from DIR/field/calibration.tsv). */
typedef struct { const char *target; const char *cmd; } sens_step;
static const sens_step STEPS[] = {
    {"mechanism/sweep.tsv", "mechanism-sweep --stands %S --out %D"},
    {"mechanism/ablation.tsv", "mechanism-ablation --stands %S --out %D"},
    {"mechanism/figure_crowns.tsv", "mechanism-figure --out %D"},
    {"pointcloud/stats.tsv", "pointcloud-figure --out %D"},
    {"irreducibility/perturb_train.tsv", "irreducibility-perturb --stands %S --out %D"},
    {"irreducibility/refine_train.tsv", "irreducibility-refine --stands %S --out %D"},
    {"irreducibility/reduction_train.tsv", "irreducibility-reduction --stands %S --out %D"},
    {"main/baselines.tsv", "main-baselines --scale full --out %D/main/baselines.tsv"},
    {"field/calibration.tsv", "field-calibrate --out %D/field/calibration.tsv"},
    {"field/heldout.tsv", "field-heldout --calibration %D/field/calibration.tsv --stands %F --out %D/field/heldout.tsv"},
    {"anisotropy/lattice.tsv", "anisotropy-lattice --calibration %D/field/calibration.tsv --stands %F --out %D/anisotropy/lattice.tsv"},
    {"anisotropy/hardcore.tsv", "anisotropy-hardcore --calibration %D/field/calibration.tsv --stands %W --out %D/anisotropy/hardcore.tsv"},
    {"anisotropy/jitter.tsv", "anisotropy-jitter --calibration %D/field/calibration.tsv --stands %W --out %D/anisotropy/jitter.tsv"},
    {"anisotropy/jitter_calibration.tsv", "!anisotropy-jitter-calibrate --sweep %D/anisotropy/jitter.tsv --out %D/anisotropy/jitter_calibration.tsv"},
    {"anisotropy/heldout.tsv", "anisotropy-heldout --calibration %D/field/calibration.tsv --jitter-calibration %D/anisotropy/jitter_calibration.tsv --stands %F --out %D/anisotropy/heldout.tsv"},
    {"irreducibility/perturb_field.tsv", "irreducibility-perturb --stands %S --beta %B --tag field --out %D"},
    {"irreducibility/refine_field.tsv", "irreducibility-refine --stands %S --beta %B --tag field --out %D"},
    {"irreducibility/reduction_field.tsv", "irreducibility-reduction --stands %S --beta %B --tag field --out %D"},
};
#define NSTEPS (sizeof STEPS / sizeof STEPS[0])

typedef struct { const char *dir, *vary; long stands, field_stands, sweep_stands; char beta[40]; } sens_ctx;

/* Expand a step's command into argv (words separated by spaces; no word
 * holds one). A leading '!' marks a command without --vary (a pure
 * computation on tables of the unit). buf holds the words. */
static int expand(const sens_ctx *x, const char *tmpl, char *buf, size_t bn, char **argv, int maxv)
{
    int novary = tmpl[0] == '!';
    size_t o = (size_t)snprintf(buf, bn, "crownshy ");
    for (const char *p = tmpl + novary; *p && o + 1 < bn; p++) {
        if (*p != '%') { buf[o++] = *p; continue; }
        p++;
        char num[32];
        const char *s = *p == 'D' ? x->dir : *p == 'B' ? x->beta : num;
        long v = *p == 'S' ? x->stands : *p == 'F' ? x->field_stands : x->sweep_stands;
        snprintf(num, sizeof num, "%ld", v);
        o += (size_t)snprintf(buf + o, bn - o, "%s", s);
    }
    if (x->vary && !novary) o += (size_t)snprintf(buf + o, bn - o, " --vary %s", x->vary);
    buf[o < bn ? o : bn - 1] = '\0';
    int n = 0;
    for (char *t = strtok(buf, " "); t && n < maxv - 1; t = strtok(NULL, " ")) argv[n++] = t;
    argv[n] = NULL;
    return n;
}

static int exists(const char *path) { struct stat sb; return stat(path, &sb) == 0 && S_ISREG(sb.st_mode); }

/* DIR/unit.tsv: where each table of the variant lives (this folder or the centre's). */
/* failed[i]: the reason step i could not be built ("" when it was, or was
 * not run); DIR/unit.tsv records it, and the summary reports the numbers
 * of that table as not computable with the reason. */
static cs_status write_unit(const sens_ctx *x, const unstated_choice *c, double value, char failed[][300], int argc,
                            char **argv)
{
    char path[600];
    snprintf(path, sizeof path, "%s/unit.tsv", x->dir);
    tsv_writer *w;
    cs_status st = tsv_writer_open(&w, path);
    if (st) return st;
    prov p;
    prov_begin(&p, "sensitivity", argc, argv);
    snprintf(p.seeds, sizeof p.seeds, "those of each table's experiment (the full run's seeds)");
    p.worst_overlap_m = -1;
    if ((st = prov_write(w, &p))) { tsv_writer_abort(w); return st; }
    tsv_writer_meta(w, "what",
                    "one sensitivity unit (design.md §7 E0): %s; folder = where the variant's table lives (here, or "
                    "the centre run's: the choice cannot change it)",
                    c ? c->what : "the centre run (every choice the design's)");
    if (c) tsv_writer_meta(w, "choice", "%s = %.17g (ours %.17g)", c->name, value, c->ours);
    tsv_writer_meta(
        w, "stands",
        "E1/E2 %ld per cell (the full run: 8), E5/E6 %ld held-out and %ld per sweep level (as the full run)", x->stands,
        x->field_stands, x->sweep_stands);
    tsv_writer_meta(
        w, "failed",
        "a table the unit's stands could not be built for (the teacher refuses overlapping starting crowns; an E6 tree "
        "with an empty cardinal cone): a finding of that choice, its numbers not computable");
    tsv_writer_columns(w, "table\tfolder\tnote");
    for (size_t i = 0; i < NSTEPS; i++) {
        tsv_writer_str(w, STEPS[i].target);
        tsv_writer_str(w, failed[i][0]                                 ? "failed"
                          : !c || unstated_touches(c, STEPS[i].target) ? "here"
                                                                       : UNSTATED_CENTRE);
        tsv_writer_str(w, failed[i][0] ? failed[i] : "-");
        tsv_writer_endrow(w);
    }
    return tsv_writer_commit(w);
}

/* "centre" (c = NULL) or "<choice>_<value>" with value one of the choice's (%g). */
static int parse_unit(const char *unit, const unstated_choice **c, double *value)
{
    *c = NULL;
    if (!strcmp(unit, UNSTATED_CENTRE)) return 0;
    size_t nc;
    const unstated_choice *cl = unstated_list(&nc);
    for (size_t i = 0; i < nc; i++)
        for (int k = 0; k < cl[i].nvalues; k++) {
            char d[64];
            unstated_dirname(&cl[i], cl[i].values[k], d, sizeof d);
            if (!strcmp(d, unit)) { *c = &cl[i]; *value = cl[i].values[k]; return 0; }
        }
    return -1;
}

/* The beta_field of a unit's own calibration into x->beta (the %B of a step). */
static cs_status unit_beta(sens_ctx *x)
{
    char cal[600];
    fs_calibration fc;
    snprintf(cal, sizeof cal, "%s/field/calibration.tsv", x->dir);
    cs_status st = fs_beta_field(cal, &fc);
    if (!st) snprintf(x->beta, sizeof x->beta, "%.17g", fc.value);
    return st;
}

cs_status exp_sensitivity_run(const exp_sensitivity_args *a)
{
    const unstated_choice *c;
    double value = 0.0;
    if (parse_unit(a->unit, &c, &value))
        return cs_err(CS_EUSAGE, "--unit: no unit '%s' (centre or <choice>_<value>, see --help)", a->unit);
    sens_ctx x = {.dir = a->out, .stands = a->stands, .field_stands = a->field_stands, .sweep_stands = a->sweep_stands};
    char vary[64];
    if (c) { snprintf(vary, sizeof vary, "%s=%.17g", c->name, value); x.vary = vary; }
    static char failed[NSTEPS][300];
    memset(failed, 0, sizeof failed);
    for (size_t i = 0; i < NSTEPS; i++) {
        char path[600];
        snprintf(path, sizeof path, "%s/%s", a->out, STEPS[i].target);
        if ((c && !unstated_touches(c, STEPS[i].target)) || exists(path)) continue;
        /* a step reading a table that could not be built cannot be built either */
        for (size_t j = 0; j < i && !failed[i][0]; j++)
            if (failed[j][0] && (strstr(STEPS[i].cmd, STEPS[j].target) ||
                                 (strstr(STEPS[i].cmd, "%B") && !strcmp(STEPS[j].target, "field/calibration.tsv"))))
                snprintf(failed[i], sizeof failed[i], "needs %s, not buildable under this choice", STEPS[j].target);
        if (failed[i][0]) continue;
        if (strstr(STEPS[i].cmd, "%B")) {
            cs_status st = unit_beta(&x);
            if (st) return st;
        }
        char buf[1600], *av[48];
        int n = expand(&x, STEPS[i].cmd, buf, sizeof buf, av, 48);
        fprintf(stderr, "sensitivity-run %s: step %zu of %zu: %s\n", a->unit, i + 1, NSTEPS, STEPS[i].target);
        cs_errclear();
        int rc = a->run(n, av);
        /* a stand the choice cannot build (exit 3, bad input) or a statistic it
         * leaves undefined (exit 4 from the E6 cone check) is a finding of the
         * choice: recorded, the other steps still run; anything else stops */
        if (rc == 3 || rc == 4) {
            snprintf(failed[i], sizeof failed[i], "exit %d: %.260s", rc, cs_errmsg()[0] ? cs_errmsg() : "see the log");
            for (char *q = failed[i]; *q; q++) if (*q == '\t' || *q == '\n') *q = ' ';
            fprintf(stderr, "crownshy sensitivity-run: step %s not buildable under %s: %s (recorded)\n",
                    STEPS[i].target, a->unit, failed[i]);
        } else if (rc) return cs_err(rc == 1 ? CS_EFAIL : CS_EUSAGE, "step %s failed (exit %d)", STEPS[i].target, rc);
    }
    return write_unit(&x, c, value, failed, a->argc, a->argv);
}
