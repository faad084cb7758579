/* cli_audit: the reviewer's and auditor's commands (design.md §9): verify,
 * numbers, audit, trace, pin, hash-frozen, gates, check-tsv, figures. Only
 * the CLI decides how the process dies. */
#include "cli.h"
#include "audit.h"
#include "audit_pin.h"
#include "claims.h"
#include "gate.h"
#include "opts.h"
#include "paths.h"
#include "readings.h"
#include <sys/stat.h>
#include "tsv.h"
#include "verify.h"
#include "figcheck.h"
#include "audit_paper.h"
#include "audit_docs.h"
#include "agree.h"
#include <unistd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cli_cmd_verify(int argc, char **argv)
{
    verify_opts o = {0};
    long spot_seed = 0;
    const opt_spec spec[] = {
        {"no-figures", OPT_FLAG, &o.no_figures, 0, 0, "skip the redraws (the figures and the spot check)"},
        {"strict", OPT_FLAG, &o.strict, 0, 0, "also fail when a preregistered gate fails (a finding)"},
        {"seed", OPT_LONG, &spot_seed, 1, 4294967295.0,
         "the spot check's pick (default: from the clock; printed, to repeat it)"},
        {"prereg", OPT_STR, &o.prereg, 0, 0,
         "the gates' sha256 from a copy you trust (CITATION.cff, the write-up's first page); without it the "
         "preregistration is self-attested"}};
    const opts_cmd oc = {"verify", "[--no-figures] [--strict] [--seed N] [--prereg SHA256]",
                        "Audit pins, frozen hashes, provenance and aggregates, recompute every claim of\n"
                        "audit/claims.tsv from frozen/, compare with the generated paper files, check the\n"
                        "paper text, judge every gate, redraw every figure into build/ (the data it plots\n"
                        "compared with figures/plotted.sha256, the PNG byte for byte where the renderer is the\n"
                        "pinned one), and print the package's consistency and the reference paper's gated\n"
                        "claims (reproduced, not reproduced, pending). A failing gate is a finding, not an error.\n"
                        "Exit 0: consistent (gate failures allowed); 1: any inconsistency (with --strict also any\n"
                        "failing gate); 2: usage; 3: bad input (the registry or gate map unreadable, a FIELD_TABLE or\n"
                        "CHM that cannot be read); 4: environment (a build/ that cannot be written, I/O, memory).",
                        spec, 4, 0, 0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    o.spot_seed = (unsigned long)spot_seed;
    if (o.prereg && (strlen(o.prereg) != 64 || strspn(o.prereg, "0123456789abcdef") != 64)) {
        fprintf(stderr, "crownshy verify: --prereg: '%s' is not a sha256 (64 lowercase hex digits)\n", o.prereg);
        return 2;
    }
    cs_status st = verify_run(&o);
    if (st && st != CS_EFAIL) return cli_fail("verify", st);
    return cs_exit_code(st);
}

/* Every generated file the generation wrote into dir (readings.tex and
 * sensitivity.tex only when their frozen summaries exist) moves into paper/,
 * when the generation succeeded (st); dir is emptied and removed either way. */
static cs_status move_generated(cs_status st, const char *dir, char *wrote, size_t n)
{
    for (size_t i = 0; paper_generated(i); i++) {
        char p[256];
        struct stat sb;
        snprintf(p, sizeof p, "%s/%s", dir, strrchr(paper_generated(i), '/') + 1);
        if (stat(p, &sb) != 0) continue;
        if (!st && rename(p, paper_generated(i)) != 0)
            st = cs_err(CS_EIO, "%s: cannot move to %s", p, paper_generated(i));
        else if (!st)
            snprintf(wrote + strlen(wrote), n - strlen(wrote), "%s%s", wrote[0] ? ", " : "", paper_generated(i));
        unlink(p);
    }
    rmdir(dir);
    return st;
}

int cli_cmd_numbers(int argc, char **argv)
{
    int check = 0;
    const opt_spec spec[] = {
        {"check", OPT_FLAG, &check, 0, 0, "only compare the three files with a fresh generation (write nothing)"}};
    const opts_cmd oc = {
        "numbers",
        "[--check]",
        "Regenerate paper/numbers.tex, paper/comparison.tex and paper/readings.tex from frozen/:\n"
        "all three are generated into build/ first and moved into paper/ only when every claim\n"
        "was computed (exit 3 naming the claim and its input otherwise, writing nothing); then the\n"
        "generated regions (<!--Macro-->value<!--/-->, <!-- findings -->) of README.md and the *.md pages.\n"
        "--check: compare the three with a fresh generation (exit 1 naming the first differing line).",
        spec, 1, 0, 0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    claims c;
    claim_result *res;
    cs_status st = verify_preflight();
    if (st || (st = verify_load_eval(&c, &res))) return cli_fail("numbers", st);
    if (check) {
        checklist cl = {0};
        audit_generated(&c, res, &cl, 0);
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
    /* bad input (a claim that cannot be computed: a malformed FIELD_TABLE or
     * CHM, a damaged frozen table): say so and write nothing into paper/ */
    size_t nbad = 0;
    for (size_t i = 0; i < c.n; i++)
        if (res[i].status == VERDICT_FAIL) {
            fprintf(stderr, "crownshy numbers: %s: %s\n", c.rows[i].macro, res[i].why);
            nbad++;
        }
    if (nbad) {
        fprintf(stderr,
                "crownshy numbers: %zu claim(s) cannot be computed from their input; nothing written into %s/\n", nbad,
                PATHS_PAPER_DIR);
        free(res);
        claims_free(&c);
        return 3;
    }
    /* generate all three into build/, then move them into paper/ */
    char dir[128];
    snprintf(dir, sizeof dir, "build/numbers.%ld", (long)getpid());
    int readings = 0;
    char wrote[1024] = "";
    st = move_generated(paper_generate(&c, res, dir, &readings), dir, wrote, sizeof wrote);
    size_t pend = 0;
    for (size_t i = 0; i < c.n; i++) pend += res[i].status != VERDICT_PASS;
    if (!st) printf("wrote %s: %zu claims (%zu pending)\n", wrote, c.n, pend);
    size_t pages = 0; /* the generated regions of the documentation pages */
    if (!st && !(st = docs_refresh(&c, res, &pages)) && pages)
        printf("refreshed the generated regions of %zu documentation page(s)\n", pages);
    free(res);
    claims_free(&c);
    return st ? cli_fail("numbers", st) : 0;
}

int cli_cmd_audit(int argc, char **argv)
{
    const opts_cmd oc = {"audit",
                         "",
                         "Check pins (estimator hash, teacher version and hash, gate hashes), frozen-file hashes,\n"
                         "frozen provenance vs pins, the claim registry, numbers.tex and the paper text.",
                         NULL,
                         0,
                         0,
                         0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    claims c;
    claim_result *res;
    cs_status st = verify_preflight();
    if (st || (st = verify_load_eval(&c, &res))) return cli_fail("audit", st);
    if ((st = verify_external_inputs(&c, res, "audit"))) { free(res); claims_free(&c); return cli_fail("audit", st); }
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
    const opts_cmd oc = {"trace", "MACRO", "Print a claim's value, frozen file, function, gate and test.", NULL, 0,
                         1,       1};
    char *pos[argc > 0 ? argc : 1];
    int r = opts_parse(&oc, argc, argv, pos, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = verify_trace(pos[0]);
    return st ? cli_fail("trace", st) : 0;
}

int cli_cmd_pin(int argc, char **argv)
{
    const opts_cmd oc = {"pin",
                         "",
                         "Rewrite audit/pins.tsv from the current estimator, teacher and gates. Deliberate:\n"
                         "afterwards frozen/ must be regenerated (make reproduce freeze) or the audit fails.",
                         NULL,
                         0,
                         0,
                         0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = audit_pin();
    if (st) return cli_fail("pin", st);
    printf("wrote %s\n", PATHS_PINS);
    return 0;
}

int cli_cmd_claims_table(int argc, char **argv)
{
    int check = 0;
    const opt_spec spec[] = {{"check", OPT_FLAG, &check, 0, 0, "only compare the file with the print (write nothing)"}};
    const opts_cmd oc = {"claims-table", "[--check]",
                         "Write audit/claims.tsv, the print of the claim tables (src/claims/claim_*_table.c, in\n"
                         "the order of the CLAIMS rows of src/base/manifest.h). --check: compare only (exit 1\n"
                         "naming the first differing line; crownshy verify does the same).",
                         spec, 1, 0, 0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = check ? claims_registry_check(PATHS_CLAIMS) : claims_registry_write(PATHS_CLAIMS);
    if (st && check && st == CS_EINVARIANT) {
        fprintf(stderr, "crownshy claims-table: %s\n", cs_errmsg());
        return 1;
    }
    if (st) return cli_fail("claims-table", st);
    printf("%s %s\n", check ? "checked" : "wrote", PATHS_CLAIMS);
    return 0;
}

int cli_cmd_hash_frozen(int argc, char **argv)
{
    const opts_cmd oc = {
        "hash-frozen", "", "Rewrite audit/frozen.sha256 from frozen/ (part of make freeze).", NULL, 0, 0, 0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    cs_status st = audit_hash_frozen();
    if (st) return cli_fail("hash-frozen", st);
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
        if (paths_list_files(PATHS_GATES_DIR, ".gate", 0, &files))
            return cli_fail("gates", cs_err(CS_ENOMEM, "out of memory"));
        if (!files.n) {
            fprintf(stderr, "crownshy gates: %s/: no .gate files\n", PATHS_GATES_DIR);
            paths_list_free(&files);
            return 3;
        }
    } else {
        memset(&files, 0, sizeof files);
        for (int i = 0; i < npos; i++)
            if (paths_list_add(&files, pos[i])) {
                paths_list_free(&files);
                return cli_fail("gates", cs_err(CS_ENOMEM, "out of memory"));
            }
    }
    int rc = 0;
    for (size_t i = 0; i < files.n; i++) {
        gate *g;
        if (gate_load(files.p[i], &g)) { cli_fail("gates", CS_EINPUT); rc = 3; continue; }
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
        if (tsv_read(pos[i], &t)) { cli_fail("check-tsv", CS_EINPUT); rc = 3; continue; }
        int bad = 0;
        for (size_t c = 0; c < tsv_ncols(t) && !bad && tsv_nrows(t) > 0; c++) {
            double v;
            const char *col = tsv_colname(t, c);
            if (tsv_double_nf(t, 0, col, &v)) continue; /* a text column */
            for (size_t r = 1; r < tsv_nrows(t) && !bad; r++)
                if (tsv_double_nf(t, r, col, &v)) { cli_fail("check-tsv", CS_EINPUT); bad = 1; }
        }
        if (bad) rc = 3;
        else printf("%s: ok (%zu rows, %zu columns)\n", pos[i], tsv_nrows(t), tsv_ncols(t));
        tsv_free(t);
    }
    return rc;
}

int cli_cmd_figures(int argc, char **argv)
{
    const opts_cmd oc = {"figures",
                         "",
                         "Redraw every figure (figures/ *.gp, gnuplot) from frozen/ into build/, and install a\n"
                         "redraw into figures/ only when its script succeeded (verify only compares). Exit 1 if a\n"
                         "script fails or its data are missing.",
                         NULL,
                         0,
                         0,
                         0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    claims c;
    int have_c = claims_registry(&c) == CS_OK;
    checklist cl = {0};
    figcheck_verify(&cl, 1, have_c ? &c : NULL);
    if (have_c) claims_free(&c);
    size_t count[3] = {0};
    checklist_print(&cl, count);
    checklist_free(&cl);
    return count[VERDICT_FAIL] ? 1 : 0;
}


int cli_cmd_report(int argc, char **argv)
{
    const opts_cmd oc = {
        "report",
        "",
        "Print the reproduction summary (the table that opens the write-up, paper/summary.tex):\n"
        "every measured claim with a paper value or a gate, ours with its 95 % interval over the\n"
        "independent replicate unit, the gate verdict and the agreement class (colour only on a terminal).",
        NULL,
        0,
        0,
        0};
    int r = opts_parse(&oc, argc, argv, NULL, NULL);
    if (r) return opts_exit_code(r);
    claims c;
    claim_result *res;
    cs_status st = verify_load_eval(&c, &res);
    if (st) return cli_fail("report", st);
    const claim_interval *ci;
    attrib_data at = {0};
    if (!(st = agree_intervals_cached(&c, res, &ci)) &&
        !(st = attrib_load(PATHS_READINGS_SUMMARY, PATHS_SENS_SUMMARY, &at))) {
        attrib_bind(&at, &c, res, ci);
        agree_print_report(stdout, &c, res, ci, &at, isatty(STDOUT_FILENO));
        attrib_free(&at);
    }
    free(res);
    claims_free(&c);
    return st ? cli_fail("report", st) : 0;
}
