/* crownshy: the one command-line entry point. Only this file decides how the
 * process dies; library calls return a cs_status (SPEC §11 exit codes). */
#include "cs.h"
#include "experiments.h"
#include "audit.h"
#include "claims.h"
#include "verify.h"
#include "gate.h"
#include "tsv.h"
#include "exp_main.h"
#include "exp_field.h"
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef int (*cmd_fn)(int argc, char **argv);
typedef struct { const char *name; cmd_fn fn; const char *help; } cli_cmd;

static int cmd_version(int argc, char **argv)
{
    (void)argc; (void)argv;
    puts("crownshy 0.1");
    return 0;
}

/* Common --help handling: every command answers --help with exit 0. */
static int want_help(int argc, char **argv, const char *text)
{
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) { fputs(text, stdout); return 1; }
    return 0;
}

static int die(cs_status st)
{
    fprintf(stderr, "crownshy: %s\n", cs_errmsg()[0] ? cs_errmsg() : cs_status_name(st));
    return cs_exit_code(st);
}

static int cmd_verify(int argc, char **argv)
{
    if (want_help(argc, argv,
                  "usage: crownshy verify [--no-figures]\n"
                  "Audit pins and frozen hashes, recompute every claim of audit/claims.tsv from frozen/,\n"
                  "compare with paper/numbers.tex, judge every gate, redraw every figure, and print\n"
                  "'N passed, N failed'. Exit 1 if anything failed; pending claims are listed, not passed.\n"))
        return 0;
    verify_opts o = {0};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--no-figures")) o.no_figures = 1;
        else { fprintf(stderr, "crownshy verify: unknown option '%s'\n", argv[i]); return 2; }
    }
    cs_status st = verify_run(&o);
    if (st && st != CS_EFAIL) return die(st);
    return cs_exit_code(st);
}

static int cmd_numbers(int argc, char **argv)
{
    if (want_help(argc, argv,
                  "usage: crownshy numbers [--check]\n"
                  "Regenerate paper/numbers.tex from frozen/ (atomic). With --check, only compare.\n"))
        return 0;
    int check = argc > 1 && !strcmp(argv[1], "--check");
    if (argc > 1 && !check) { fprintf(stderr, "crownshy numbers: unknown option '%s'\n", argv[1]); return 2; }
    claims c;
    cs_status st = claims_load(AUDIT_CLAIMS, &c);
    if (st) return die(st);
    claim_result *res;
    if ((st = verify_eval_all(&c, &res))) { claims_free(&c); return die(st); }
    if (check) {
        checklist cl = {0};
        audit_run(&c, res, &cl);
        int bad = 0;
        for (size_t i = 0; i < cl.n; i++)
            if (!strcmp(cl.items[i].name, "numbers.tex")) {
                printf("%s %s\n", verdict_name(cl.items[i].v), cl.items[i].msg);
                bad |= cl.items[i].v == VERDICT_FAIL;
            }
        checklist_free(&cl);
        free(res);
        claims_free(&c);
        return bad ? 1 : 0;
    }
    st = claims_write_numbers(AUDIT_NUMBERS, &c, res);
    if (!st) st = claims_write_comparison("paper/comparison.tex", &c, res);
    size_t pend = 0;
    for (size_t i = 0; i < c.n; i++) pend += res[i].status != VERDICT_PASS;
    if (!st) printf("wrote %s: %zu claims (%zu pending)\n", AUDIT_NUMBERS, c.n, pend);
    free(res);
    claims_free(&c);
    return st ? die(st) : 0;
}

static int cmd_audit(int argc, char **argv)
{
    if (want_help(argc, argv,
                  "usage: crownshy audit\n"
                  "Check pins (estimator hash, teacher version and hash, gate hashes), frozen-file hashes,\n"
                  "frozen provenance vs pins, the claim registry, numbers.tex and the paper text.\n"))
        return 0;
    claims c;
    cs_status st = claims_load(AUDIT_CLAIMS, &c);
    if (st) return die(st);
    claim_result *res;
    if ((st = verify_eval_all(&c, &res))) { claims_free(&c); return die(st); }
    checklist cl = {0};
    audit_run(&c, res, &cl);
    size_t pass = 0, fail = 0;
    for (size_t i = 0; i < cl.n; i++) {
        printf("  %-7s %-28s %s\n", verdict_name(cl.items[i].v), cl.items[i].name, cl.items[i].msg);
        if (cl.items[i].v == VERDICT_FAIL) fail++; else pass++;
    }
    printf("%zu passed, %zu failed\n", pass, fail);
    checklist_free(&cl);
    free(res);
    claims_free(&c);
    return fail ? 1 : 0;
}

static int cmd_trace(int argc, char **argv)
{
    if (want_help(argc, argv, "usage: crownshy trace MACRO\nPrint a claim's value, frozen file, function, gate and test.\n")) return 0;
    if (argc != 2) { fprintf(stderr, "usage: crownshy trace MACRO\n"); return 2; }
    cs_status st = verify_trace(argv[1]);
    return st ? die(st) : 0;
}

static int cmd_pin(int argc, char **argv)
{
    if (want_help(argc, argv,
                  "usage: crownshy pin\n"
                  "Rewrite audit/pins.tsv from the current estimator, teacher and gates. Deliberate:\n"
                  "afterwards frozen/ must be regenerated (make reproduce freeze) or the audit fails.\n"))
        return 0;
    cs_status st = audit_pin();
    if (st) return die(st);
    printf("wrote %s\n", AUDIT_PINS);
    return 0;
}

static int cmd_hash_frozen(int argc, char **argv)
{
    if (want_help(argc, argv, "usage: crownshy hash-frozen\nRewrite audit/frozen.sha256 from frozen/ (part of make freeze).\n")) return 0;
    cs_status st = audit_hash_frozen();
    if (st) return die(st);
    printf("wrote %s\n", AUDIT_FROZEN_HASHES);
    return 0;
}

static int cmd_gates(int argc, char **argv)
{
    if (want_help(argc, argv,
                  "usage: crownshy gates [FILE.gate ...]\n"
                  "Parse the preregistered gate files (default: every gates/ *.gate) and print each\n"
                  "threshold with its file and line. Exit 3 on a malformed file.\n"))
        return 0;
    char *files[64];
    int n = 0;
    if (argc > 1) {
        for (int i = 1; i < argc && n < 64; i++) files[n++] = strdup(argv[i]);
    } else {
        DIR *d = opendir("gates");
        if (!d) { fprintf(stderr, "crownshy gates: gates/: cannot open\n"); return 3; }
        struct dirent *e;
        while ((e = readdir(d)) && n < 64) {
            size_t l = strlen(e->d_name);
            if (l > 5 && !strcmp(e->d_name + l - 5, ".gate")) {
                char p[600];
                snprintf(p, sizeof p, "gates/%s", e->d_name);
                files[n++] = strdup(p);
            }
        }
        closedir(d);
    }
    int rc = 0;
    for (int i = 0; i < n; i++) {
        gate *g;
        if (gate_load(files[i], &g)) { fprintf(stderr, "crownshy: %s\n", cs_errmsg()); rc = 3; free(files[i]); continue; }
        printf("%s: ok\n", files[i]);
        gate_free(g);
        free(files[i]);
    }
    return rc;
}

static int cmd_check_tsv(int argc, char **argv)
{
    if (want_help(argc, argv,
                  "usage: crownshy check-tsv FILE.tsv ...\n"
                  "Validate frozen tables: provenance lines, header, field counts, and every column\n"
                  "that is numeric in its first row numeric in every row. Exit 3 naming file, line, field.\n"))
        return 0;
    if (argc < 2) { fprintf(stderr, "usage: crownshy check-tsv FILE.tsv ...\n"); return 2; }
    int rc = 0;
    for (int i = 1; i < argc; i++) {
        tsv *t;
        if (tsv_read(argv[i], &t)) { fprintf(stderr, "crownshy: %s\n", cs_errmsg()); rc = 3; continue; }
        int bad = 0;
        for (size_t c = 0; c < tsv_ncols(t) && !bad && tsv_nrows(t) > 0; c++) {
            double v;
            const char *col = tsv_colname(t, c);
            if (tsv_double_nf(t, 0, col, &v)) continue; /* a text column */
            for (size_t r = 1; r < tsv_nrows(t) && !bad; r++)
                if (tsv_double_nf(t, r, col, &v)) { fprintf(stderr, "crownshy: %s\n", cs_errmsg()); bad = 1; }
        }
        if (bad) rc = 3;
        else printf("%s: ok (%zu rows, %zu columns)\n", argv[i], tsv_nrows(t), tsv_ncols(t));
        tsv_free(t);
    }
    return rc;
}

static const cli_cmd cli_cmds[] = {
    {"main-run", exp_main_cmd_run, "E3/E4: one (seed, arm) training + evaluation unit"},
    {"main-baselines", exp_main_cmd_baselines, "E3/E4: direction-blind baseline and noise floor"},
    {"main-summary", exp_main_cmd_summary, "E3/E4: gather runs into frozen tables"},
    {"bench-teacher", exp_cmd_bench_teacher, "teacher ms per 144-tree stand at N = 48 and 384"},
    {"run", exp_cmd_run, "run one experiment unit of E1/E2/figure data (crownshy run --help)"},
    {"gates", cmd_gates, "parse and list the preregistered gate files"},
    {"check-tsv", cmd_check_tsv, "validate frozen TSV files"},
    {"verify", cmd_verify, "audit, recompute every claim, judge gates, redraw figures"},
    {"numbers", cmd_numbers, "regenerate paper/numbers.tex from frozen/"},
    {"audit", cmd_audit, "check pins, frozen hashes, provenance, registry and paper"},
    {"trace", cmd_trace, "trace one macro to its value, file, function, gate and test"},
    {"pin", cmd_pin, "re-pin the estimator, teacher and gates (deliberate)"},
    {"hash-frozen", cmd_hash_frozen, "record the hashes of frozen/ (make freeze)"},
    {"field-summary", cmd_field_summary, "summarise a raw field table (FIELD_TABLE) with the canonical estimator"},
    {"field-calibrate", cmd_field_calibrate, "E5: calibrate die-back beta to the field tree-mean median clearance"},
    {"field-beta", cmd_field_beta, "E5: print beta_field from a calibration table"},
    {"field-heldout", cmd_field_heldout, "E5: held-out spread, elongation and uncoupled control at beta_field"},
    {"aniso-lattice", cmd_aniso_lattice, "E6: anisotropy on the controlled lattice at beta_field"},
    {"aniso-hardcore", cmd_aniso_hardcore, "E6: hard-core stem family sweep"},
    {"aniso-jitter", cmd_aniso_jitter, "E6: jitter-amplitude family sweep"},
    {"aniso-jitter-calibrate", cmd_aniso_jitter_calibrate, "E6: calibrate jitter a* to the field anisotropy median"},
    {"aniso-heldout", cmd_aniso_heldout, "E6: held-out stands at a*"},
    {"field-diagnose", cmd_field_diagnose, "E5/E6: diagnostics for the elongation and anisotropy verdicts"},
    {"version", cmd_version, "print the version"},
};
#define NCMDS (sizeof cli_cmds / sizeof cli_cmds[0])

static void usage(FILE *f)
{
    fprintf(f, "usage: crownshy <command> [options]   (crownshy <command> --help)\n\ncommands:\n");
    for (size_t i = 0; i < NCMDS; i++) fprintf(f, "  %-16s %s\n", cli_cmds[i].name, cli_cmds[i].help);
    fprintf(f, "\nexit codes: 0 ok, 1 a gate or claim failed, 2 usage error, 3 bad or missing input\n");
}

int main(int argc, char **argv)
{
    cs_gsl_install();
    if (argc < 2) { usage(stderr); return 2; }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    for (size_t i = 0; i < NCMDS; i++)
        if (!strcmp(argv[1], cli_cmds[i].name)) return cli_cmds[i].fn(argc - 1, argv + 1);
    fprintf(stderr, "crownshy: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
