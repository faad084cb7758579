/* verify: the `make verify` driver and `crownshy trace` (SPEC §9). */
#include "verify.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>

cs_status verify_eval_all(const claims *c, claim_result **out)
{
    claim_result *res = calloc(c->n ? c->n : 1, sizeof *res);
    if (!res) return cs_err(CS_ENOMEM, "out of memory");
    for (size_t i = 0; i < c->n; i++) claims_eval(&c->rows[i], &res[i]);
    *out = res;
    return CS_OK;
}

verdict verify_consistent(const claim_row *row, const claim_result *res, const numbers_tex *nt, char *msg, size_t n)
{
    char want[256];
    claims_expected_text(row, res, want, sizeof want);
    int line = 0;
    const char *have = nt ? numbers_get(nt, row->macro, &line) : NULL;
    if (res->status == VERDICT_FAIL) {
        snprintf(msg, n, "%s: cannot recompute from %s: %s", row->macro, row->source, res->why);
        return VERDICT_FAIL;
    }
    if (!have) {
        snprintf(msg, n, "%s: \\%s missing from paper/numbers.tex", row->macro, row->macro);
        return VERDICT_FAIL;
    }
    if (strcmp(have, want)) {
        snprintf(msg, n, "%s: paper/numbers.tex:%d says '%s' but %s gives '%s'", row->macro, line, have, res->where, want);
        return VERDICT_FAIL;
    }
    if (strcmp(row->gate, "-")) {
        char gname[96];
        snprintf(gname, sizeof gname, "%sGate", row->macro);
        const char *gv = numbers_get(nt, gname, &line);
        if (!gv || strcmp(gv, verdict_name(res->gate))) {
            snprintf(msg, n, "%s: paper/numbers.tex:%d states gate %s as '%s' but %s judges it %s (%s)", row->macro, line,
                     row->gate, gv ? gv : "(missing)", row->source, verdict_name(res->gate), res->gate_detail);
            return VERDICT_FAIL;
        }
    }
    if (res->status == VERDICT_PENDING) {
        snprintf(msg, n, "%s", res->why);
        return VERDICT_PENDING;
    }
    snprintf(msg, n, "%s", res->where);
    return VERDICT_PASS;
}

verdict verify_claim(const claim_row *row, const claim_result *res, const numbers_tex *nt, char *msg, size_t n)
{
    verdict v = verify_consistent(row, res, nt, msg, n);
    if (v != VERDICT_FAIL && strcmp(row->gate, "-") && res->gate == VERDICT_FAIL) {
        snprintf(msg, n, "%s = %s fails its preregistered gate %s: %s (%s)", row->macro, res->text, row->gate, res->gate_detail, row->source);
        return VERDICT_FAIL;
    }
    return v;
}

static int has_gnuplot(void)
{
    return system("command -v gnuplot >/dev/null 2>&1") == 0;
}

void verify_figures(checklist *cl)
{
    paths_list gps;
    if (paths_list_files(PATHS_FIGURES_DIR, ".gp", 0, &gps)) { checklist_add(cl, VERDICT_FAIL, "figures", "%s", cs_errmsg()); return; }
    size_t n = gps.n;
    int gp = has_gnuplot();
    for (size_t i = 0; i < n; i++) {
        const char *script = gps.p[i], *base = script + strlen(PATHS_FIGURES_DIR) + 1;
        char item[96];
        snprintf(item, sizeof item, "figure %.*s", (int)(strlen(base) - 3), base);
        /* "# data: path" lines declare the inputs; a figure whose data are not frozen yet is pending */
        FILE *f = fopen(script, "r");
        char line[1024], missing[1100] = "";
        while (f && fgets(line, sizeof line, f)) {
            if (strncmp(line, "# data: ", 8)) continue;
            line[strcspn(line, "\n")] = '\0';
            struct stat sb;
            if (stat(line + 8, &sb) != 0 && !missing[0]) snprintf(missing, sizeof missing, "%s", line + 8);
        }
        if (f) fclose(f);
        if (missing[0]) { checklist_add(cl, VERDICT_PENDING, item, "needs %s (not frozen yet)", missing); continue; }
        if (!gp) { checklist_add(cl, VERDICT_FAIL, item, "gnuplot not installed (make deps)"); continue; }
        char cmd[1400];
        snprintf(cmd, sizeof cmd, "gnuplot '%s' > build/gnuplot-%s.log 2>&1", script, base);
        int rc = system(cmd);
        if (rc != 0) checklist_add(cl, VERDICT_FAIL, item, "gnuplot %s failed (see build/gnuplot-%s.log)", script, base);
        else checklist_add(cl, VERDICT_PASS, item, "redrawn by gnuplot %s", script);
    }
    paths_list_free(&gps);
}

cs_status verify_run(const verify_opts *o)
{
    claims c;
    cs_status st = claims_load(PATHS_CLAIMS, &c);
    if (st) return st;
    claim_result *res;
    if ((st = verify_eval_all(&c, &res))) { claims_free(&c); return st; }
    numbers_tex nt;
    int have_nt = numbers_read(PATHS_NUMBERS, &nt) == CS_OK;
    char nterr[512];
    snprintf(nterr, sizeof nterr, "%s", have_nt ? "" : cs_errmsg());

    size_t count[3] = {0}; /* by verdict: PASS, FAIL, PENDING */
    checklist cl = {0};
    audit_run(&c, res, &cl);
    printf("== audit (pins, frozen hashes, provenance, registry, paper)\n");
    checklist_print(&cl, count);
    checklist_free(&cl);

    printf("\n== claims (recomputed from frozen/ and compared with paper/numbers.tex)\n");
    printf("  %-7s %-19s %-12s %-10s %-8s %s\n", "status", "macro", "value", "kind", "gate", "source / reason");
    if (!have_nt) { printf("  FAIL    paper/numbers.tex unreadable: %s\n", nterr); count[VERDICT_FAIL]++; }
    for (size_t i = 0; i < c.n; i++) {
        char msg[1200];
        verdict v = verify_claim(&c.rows[i], &res[i], have_nt ? &nt : NULL, msg, sizeof msg);
        const char *val = res[i].status == VERDICT_PASS ? res[i].text : "-";
        const char *g = strcmp(c.rows[i].gate, "-") ? verdict_name(res[i].gate) : "-";
        double ref, rel;
        char dist[96] = "";
        if (claims_rel_diff(&c.rows[i], &res[i], &ref, &rel))
            snprintf(dist, sizeof dist, " [paper %s: %+.1f %%]", c.rows[i].reference, 100.0 * rel);
        printf("  %-7s %-19s %-12s %-10s %-8s %s%s\n", verdict_name(v), c.rows[i].macro, val, c.rows[i].kind, g, msg, dist);
        count[v]++;
    }

    if (!o->no_figures) {
        checklist fl = {0};
        verify_figures(&fl);
        printf("\n== figures (gnuplot)\n");
        if (!fl.n) printf("  (no figure scripts yet)\n");
        checklist_print(&fl, count);
        checklist_free(&fl);
    }
    printf("\n%zu pending (experiment not yet run and frozen, or input data missing: reason above; never counted as passed)\n", count[VERDICT_PENDING]);
    size_t m, a10, a25;
    claims_within(&c, res, &m, &a10, &a25);
    printf("%zu of %zu measured numbers within 10 %% / %zu within 25 %% of the reference paper (distance, not a verdict)\n", a10, m, a25);
    printf("%zu passed, %zu failed\n", count[VERDICT_PASS], count[VERDICT_FAIL]);
    if (have_nt) numbers_free(&nt);
    free(res);
    claims_free(&c);
    return count[VERDICT_FAIL] ? CS_EFAIL : CS_OK;
}

cs_status verify_trace(const char *macro)
{
    claims c;
    cs_status st = claims_load(PATHS_CLAIMS, &c);
    if (st) return st;
    const claim_row *row = claims_find(&c, macro[0] == '\\' ? macro + 1 : macro);
    if (!row) { claims_free(&c); return cs_err(CS_EINPUT, "%s: no claim named '%s'", PATHS_CLAIMS, macro); }
    claim_result r;
    claims_eval(row, &r);
    numbers_tex nt;
    int line = 0;
    const char *have = NULL;
    if (numbers_read(PATHS_NUMBERS, &nt) == CS_OK) have = numbers_get(&nt, row->macro, &line);
    printf("macro        \\%s\n", row->macro);
    printf("kind         %s\n", row->kind);
    printf("value        %s%s%s\n", r.status == VERDICT_PASS ? r.text : verdict_name(r.status), r.status == VERDICT_PASS ? "" : ": ", r.status == VERDICT_PASS ? "" : r.why);
    printf("numbers.tex  %s (paper/numbers.tex:%d)\n", have ? have : "(absent)", line);
    printf("source       %s\n", r.where);
    printf("function     %s (src/claim_*.c)\n", row->function);
    printf("gate         %s%s%s%s\n", row->gate, strcmp(row->gate, "-") ? " -> " : "", strcmp(row->gate, "-") ? verdict_name(r.gate) : "",
           r.gate_detail[0] ? "" : "");
    if (r.gate_detail[0]) printf("gate detail  %s\n", r.gate_detail);
    printf("test         %s\n", row->test);
    printf("section      %s of the reference paper (reference value %s)\n", row->section, row->reference);
    printf("registry     %s:%d\n", PATHS_CLAIMS, row->line);
    if (have) numbers_free(&nt);
    claims_free(&c);
    return CS_OK;
}
