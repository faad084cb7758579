/* verify: the `make verify` driver and `crownshy trace` (design.md §9). */
#include "verify.h"
#include "audit_render.h"
#include "agree.h"
#include "attrib.h"
#include "study.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <errno.h>
#include <unistd.h>
#include "afile.h"
#include "audit_data.h"
#include "audit_evidence.h"
#include "audit_docs.h"
#include "figcheck.h"
#include "spot.h"

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
        snprintf(msg, n, "%s: paper/numbers.tex:%d says '%s' but %s gives '%s'", row->macro, line, have, res->where,
                 want);
        return VERDICT_FAIL;
    }
    if (strcmp(row->gate, "-")) {
        char gname[96];
        snprintf(gname, sizeof gname, "%sGate", row->macro);
        const char *gv = numbers_get(nt, gname, &line);
        if (!gv || strcmp(gv, verdict_name(res->gate))) {
            snprintf(msg, n, "%s: paper/numbers.tex:%d states gate %s as '%s' but %s judges it %s (%s)", row->macro,
                     line, row->gate, gv ? gv : "(missing)", row->source, verdict_name(res->gate), res->gate_detail);
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
        snprintf(msg, n, "%s = %s fails its preregistered gate %s: %s (%s)", row->macro, res->text, row->gate,
                 res->gate_detail, row->source);
        return VERDICT_FAIL;
    }
    return v;
}

cs_status verify_load_eval(claims *c, claim_result **res)
{
    cs_status st = claims_registry(c);
    if (st) return st;
    if ((st = verify_eval_all(c, res))) claims_free(c);
    return st;
}

cs_status verify_preflight(void)
{
    /* the write-up is read as TeX renders it: its renderer is a dependency */
    if (!render_tools_present())
        return cs_err(CS_EIO, "pdflatex or pdftotext not found: the audit renders the write-up (an environment error); "
                              "install them: sudo apt-get install -y " RENDER_DEBS " (make verify does so as root)");
    char d[64];
    snprintf(d, sizeof d, "build/preflight.%ld", (long)getpid());
    if ((mkdir("build", 0777) && errno != EEXIST) || mkdir(d, 0777))
        return cs_err(CS_EIO,
                      "build/: cannot create %s (%s): the fresh generation and the figure redraws need a writable "
                      "build/ (an environment error)",
                      d, strerror(errno));
    /* a file written and synced: a file-size limit or a full disk shows here,
     * not later as a generated file that "differs" */
    char f[96], block[65536];
    snprintf(f, sizeof f, "%s/probe", d);
    memset(block, 0, sizeof block);
    FILE *fp = fopen(f, "wb");
    int ok = fp && fwrite(block, 1, sizeof block, fp) == sizeof block;
    int err = errno;
    if (fp) {
        ok = fflush(fp) == 0 && ok;
        err = ok ? 0 : errno;
        ok = fsync(fileno(fp)) == 0 && ok;
        if (fclose(fp)) ok = 0;
    }
    unlink(f);
    rmdir(d);
    if (!ok)
        return cs_err(CS_EIO,
                      "build/: cannot write a file of %zu bytes into %s (%s): the fresh generation and the redraws "
                      "need a writable build/ (an environment error)",
                      sizeof block, d, strerror(err ? err : EIO));
    return CS_OK;
}

/* A claim that cannot be computed from an input the user supplied (FIELD_TABLE,
 * CHM): an input error of this run, not an inconsistency of the package. */
static int external_input_failed(const claim_row *row, const claim_result *res)
{
    if (res->status != VERDICT_FAIL || strcmp(row->kind, "needs-data")) return 0;
    const char *env[] = {"FIELD_TABLE", "CHM"};
    for (int k = 0; k < 2; k++) {
        const char *v = getenv(env[k]);
        if (v && v[0] && strstr(res->why, v)) return 1;
    }
    return 0;
}

cs_status verify_external_inputs(const claims *c, const claim_result *res, const char *who)
{
    size_t bad = 0;
    for (size_t i = 0; i < c->n; i++)
        if (external_input_failed(&c->rows[i], &res[i])) {
            fprintf(stderr, "crownshy %s: %s: %s\n", who, c->rows[i].macro, res[i].why);
            bad++;
        }
    return bad ? cs_err(CS_EINPUT,
                        "%zu claim(s) cannot be computed from the input given (FIELD_TABLE, CHM): a bad input, not an "
                        "inconsistency of the package",
                        bad)
               : CS_OK;
}

/* What the gated claims say about the reference paper, tallied by print_claims. */
/* ext*: [0] the extension's claims, [1] the variants' (claims_kind_beside) */
typedef struct {
    size_t rep, notrep, gpend;
    char notrep_list[1024];
    size_t ext[2][3];
    char ext_fail[2][512], ext_src[2][512];
} gate_tally;

/* An extension claim's gate (design.md §8): tallied apart from the reference
 * paper's, with the frozen tables it rests on. */
static void tally_extension(const claim_row *row, const claim_result *r, verdict v, gate_tally *t)
{
    const int b = strcmp(row->kind, "extension") != 0;
    int k = v == VERDICT_FAIL || r->gate == VERDICT_PENDING ? 2 : r->gate == VERDICT_PASS ? 0 : 1;
    t->ext[b][k]++;
    if (k == 1) {
        size_t l = strlen(t->ext_fail[b]);
        snprintf(t->ext_fail[b] + l, sizeof t->ext_fail[b] - l, "%s%s", l ? ", " : "", row->macro);
    }
    char dir[300];
    const char *slash = strrchr(row->source, '/');
    snprintf(dir, sizeof dir, "%.*s/", slash ? (int)(slash - row->source) : 0, row->source);
    if (!strstr(t->ext_src[b], dir)) {
        size_t l = strlen(t->ext_src[b]);
        snprintf(t->ext_src[b] + l, sizeof t->ext_src[b] - l, "%s%s", l ? ", " : "", dir);
    }
}

/* One line per claim: consistent or not, and its gate's verdict (a table
 * made by a superseded reading is pending, never reproduced nor not). */
static void print_claims(const claims *c, const claim_result *res, const numbers_tex *nt, const attrib_data *at,
                         const claim_interval *ci, size_t count[3], gate_tally *t)
{
    for (size_t i = 0; i < c->n; i++) {
        char msg[1200];
        verdict v = verify_consistent(&c->rows[i], &res[i], nt, msg, sizeof msg);
        /* the interval recomputed from its replicates, against the generated table */
        if (v != VERDICT_FAIL && ci[i].why[0] && !strncmp(ci[i].why, "interval error: ", 16)) {
            v = VERDICT_FAIL;
            snprintf(msg, sizeof msg, "%s: %s", c->rows[i].macro, ci[i].why);
        } else if (v != VERDICT_FAIL && res[i].status == VERDICT_PASS) {
            char imsg[1200];
            if (agree_check_interval(PATHS_INTERVALS_OUT, &c->rows[i], &ci[i], imsg, sizeof imsg) == VERDICT_FAIL) {
                v = VERDICT_FAIL;
                snprintf(msg, sizeof msg, "%s", imsg);
            }
        }
        int gated = strcmp(c->rows[i].gate, "-") != 0;
        const char *label = verdict_name(v);
        const int ext = gated && claims_is_beside(&c->rows[i]);
        /* a table made by a superseded reading: its numbers are that reading's
         * until re-run; never counted as reproduced (nor as not reproduced) */
        if (v != VERDICT_FAIL && !strncmp(c->rows[i].source, PATHS_FROZEN_DIR "/", strlen(PATHS_FROZEN_DIR) + 1) &&
            audit_table_superseded(c->rows[i].source)) {
            v = VERDICT_PENDING;
            label = "PENDING";
            snprintf(msg, sizeof msg, "%s was made by a superseded reading (%s): pending until its unit is re-run",
                     c->rows[i].source, PATHS_PINS_SUPERSEDED);
            if (gated) t->gpend++;
            gated = 0;
        }
        if (ext) {
            tally_extension(&c->rows[i], &res[i], v, t);
            if (v != VERDICT_FAIL && res[i].gate == VERDICT_FAIL) {
                label = "NOTMET";
                snprintf(msg, sizeof msg,
                         "%s = %s: this reading beside the verdict does not meet the threshold of %s: %s (%s); "
                         "numbers.tex states FAIL",
                         c->rows[i].macro, res[i].text, c->rows[i].gate, res[i].gate_detail, c->rows[i].source);
            }
        } else if (gated && v != VERDICT_FAIL) {
            if (res[i].gate == VERDICT_PASS) t->rep++;
            else if (res[i].gate == VERDICT_FAIL) {
                t->notrep++;
                size_t l = strlen(t->notrep_list);
                snprintf(t->notrep_list + l, sizeof t->notrep_list - l, "%s%s", l ? ", " : "", c->rows[i].macro);
                /* consistent: the write-up states this very verdict */
                label = "NOTREP";
                snprintf(
                    msg, sizeof msg,
                    "%s = %s does not reproduce: fails its preregistered gate %s: %s (%s); numbers.tex states FAIL",
                    c->rows[i].macro, res[i].text, c->rows[i].gate, res[i].gate_detail, c->rows[i].source);
            } else t->gpend++;
        }
        const char *val = res[i].status == VERDICT_PASS ? res[i].text : "-";
        const char *g = gated ? verdict_name(res[i].gate) : "-";
        double ref, rel;
        char dist[400] = "";
        if (claims_rel_diff(&c->rows[i], &res[i], &ref, &rel))
        {
            attrib_result ar;
            attrib_judge(at, &c->rows[i], &res[i], &ar);
            agree_result ag;
            agree_judge(at, &c->rows[i], &res[i], &ci[i], &ag);
            snprintf(dist, sizeof dist, " [paper %s: %+.1f %%%s%.160s; %s%s%.120s]", c->rows[i].reference, 100.0 * rel,
                     ar.kind == ATTRIB_EXPLAINED     ? "; reached by "
                     : ar.kind == ATTRIB_UNEXPLAINED ? "; unexplained"
                     : ar.kind == ATTRIB_UNTESTED    ? "; unexplained, not varied"
                                                     : "",
                     ar.kind == ATTRIB_EXPLAINED ? ar.by : "", agree_name(ag.kind), ag.by[0] ? ": " : "", ag.by);
        }
        const char *iv = !strcmp(c->rows[i].kind, "measured") || claims_kind_beside(c->rows[i].kind)
                             ? (ci[i].has ? ci[i].text : "none")
                             : "-";
        printf("  %-7s %-19s %-12s %-22s %-10s %-8s %s%s\n", label, c->rows[i].macro, val, iv, c->rows[i].kind, g, msg,
               dist);
        count[v]++;
    }
}

/* The summary's pending count, distance to the paper and agreement lines. */
static void print_distance(const attrib_data *at, const claims *c, const claim_result *res, const claim_interval *ci,
                           size_t pending)
{
    attrib_counts ak;
    attrib_count(at, c, res, &ak);
    agree_counts gk;
    agree_count(at, c, res, ci, &gk);
    char aline[600], gline[800];
    attrib_line(&ak, 0, aline, sizeof aline);
    agree_line(&gk, 0, gline, sizeof gline);
    printf("\n%zu pending (input data missing on this machine, or a reading's units not yet frozen: reason above; "
           "never counted as passed)\n",
           pending);
    printf("%s (distance, not a verdict)\n", aline);
    printf("%s\n", gline);
}

/* The summary's gate lines: the reference paper's gated claims, then each
 * kind of claim judged beside the verdict by the same thresholds, when it has any. */
static void print_gates(const gate_tally *t)
{
    printf("reference paper's gated claims: %zu reproduced, %zu not reproduced%s%s%s, %zu pending\n", t->rep,
           t->notrep, t->notrep ? " (" : "", t->notrep_list, t->notrep ? ")" : "", t->gpend);
    static const char *const beside[2] = {
        "extension claims (a generator reading added after the first verdict, design.md §8",
        "variant claims (the paper reading under one unstated training choice, at the gate's seeds, design.md §8"};
    for (int b = 0; b < 2; b++)
        if (t->ext[b][0] + t->ext[b][1] + t->ext[b][2])
            printf("%s; same thresholds, %s): %zu meet, %zu do not%s%s%s, %zu pending; tables: %s\n", beside[b],
                   PATHS_GATE_MAP_EXT, t->ext[b][0], t->ext[b][1], t->ext[b][1] ? " (" : "", t->ext_fail[b],
                   t->ext[b][1] ? ")" : "", t->ext[b][2], t->ext_src[b]);
}

/* The last lines: the package's verdict and the count; CS_EFAIL on an
 * inconsistency or (strict_notrep > 0) a failing gate under --strict. A run
 * that ran out of memory proved nothing either way: an environment error. */
static cs_status print_verdict(const size_t count[3], size_t strict_notrep)
{
    if (cs_nomem_count()) {
        printf("environment: out of memory %zu time(s) during the checks: the package was not checked (an environment "
               "error, not an inconsistency)\n",
               cs_nomem_count());
        return cs_err(CS_ENOMEM, "out of memory during the checks (%zu time(s)): an environment error",
                      cs_nomem_count());
    }
    if (count[VERDICT_FAIL])
        printf("package: INCONSISTENT: %zu check(s) failed: a number, verdict, table, figure or sentence does not "
               "follow from frozen/ and the pinned code\n",
               count[VERDICT_FAIL]);
    else
        printf("package: consistent: every number, verdict, table, figure and sentence follows from frozen/ and the "
               "pinned code\n");
    if (strict_notrep) printf("--strict: %zu preregistered gate(s) not reproduced\n", strict_notrep);
    printf("%zu passed, %zu failed\n", count[VERDICT_PASS], count[VERDICT_FAIL] + strict_notrep);
    return count[VERDICT_FAIL] || strict_notrep ? CS_EFAIL : CS_OK;
}

cs_status verify_run(const verify_opts *o)
{
    claims c;
    claim_result *res;
    cs_status st = verify_preflight();
    if (st) return st;
    /* the history as committed: a git replace ref does not stand in for a commit */
    setenv("GIT_NO_REPLACE_OBJECTS", "1", 1);
    if (!o->no_figures) spot_launch(o->spot_seed);
    if (!o->no_figures) figcheck_launch();
    if ((st = verify_load_eval(&c, &res))) { figcheck_wait(); return st; }
    if ((st = verify_external_inputs(&c, res, "verify"))) { figcheck_wait(); free(res); claims_free(&c); return st; }
    /* a claim that could not be computed for want of memory or a working disk
     * is no inconsistency of the results: the run stops as an environment error */
    for (size_t i = 0; i < c.n && !st; i++)
        if (res[i].status == VERDICT_FAIL && (res[i].err == CS_ENOMEM || res[i].err == CS_EIO))
            st = cs_err(res[i].err, "%s could not be computed (%s): an environment error, not an inconsistency",
                        c.rows[i].macro, res[i].why);
    if (st) { figcheck_wait(); free(res); claims_free(&c); return st; }
    numbers_tex nt;
    int have_nt = numbers_read(PATHS_NUMBERS, &nt) == CS_OK;
    char nterr[512];
    snprintf(nterr, sizeof nterr, "%s", have_nt ? "" : cs_errmsg());

    size_t count[3] = {0}; /* consistency checks by verdict: PASS, FAIL, PENDING */
    checklist cl = {0};
    char prereg_line[700];
    audit_run(&c, res, &cl);
    audit_docs(&c, res, &cl);
    audit_prereg_anchor(&cl, o->prereg, prereg_line, sizeof prereg_line);
    printf("== audit (pins, frozen hashes and provenance, aggregates, registry and gate map, generated and written "
           "paper)\n");
    checklist_print(&cl, count);
    checklist_free(&cl);

    printf("\n== claims (recomputed from frozen/ and compared with paper/numbers.tex; a failing gate is a finding: "
           "NOTREP)\n");
    printf("  %-7s %-19s %-12s %-22s %-10s %-8s %s\n", "status", "macro", "value", "95 % interval", "kind", "gate",
           "source / reason");
    if (!have_nt) { printf("  FAIL    paper/numbers.tex unreadable: %s\n", nterr); count[VERDICT_FAIL]++; }
    gate_tally gt = {0};
    /* the attribution of each difference (attrib.h), from the frozen summaries */
    attrib_data at = {0};
    int at_ok = attrib_load(PATHS_READINGS_SUMMARY, PATHS_SENS_SUMMARY, &at) == CS_OK;
    const claim_interval *ci = NULL;
    cs_status ist = agree_intervals_cached(&c, res, &ci);
    if (ist) printf("  FAIL    intervals: %s\n", cs_errmsg());
    if (ist) count[VERDICT_FAIL]++;
    if (at_ok && ci) attrib_bind(&at, &c, res, ci);
    print_claims(&c, res, have_nt ? &nt : NULL, &at, ci, count, &gt);

    if (!o->no_figures) {
        checklist fl = {0};
        figcheck_verify(&fl, 0, &c);
        spot_check(&fl, &c);
        printf("\n== redraws (a random slice of one generator unit from its weights; every figure by gnuplot into "
               "build/)\n");
        if (!fl.n) printf("  (no figure scripts yet)\n");
        checklist_print(&fl, count);
        checklist_free(&fl);
    }
    printf("\n== ledger (pinned files changed after the commit that added the preregistered gates)\n");
    audit_ledger(stdout);

    if (!at_ok) printf("(attribution: %s)\n", cs_errmsg());
    print_distance(&at, &c, res, ci, count[VERDICT_PENDING]);
    attrib_free(&at);
    print_gates(&gt);
    printf("%s\n", prereg_line);
    st = print_verdict(count, o->strict ? gt.notrep : 0);
    if (have_nt) numbers_free(&nt);
    free(res);
    claims_free(&c);
    return st;
}

cs_status verify_trace(const char *macro)
{
    claims c;
    cs_status st = claims_registry(&c);
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
    printf("value        %s%s%s\n", r.status == VERDICT_PASS ? r.text : verdict_name(r.status),
           r.status == VERDICT_PASS ? "" : ": ", r.status == VERDICT_PASS ? "" : r.why);
    printf("numbers.tex  %s (paper/numbers.tex:%d)\n", have ? have : "(absent)", line);
    printf("source       %s\n", r.where);
    char fpath[512];
    int fline = 0;
    if (claims_function_file(row->function, fpath, sizeof fpath, &fline))
        printf("function     %s (%s)\n", row->function, cs_errmsg());
    else printf("function     %s (%s:%d)\n", row->function, fpath, fline);
    char params[256];
    claim_params_format(&row->param, params, sizeof params);
    printf("params       %s\n", params);
    const study_experiment *ex = study_of_path(row->source);
    if (ex) printf("experiment   %s (%s): %s; run by %s\n", ex->name, ex->code, ex->what, ex->source);
    printf("gate         %s%s%s%s\n", row->gate, strcmp(row->gate, "-") ? " -> " : "",
           strcmp(row->gate, "-") ? verdict_name(r.gate) : "", r.gate_detail[0] ? "" : "");
    if (r.gate_detail[0]) printf("gate detail  %s\n", r.gate_detail);
    printf("test         %s (alone: make test-claim MACRO=%s)\n", row->test, row->macro);
    printf("section      %s of the reference paper (reference value %s)\n", row->section, row->reference);
    if (claims_table_where(row, fpath, sizeof fpath, &fline))
        printf("table        %s (%s)\n", row->table ? row->table : "-", cs_errmsg());
    else printf("table        %s (%s:%d)\n", row->table ? row->table : "-", fpath, fline);
    printf("registry     %s:%d (the tables' print)\n", PATHS_CLAIMS, row->line);
    if (have) numbers_free(&nt);
    claims_free(&c);
    /* a claim its input keeps from being computed: the command exits by that kind */
    if (r.status == VERDICT_FAIL && r.err) return cs_err(r.err, "%s: %s", macro, r.why);
    return CS_OK;
}
