/* cli_audit: the reviewer's and auditor's commands (SPEC §9): verify,
 * numbers, audit, trace, pin, hash-frozen, gates, check-tsv, figures. Only
 * the CLI decides how the process dies. */
#include "cli.h"
#include "audit.h"
#include "claims.h"
#include "gate.h"
#include "opts.h"
#include "paths.h"
#include "readings.h"
#include <sys/stat.h>
#include "tsv.h"
#include "verify.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int die(cs_status st)
{
    fprintf(stderr, "crownshy: %s\n", cs_errmsg()[0] ? cs_errmsg() : cs_status_name(st));
    return cs_exit_code(st);
}

int cli_cmd_verify(int argc, char **argv)
{
    verify_opts o = {0};
    const opt_spec spec[] = {{"no-figures", OPT_FLAG, &o.no_figures, 0, 0, "skip redrawing the figures"}};
    const opts_cmd oc = {"verify", "[--no-figures]",
                        "Audit pins and frozen hashes, recompute every claim of audit/claims.tsv from frozen/,\n"
                        "compare with paper/numbers.tex, judge every gate, redraw every figure, and print\n"
                        "'N passed, N failed'. Exit 1 if anything failed; pending claims are listed, not passed.",
                        spec, 1, 0, 0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = verify_run(&o);
    if (st && st != CS_EFAIL) return die(st);
    return cs_exit_code(st);
}

int cli_cmd_numbers(int argc, char **argv)
{
    int check = 0;
    const opt_spec spec[] = {{"check", OPT_FLAG, &check, 0, 0, "only compare paper/numbers.tex with a fresh generation"}};
    const opts_cmd oc = {"numbers", "[--check]", "Regenerate paper/numbers.tex and paper/comparison.tex from frozen/ (atomic).", spec, 1, 0, 0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    claims c;
    cs_status st = claims_load(PATHS_CLAIMS, &c);
    if (st) return die(st);
    claim_result *res;
    if ((st = verify_eval_all(&c, &res))) { claims_free(&c); return die(st); }
    if (check) {
        checklist cl = {0};
        audit_numbers(&c, res, &cl);
        int bad = 0;
        for (size_t i = 0; i < cl.n; i++) {
            printf("%s %s\n", verdict_name(cl.items[i].v), cl.items[i].msg);
            bad |= cl.items[i].v == VERDICT_FAIL;
        }
        checklist_free(&cl);
        free(res);
        claims_free(&c);
        return bad ? 1 : 0;
    }
    st = claims_write_numbers(PATHS_NUMBERS, &c, res);
    if (!st) st = claims_write_comparison(PATHS_COMPARISON, &c, res);
    /* the E0 readings table, recomputed from frozen/readings/ and checked against its summary */
    struct stat sb;
    if (!st && stat(PATHS_READINGS_SUMMARY, &sb) == 0) {
        size_t nr = readings_count();
        readings_row *rows = calloc(nr, sizeof *rows);
        st = rows ? readings_compute(&c, PATHS_READINGS_DIR, rows) : cs_err(CS_ENOMEM, "out of memory");
        if (!st) st = readings_check(PATHS_READINGS_SUMMARY, rows, nr);
        if (!st) st = readings_write_tex(PATHS_READINGS_TEX, rows, nr);
        free(rows);
    }
    size_t pend = 0;
    for (size_t i = 0; i < c.n; i++) pend += res[i].status != VERDICT_PASS;
    if (!st) printf("wrote %s: %zu claims (%zu pending)\n", PATHS_NUMBERS, c.n, pend);
    free(res);
    claims_free(&c);
    return st ? die(st) : 0;
}

int cli_cmd_audit(int argc, char **argv)
{
    const opts_cmd oc = {"audit", "", "Check pins (estimator hash, teacher version and hash, gate hashes), frozen-file hashes,\n"
                  "frozen provenance vs pins, the claim registry, numbers.tex and the paper text.", NULL, 0, 0, 0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    claims c;
    cs_status st = claims_load(PATHS_CLAIMS, &c);
    if (st) return die(st);
    claim_result *res;
    if ((st = verify_eval_all(&c, &res))) { claims_free(&c); return die(st); }
    checklist cl = {0};
    audit_run(&c, res, &cl);
    size_t count[3] = {0};
    checklist_print(&cl, count);
    printf("%zu passed, %zu failed\n", count[VERDICT_PASS] + count[VERDICT_PENDING], count[VERDICT_FAIL]);
    checklist_free(&cl);
    free(res);
    claims_free(&c);
    return count[VERDICT_FAIL] ? 1 : 0;
}

int cli_cmd_trace(int argc, char **argv)
{
    const opts_cmd oc = {"trace", "MACRO", "Print a claim's value, frozen file, function, gate and test.", NULL, 0, 1, 1};
    char *pos[argc > 0 ? argc : 1];
    int r = opts_parse(&oc, argc, argv, pos, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = verify_trace(pos[0]);
    return st ? die(st) : 0;
}

int cli_cmd_pin(int argc, char **argv)
{
    const opts_cmd oc = {"pin", "", "Rewrite audit/pins.tsv from the current estimator, teacher and gates. Deliberate:\n"
                  "afterwards frozen/ must be regenerated (make reproduce freeze) or the audit fails.", NULL, 0, 0, 0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = audit_pin();
    if (st) return die(st);
    printf("wrote %s\n", PATHS_PINS);
    return 0;
}

int cli_cmd_hash_frozen(int argc, char **argv)
{
    const opts_cmd oc = {"hash-frozen", "", "Rewrite audit/frozen.sha256 from frozen/ (part of make freeze).", NULL, 0, 0, 0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = audit_hash_frozen();
    if (st) return die(st);
    printf("wrote %s\n", PATHS_FROZEN_HASHES);
    return 0;
}

int cli_cmd_gates(int argc, char **argv)
{
    const opts_cmd oc = {"gates", "[FILE.gate ...]",
                        "Parse the preregistered gate files (default: every gates/ *.gate) and say ok per file.\n"
                        "Exit 3 on a malformed file, naming file, line and field.", NULL, 0, 0, -1};
    char *pos[argc > 0 ? argc : 1];
    int npos = 0;
    int r = opts_parse(&oc, argc, argv, pos, &npos);
    if (r) return opts_exit_code(r);
    paths_list files;
    if (npos == 0) {
        if (paths_list_files(PATHS_GATES_DIR, ".gate", 0, &files)) return die(CS_ENOMEM);
        if (!files.n) { fprintf(stderr, "crownshy gates: %s/: no .gate files\n", PATHS_GATES_DIR); paths_list_free(&files); return 3; }
    } else {
        memset(&files, 0, sizeof files);
        for (int i = 0; i < npos; i++)
            if (paths_list_add(&files, pos[i])) { paths_list_free(&files); return die(CS_ENOMEM); }
    }
    int rc = 0;
    for (size_t i = 0; i < files.n; i++) {
        gate *g;
        if (gate_load(files.p[i], &g)) { fprintf(stderr, "crownshy: %s\n", cs_errmsg()); rc = 3; continue; }
        printf("%s: ok\n", files.p[i]);
        gate_free(g);
    }
    paths_list_free(&files);
    return rc;
}

int cli_cmd_check_tsv(int argc, char **argv)
{
    const opts_cmd oc = {"check-tsv", "FILE.tsv ...",
                        "Validate frozen tables: provenance lines, header, field counts, and every column\n"
                        "that is numeric in its first row numeric in every row. Exit 3 naming file, line, field.",
                        NULL, 0, 1, -1};
    char *pos[argc > 0 ? argc : 1];
    int npos = 0;
    int r = opts_parse(&oc, argc, argv, pos, &npos);
    if (r) return opts_exit_code(r);
    int rc = 0;
    for (int i = 0; i < npos; i++) {
        tsv *t;
        if (tsv_read(pos[i], &t)) { fprintf(stderr, "crownshy: %s\n", cs_errmsg()); rc = 3; continue; }
        int bad = 0;
        for (size_t c = 0; c < tsv_ncols(t) && !bad && tsv_nrows(t) > 0; c++) {
            double v;
            const char *col = tsv_colname(t, c);
            if (tsv_double_nf(t, 0, col, &v)) continue; /* a text column */
            for (size_t r = 1; r < tsv_nrows(t) && !bad; r++)
                if (tsv_double_nf(t, r, col, &v)) { fprintf(stderr, "crownshy: %s\n", cs_errmsg()); bad = 1; }
        }
        if (bad) rc = 3;
        else printf("%s: ok (%zu rows, %zu columns)\n", pos[i], tsv_nrows(t), tsv_ncols(t));
        tsv_free(t);
    }
    return rc;
}

int cli_cmd_figures(int argc, char **argv)
{
    const opts_cmd oc = {"figures", "", "Redraw every figure (figures/ *.gp, gnuplot) whose frozen data exist; the same step as\n"
                  "in crownshy verify. Exit 1 if a script fails.", NULL, 0, 0, 0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    checklist cl = {0};
    verify_figures(&cl);
    size_t count[3] = {0};
    checklist_print(&cl, count);
    checklist_free(&cl);
    return count[VERDICT_FAIL] ? 1 : 0;
}

