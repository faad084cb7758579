/* audit_paper: the generated write-up against frozen/ (design.md §9):
 * numbers.tex, comparison.tex and readings.tex must equal a fresh generation.
 * The hand-written text is read by audit_tex.c. */
#include "audit_paper.h"
#include "afile.h"
#include "agree.h"
#include "attrib.h"
#include "model_readings.h"
#include "readings.h"
#include "sens.h"
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *const generated[] = {PATHS_NUMBERS,  PATHS_CONSTANTS_TEX, PATHS_COMPARISON,  PATHS_READINGS_TEX,
                                        PATHS_SENS_TEX, PATHS_INTERVALS_OUT, PATHS_SUMMARY_TEX, NULL};

const char *paper_generated(size_t i)
{
    return i < sizeof generated / sizeof *generated ? generated[i] : NULL;
}

int paper_is_generated(const char *path)
{
    for (int i = 0; generated[i]; i++) if (!strcmp(path, generated[i])) return 1;
    return 0;
}

/* The sensitivity table (design.md §7 E0), checked against its unit tables. */
static cs_status sens_generate(const claims *c, const char *dir, int *made)
{
    struct stat sb;
    *made = 0;
    if (stat(PATHS_SENS_SUMMARY, &sb) != 0) return CS_OK;
    size_t n = sens_count();
    sens_row *rows = calloc(n, sizeof *rows);
    cs_status st = rows ? sens_compute(c, PATHS_SENS_DIR, rows) : cs_err(CS_ENOMEM, "out of memory");
    if (!st) st = sens_check(PATHS_SENS_SUMMARY, rows, n);
    char p[512];
    snprintf(p, sizeof p, "%s/sensitivity.tex", dir);
    if (!st) st = sens_write_tex(p, rows, n);
    free(rows);
    *made = !st;
    return st;
}

cs_status paper_generate(const claims *c, const claim_result *res, const char *dir, int *readings)
{
    char p[512];
    snprintf(p, sizeof p, "%s/numbers.tex", dir);
    cs_status st = claims_write_numbers(p, c, res, 0);
    snprintf(p, sizeof p, "%s/constants.tex", dir);
    if (!st) st = audit_write_constants(p, 0);
    struct stat sb;
    *readings = 0;
    if (!st && stat(PATHS_READINGS_SUMMARY, &sb) == 0) {
        size_t nr = readings_count();
        readings_row *rows = calloc(nr, sizeof *rows);
        st = rows ? readings_compute(c, PATHS_READINGS_DIR, rows) : cs_err(CS_ENOMEM, "out of memory");
        if (!st) st = readings_check(PATHS_READINGS_SUMMARY, rows, nr);
        snprintf(p, sizeof p, "%s/readings.tex", dir);
        if (!st) st = readings_write_tex(p, rows, nr);
        free(rows);
        *readings = !st;
    }
    /* the generator readings table (design.md §8), when frozen, against its
     * readings' frozen per-run summaries */
    if (!st && stat(PATHS_MODEL_READINGS_SUMMARY, &sb) == 0) {
        model_readings_row mr[4];
        size_t nm = 0;
        st = model_readings_compute(PATHS_FROZEN_DIR, mr, &nm);
        if (!st) st = model_readings_check(PATHS_MODEL_READINGS_SUMMARY, mr, nm);
    }
    int sens = 0;
    if (!st) st = sens_generate(c, dir, &sens);
    if (sens) *readings |= 2;
    /* the comparison last: its attribution column reads the two summaries just checked */
    attrib_data at = {0};
    if (!st) st = attrib_load(PATHS_READINGS_SUMMARY, PATHS_SENS_SUMMARY, &at);
    const claim_interval *ci = NULL;
    if (!st) st = agree_intervals_cached(c, res, &ci);
    if (!st) attrib_bind(&at, c, res, ci);
    snprintf(p, sizeof p, "%s/intervals.tsv", dir);
    if (!st) st = agree_write_intervals(p, c, ci);
    snprintf(p, sizeof p, "%s/summary.tex", dir);
    if (!st) st = agree_write_summary(p, c, res, ci, &at);
    snprintf(p, sizeof p, "%s/comparison.tex", dir);
    if (!st) st = agree_write_comparison(p, c, res, &at, ci);
    attrib_free(&at);
    return st;
}

/* First differing line of a and b (0: equal); *missing when b is absent. */
static int first_diff(const char *a, const char *b, char *lb, size_t n, int *missing)
{
    FILE *fa = fopen(a, "r"), *fb = fopen(b, "r");
    *missing = !fb;
    lb[0] = '\0';
    int lineno = 0, diff = 0;
    char la[4096], bb[4096];
    while (fb) {
        char *ra = fa ? fgets(la, sizeof la, fa) : NULL, *rb = fgets(bb, sizeof bb, fb);
        lineno++;
        if (!ra && !rb) break;
        if (!ra || !rb || strcmp(la, bb)) {
            diff = lineno;
            if (rb) snprintf(lb, n, "%.*s", (int)strcspn(bb, "\n"), bb);
            break;
        }
    }
    if (fa) fclose(fa);
    if (fb) fclose(fb);
    return *missing ? 1 : diff;
}

static void rmdir_fresh(const char *dir)
{
    char p[512];
    for (int i = 0; generated[i]; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, strrchr(generated[i], '/') + 1);
        unlink(p);
    }
    rmdir(dir);
}

void paper_line_claim(const claims *c, const char *line, char *out, size_t n)
{
    static const char gate[] = "Gate"; /* numbers.tex writes a claim's verdict as \<claim>Gate */
    out[0] = '\0';
    for (const char *p = line; *p && !out[0];) {
        size_t w = 0;
        while (isalnum((unsigned char)p[w])) w++;
        if (!w) { p++; continue; }
        char word[128];
        snprintf(word, sizeof word, "%.*s", (int)w, p);
        const claim_row *row = claims_find(c, word);
        size_t g = sizeof gate - 1;
        if (!row && w > g && !strcmp(word + w - g, gate)) {
            word[w - g] = '\0';
            row = claims_find(c, word);
        }
        if (row) snprintf(out, n, "%s", row->macro);
        p += w;
    }
}

void audit_generated(const claims *c, const claim_result *res, checklist *cl, int only_numbers)
{
    char dir[128];
    snprintf(dir, sizeof dir, "build/fresh.%ld", (long)getpid());
    int readings = 0;
    if (paper_generate(c, res, dir, &readings)) {
        checklist_add(cl, VERDICT_FAIL, "generated paper files", "cannot generate them from frozen/: %s", cs_errmsg());
        rmdir_fresh(dir);
        return;
    }
    for (int i = 0; generated[i]; i++) {
        if (only_numbers && i) break;
        const char *name = strrchr(generated[i], '/') + 1;
        char fresh[256], item[64], lb[4096];
        snprintf(fresh, sizeof fresh, "%s/%s", dir, name);
        snprintf(item, sizeof item, "%s", name);
        struct stat sb;
        if (stat(fresh, &sb) != 0) {
            if (stat(generated[i], &sb) == 0)
                checklist_add(cl, VERDICT_FAIL, item, "%s exists but nothing generates it (%s absent)", generated[i],
                              PATHS_READINGS_SUMMARY);
            continue;
        }
        int missing, d = first_diff(fresh, generated[i], lb, sizeof lb, &missing);
        if (missing)
            checklist_add(cl, VERDICT_FAIL, item, "%s missing (generate it with crownshy numbers)", generated[i]);
        else if (d) {
            /* name the claim on the differing line when there is one */
            char name[64], claim[80] = "";
            paper_line_claim(c, lb, name, sizeof name);
            if (name[0]) snprintf(claim, sizeof claim, "; claim: %s", name);
            checklist_add(cl, VERDICT_FAIL, item,
                          "%s:%d differs from a fresh generation ('%.200s'): edited by hand or stale%s", generated[i],
                          d, lb, claim);
        } else checklist_add(cl, VERDICT_PASS, item, "%s equals a fresh generation from frozen/", generated[i]);
    }
    rmdir_fresh(dir);
}

