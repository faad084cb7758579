/* audit_paper: the write-up against frozen/ (design.md §9).
 * The generated files (numbers.tex, comparison.tex, readings.tex) must equal
 * a fresh generation; every other .tex under paper/ (subfolders included) may
 * use claim macros only: no measured number typed in any rounding, no claim
 * macro (re)defined, and no comment that would exempt the file or a region
 * from these checks (none is honoured; one present is itself a failure). */
#include "audit_paper.h"
#include "afile.h"
#include "readings.h"
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *const generated[] = {PATHS_NUMBERS, PATHS_COMPARISON, PATHS_READINGS_TEX, NULL};

int paper_is_generated(const char *path)
{
    for (int i = 0; generated[i]; i++) if (!strcmp(path, generated[i])) return 1;
    return 0;
}

cs_status paper_generate(const claims *c, const claim_result *res, const char *dir, int *readings)
{
    char p[512];
    snprintf(p, sizeof p, "%s/numbers.tex", dir);
    cs_status st = claims_write_numbers(p, c, res);
    snprintf(p, sizeof p, "%s/comparison.tex", dir);
    if (!st) st = claims_write_comparison(p, c, res);
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
        if (!ra || !rb || strcmp(la, bb)) { diff = lineno; if (rb) snprintf(lb, n, "%.*s", (int)strcspn(bb, "\n"), bb); break; }
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
                checklist_add(cl, VERDICT_FAIL, item, "%s exists but nothing generates it (%s absent)", generated[i], PATHS_READINGS_SUMMARY);
            continue;
        }
        int missing, d = first_diff(fresh, generated[i], lb, sizeof lb, &missing);
        if (missing) checklist_add(cl, VERDICT_FAIL, item, "%s missing (generate it with crownshy numbers)", generated[i]);
        else if (d) {
            /* name the claim on the differing line when there is one */
            char claim[80] = "";
            for (size_t r = 0; r < c->n && !claim[0]; r++) {
                char pat[96];
                snprintf(pat, sizeof pat, "{%s}", c->rows[r].macro);
                if (strstr(lb, pat) || strstr(lb, c->rows[r].macro)) snprintf(claim, sizeof claim, "; claim: %s", c->rows[r].macro);
            }
            checklist_add(cl, VERDICT_FAIL, item, "%s:%d differs from a fresh generation ('%.200s'): edited by hand or stale%s", generated[i], d, lb, claim);
        } else checklist_add(cl, VERDICT_PASS, item, "%s equals a fresh generation from frozen/", generated[i]);
    }
    rmdir_fresh(dir);
}

/* ---- the hand-written text ---- */
/* LaTeX's own capitalised commands: not claim macros. */
static const char *latex_upper[] = {"LaTeX", "TeX", "Large", "LARGE", "Huge", "HUGE", "Roman", "Alph", "Ref", "S", "P", "L", "O", "AA", "AE", "OE", "Delta", "Gamma", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi", "Omega", "Bigl", "Bigr", "Big", "Biggl", "Biggr", "bibliographystyle", "IfFileExists", NULL};

static int audit_latex_upper(const char *name)
{
    for (int i = 0; latex_upper[i]; i++) if (!strcmp(latex_upper[i], name)) return 1;
    return 0;
}

static int is_defining(const char *cmd)
{
    static const char *defs[] = {"newcommand", "renewcommand", "providecommand", "def", "gdef", "edef", "xdef", "let",
                                 "DeclareRobustCommand", "NewDocumentCommand", "RenewDocumentCommand", "ProvideDocumentCommand",
                                 "DeclareDocumentCommand", "NewExpandableDocumentCommand", "newrobustcmd", "renewrobustcmd", "csdef", NULL};
    for (int i = 0; defs[i]; i++) if (!strcmp(defs[i], cmd)) return 1;
    return 0;
}

/* A comment that asks for an exemption (never honoured). */
static int exemption_comment(const char *comment)
{
    if (strstr(comment, "GENERATED")) return 1;
    char low[4096];
    size_t i = 0;
    for (; comment[i] && i < sizeof low - 1; i++) low[i] = (char)tolower((unsigned char)comment[i]);
    low[i] = '\0';
    static const char *words[] = {"exempt", "nocheck", "no-check", "no check", "audit-ignore", "audit: ignore", "audit:ignore",
                                  "verify-ignore", "verify: skip", "skip-audit", "audit-off", "lint-ignore", NULL};
    for (int k = 0; words[k]; k++) if (strstr(low, words[k])) return 1;
    return 0;
}

/* Decimals and significant digits of a numeric token. */
static void token_digits(const char *tok, size_t len, int *dec, int *sig)
{
    const char *dot = memchr(tok, '.', len);
    *dec = dot ? (int)(tok + len - dot - 1) : 0;
    int s = 0, lead = 1;
    for (size_t i = 0; i < len; i++) {
        if (!isdigit((unsigned char)tok[i])) continue;
        if (lead && tok[i] == '0') continue;
        lead = 0;
        s++;
    }
    *sig = s;
}

/* Does `x` (as typed, with `dec` decimals and `sig` significant digits;
 * neg: a minus sign precedes it) round a measured value? A value of the other
 * sign (the text may say "a decrease of ...") counts from 3 significant digits. */
static int rounds_to(double x, int dec, int sig, int neg, double v)
{
    if (!isfinite(v) || dec > 12) return 0;
    double scale = pow(10.0, dec);
    if (fabs(fabs(x) - fabs(round(v * scale) / scale)) >= 0.25 / scale) return 0;
    return ((v < 0) == neg) || sig >= 3;
}

size_t paper_scan_file(const char *path, const claims *c, const double *vals, const char *const *who, size_t nv, checklist *cl, size_t *used)
{
    FILE *f = fopen(path, "r");
    if (!f) { checklist_add(cl, VERDICT_FAIL, "paper text", "%s: cannot read", path); return 1; }
    size_t bad = 0;
    {
        char line[8192];
        int lineno = 0;
        while (fgets(line, sizeof line, f)) {
            lineno++;
            char *pct = line;
            while ((pct = strchr(pct, '%'))) {
                if (pct == line || pct[-1] != '\\') {
                    if (exemption_comment(pct + 1)) {
                        checklist_add(cl, VERDICT_FAIL, "paper self-exemption", "%s:%d: comment '%.80s' asks for an exemption from the audit: none is honoured; remove it",
                                      path, lineno, pct + 1);
                        bad++;
                    }
                    *pct = '\0';
                    break;
                }
                pct++;
            }
            const char *lastcmd = "";
            char cmdbuf[80] = "";
            for (char *s = line; (s = strchr(s, '\\')); s++) {
                char name[80];
                int k = 0;
                while (k < 79 && isalpha((unsigned char)s[1 + k])) { name[k] = s[1 + k]; k++; }
                name[k] = '\0';
                if (!k) continue;
                char base[80];
                snprintf(base, sizeof base, "%s", name);
                size_t bl = strlen(base);
                if (bl > 4 && !strcmp(base + bl - 4, "Gate")) base[bl - 4] = '\0';
                const claim_row *row = claims_find(c, base);
                /* \newcommand{\Claim}, \renewcommand*\Claim, \def\Claim, \let\Claim ... */
                if (row && is_defining(lastcmd)) {
                    checklist_add(cl, VERDICT_FAIL, "paper macro redefined", "%s:%d: \\%s defines the claim macro \\%s in the text (only numbers.tex defines it); claim: %s",
                                  path, lineno, lastcmd, name, row->macro);
                    bad++;
                }
                if (isupper((unsigned char)name[0]) && !audit_latex_upper(name)) {
                    if (!row) {
                        checklist_add(cl, VERDICT_FAIL, "paper macros", "%s:%d: \\%s has no row in %s", path, lineno, name, PATHS_CLAIMS);
                        bad++;
                    } else (*used)++;
                }
                /* remember the command just before a possible macro name */
                snprintf(cmdbuf, sizeof cmdbuf, "%s", name);
                lastcmd = is_defining(name) ? cmdbuf : "";
                s += k;
            }
            /* numbers typed by hand, in any rounding: a decimal token with at
             * least two significant digits that rounds a measured value (ours
             * or the reference paper's). Integers are too common to police. */
            for (char *s = line; *s; ) {
                if (!isdigit((unsigned char)*s) || (s > line && (isalnum((unsigned char)s[-1]) || s[-1] == '\\' || s[-1] == '_'))) { s++; continue; }
                char *e = s;
                while (isdigit((unsigned char)*e)) e++;
                if (*e == '.' && isdigit((unsigned char)e[1])) { e++; while (isdigit((unsigned char)*e)) e++; }
                size_t len = (size_t)(e - s);
                int dec, sig;
                token_digits(s, len, &dec, &sig);
                if (dec > 0 && sig >= 2 && !isalpha((unsigned char)*e)) {
                    double x = strtod(s, NULL);
                    const char *b = s;
                    while (b > line && (b[-1] == '$' || b[-1] == ' ' || b[-1] == '{')) b--;
                    int neg = (b > line && b[-1] == '-') || (b - line >= 3 && !memcmp(b - 3, "\xe2\x88\x92", 3));
                    for (size_t q = 0; q < nv; q++)
                        if (rounds_to(x, dec, sig, neg, vals[q])) {
                            checklist_add(cl, VERDICT_FAIL, "hand-typed numbers", "%s:%d: '%.*s' typed by hand rounds the measured value %.6g; use \\%s; claim: %s",
                                          path, lineno, (int)len, s, vals[q], who[q], who[q]);
                            bad++;
                            break;
                        }
                }
                s = e;
            }
        }
        fclose(f);
    }
    return bad;
}

void audit_paper_text(const claims *c, const claim_result *res, checklist *cl)
{
    paths_list tex;
    paths_list_files(PATHS_PAPER_DIR, ".tex", 1, &tex);
    size_t bad = 0, used = 0, files = 0;
    /* the measured values a number in the text must not round */
    double *vals = calloc(2 * (c->n ? c->n : 1), sizeof *vals);
    const char **who = calloc(2 * (c->n ? c->n : 1), sizeof *who);
    size_t nv = 0;
    for (size_t r = 0; vals && who && r < c->n; r++) {
        if (strcmp(c->rows[r].kind, "measured") && strcmp(c->rows[r].kind, "needs-data") && strcmp(c->rows[r].kind, "probe")) continue;
        char *end;
        double ref = strtod(c->rows[r].reference, &end);
        if (res[r].status == VERDICT_PASS && isfinite(res[r].value)) { vals[nv] = res[r].value; who[nv++] = c->rows[r].macro; }
        if (end != c->rows[r].reference && !*end && isfinite(ref)) { vals[nv] = ref; who[nv++] = c->rows[r].macro; }
    }
    for (size_t i = 0; i < tex.n; i++) {
        if (paper_is_generated(tex.p[i])) continue; /* compared with a fresh generation instead */
        files++;
        bad += paper_scan_file(tex.p[i], c, vals, (const char *const *)who, nv, cl, &used);
    }
    free(vals);
    free(who);
    if (!bad) checklist_add(cl, VERDICT_PASS, "paper text", "%zu hand-written paper files (subfolders included): %zu claim-macro uses, all registered; no claim macro defined; no measured number typed in any rounding; no exemption comment", files, used);
    paths_list_free(&tex);
}
