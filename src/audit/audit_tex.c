/* audit_tex: the hand-written paper text read as TeX reads it (design.md §9):
 * every .tex under paper/ and every file it pulls in; claim macros
 * only, never defined in the text in any form; verdict commands with
 * generated gate macros only; every number a generated macro or a design
 * constant (audit/design_numbers.tsv); no comment asking for an exemption
 * (none is honoured; one present is itself a failure). */
#include "audit_paper.h"
#include "tex_lex.h"
#include "gate.h"
#include "tsv.h"
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ---- the hand-written text ---- */
/* A comment that asks for an exemption (never honoured). */
static int exemption_comment(const char *comment)
{
    if (strstr(comment, "GENERATED")) return 1;
    char low[4096];
    size_t i = 0;
    for (; comment[i] && i < sizeof low - 1; i++) low[i] = (char)tolower((unsigned char)comment[i]);
    low[i] = '\0';
    static const char *words[] = {"exempt",
                                  "nocheck",
                                  "no-check",
                                  "no check",
                                  "audit-ignore",
                                  "audit: ignore",
                                  "audit:ignore",
                                  "verify-ignore",
                                  "verify: skip",
                                  "skip-audit",
                                  "audit-off",
                                  "lint-ignore",
                                  NULL};
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

/* ---- the hand-written text, read as TeX reads it ----
 * A file is read whole (a command split over lines is one command), comments
 * blanked. Definitions in any form (\newcommand, \def, \let, \expandafter
 * \def\csname X\endcsname, \@namedef{X}, \csdef{X}) must not define a claim
 * macro; \csname ... \endcsname spelling a claim is a use of it; \catcode is
 * refused (it changes what the audit reads). Commands whose definition tests
 * a verdict (PASS or FAIL in its body) take a generated gate macro only, and
 * a verdict is never typed. Every number in the text is a generated macro or
 * a design constant of audit/design_numbers.tsv; dimensions (3pt, 0.9\linewidth),
 * macro parameters (#1), colour mixes (green!45!black), identifiers (E3,
 * teacher-2) and arguments that are names (\label, \ref, \cite, files) are
 * not numbers of the text. */

typedef struct {
    const claims *c;
    const double *vals;
    const char *const *who;
    size_t nv;
    const design_const *design; /* the design constants' macros */
    size_t nd;
    checklist *cl;
    size_t *used, bad;
    int collect;           /* pass 1: collect verdict commands only */
    char (*verdicts)[64];  /* names of the commands that test a verdict */
    size_t nverd;
    paths_list *pulled;    /* files \input, \include, \usepackage pull in */
    const char *path, *text;
    size_t body_end;       /* inside a definition body until here: #n and PASS/FAIL allowed */
} tex_scan;

static void tex_fail(tex_scan *t, size_t pos, const char *item, const char *fmt, const char *a, const char *b)
{
    if (t->collect) return;
    char msg[900];
    snprintf(msg, sizeof msg, fmt, a, b);
    checklist_add(t->cl, VERDICT_FAIL, item, "%s:%d: %s", t->path, tex_lex_line(t->text, pos), msg);
    t->bad++;
}

static int is_verdict_cmd(const tex_scan *t, const char *name)
{
    for (size_t i = 0; i < t->nverd; i++) if (!strcmp(t->verdicts[i], name)) return 1;
    return 0;
}

static const claim_row *claim_or_gate(const claims *c, const char *name)
{
    char base[80];
    snprintf(base, sizeof base, "%s", name);
    size_t bl = strlen(base);
    if (bl > 4 && !strcmp(base + bl - 4, "Gate")) base[bl - 4] = '\0';
    return claims_find(c, base);
}

/* A name the text uses: registered if capitalised (LaTeX's own aside). */
static void tex_use(tex_scan *t, size_t pos, const char *name)
{
    if (!isupper((unsigned char)name[0]) || tex_lex_latex_own(name)) return;
    if (claim_or_gate(t->c, name)) { (*t->used)++; return; }
    if (audit_design_find(t->design, t->nd, name)) return;
    tex_fail(t, pos, "paper macros", "\\%s has no row in " PATHS_CLAIMS " or " PATHS_DESIGN_NUMBERS "%s", name, "");
}

/* After a definer at s[i]: the defined name (\name, \csname..\endcsname, or
 * {name} for the \@namedef family); records a verdict command; returns the
 * index after the definition's body. */
static size_t tex_definition(tex_scan *t, const char *definer, size_t i)
{
    const char *s = t->text;
    char name[80] = "";
    size_t start = i;
    for (;;) {
        i = tex_lex_space(s, i);
        if (s[i] == '*' || (s[i] == '{' && !tex_lex_is_namedef(definer))) { i++; continue; }
        if (s[i] != '\\') break;
        char cs[80];
        size_t j = tex_lex_cs(s, i, cs, sizeof cs);
        if (!strcmp(cs, "expandafter") || !strcmp(cs, "global") || !strcmp(cs, "long") || !strcmp(cs, "protected") ||
            !strcmp(cs, "outer") || !strcmp(cs, "noexpand")) {
            i = j;
            continue;
        }
        if (!strcmp(cs, "csname")) { i = tex_lex_csname(s, j, name, sizeof name); break; }
        snprintf(name, sizeof name, "%s", cs);
        i = j;
        break;
    }
    if (!name[0] && tex_lex_is_namedef(definer) && s[i] == '{') {
        size_t e = tex_lex_group(s, i, '{', '}'), k = 0;
        for (size_t j = i + 1; j + 1 < e; j++)
            if (isalpha((unsigned char)s[j]) && k + 1 < sizeof name) name[k++] = s[j];
        name[k] = '\0';
        i = e;
    }
    const claim_row *row = name[0] ? claim_or_gate(t->c, name) : NULL;
    if (row)
        tex_fail(t, start, "paper macro redefined",
                 "\\%s defines the claim macro \\%s in the text (only numbers.tex defines it)", definer, name);
    /* the body: after [n][default] and a \def parameter text, one group */
    size_t b = tex_lex_space(s, i);
    if (s[b] == '}') b = tex_lex_space(s, b + 1); /* \newcommand{\name}: its closing brace */
    while (s[b] == '[') b = tex_lex_space(s, tex_lex_group(s, b, '[', ']'));
    while (s[b] && s[b] != '{' && s[b] != '\\' &&
           (s[b] == '#' || isdigit((unsigned char)s[b]) || isspace((unsigned char)s[b])))
        b++;
    if (s[b] != '{' || strcmp(definer, "let") == 0) return i;
    size_t e = tex_lex_group(s, b, '{', '}');
    if (e > t->body_end) t->body_end = e;
    if (t->collect && name[0] && t->nverd < 64) {
        char body[4096];
        snprintf(body, sizeof body, "%.*s", (int)(e - b), s + b);
        if ((strstr(body, "{PASS}") || strstr(body, "{FAIL}")) && !is_verdict_cmd(t, name))
            snprintf(t->verdicts[t->nverd++], 64, "%s", name);
    }
    return b + 1; /* the body is read on: its uses and numbers count too */
}

/* The file an \input-like argument names under paper/ (what TeX opens from
 * paper/): NAME, NAME.tex; for packages and classes NAME.sty / NAME.cls. */
static void tex_pull(tex_scan *t, size_t pos, const char *cmd, const char *arg)
{
    int pkg = !strcmp(cmd, "usepackage") || !strcmp(cmd, "RequirePackage"), cls = !strcmp(cmd, "documentclass");
    int file = !strcmp(cmd, "input") || !strcmp(cmd, "include") || !strcmp(cmd, "InputIfFileExists") ||
               !strcmp(cmd, "subfile");
    if (!pkg && !cls && !file) return;
    char list[512];
    snprintf(list, sizeof list, "%s", arg);
    for (char *sv = NULL, *nm = strtok_r(list, ",", &sv); nm; nm = strtok_r(NULL, ",", &sv)) {
        while (isspace((unsigned char)*nm)) nm++;
        nm[strcspn(nm, " \t\n")] = '\0';
        if (!nm[0]) continue;
        if (nm[0] == '/' || strstr(nm, "..")) {
            if (file)
                tex_fail(t, pos, "paper text", "\\%s pulls in %s, outside paper/: the text is only what paper/ holds",
                         cmd, nm);
            continue;
        }
        char p[600];
        struct stat sb;
        const char *ext[] = {pkg ? ".sty" : cls ? ".cls" : "", file ? ".tex" : NULL};
        for (int k = 0; k < 2 && ext[k]; k++) {
            snprintf(p, sizeof p, PATHS_PAPER_DIR "/%s%s", nm, ext[k]);
            if (stat(p, &sb) == 0 && S_ISREG(sb.st_mode)) {
                int have = 0;
                for (size_t q = 0; q < t->pulled->n && !have; q++) have = !strcmp(t->pulled->p[q], p);
                if (!have) paths_list_add(t->pulled, p);
                break;
            }
        }
    }
}

/* A verdict command's first argument: a generated gate macro (or #n in a definition). */
static void tex_verdict_arg(tex_scan *t, size_t pos, const char *cmd, size_t i)
{
    const char *s = t->text;
    i = tex_lex_space(s, i);
    char arg[128] = "";
    if (s[i] == '{') {
        size_t e = tex_lex_group(s, i, '{', '}');
        snprintf(arg, sizeof arg, "%.*s", (int)(e > i + 2 ? e - i - 2 : 0), s + i + 1);
    }
    char *a = arg;
    while (isspace((unsigned char)*a)) a++;
    size_t n = strlen(a);
    while (n && isspace((unsigned char)a[n - 1])) a[--n] = '\0';
    if (a[0] == '#' && pos < t->body_end) return;
    const claim_row *row = a[0] == '\\' ? claim_or_gate(t->c, a + 1) : NULL;
    if (row && n > 5 && !strcmp(a + n - 4, "Gate") && strcmp(row->gate, "-") &&
        strspn(a + 1, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz") == n - 1)
        return;
    tex_fail(t, pos, "paper verdicts",
             "\\%s{%s}: a verdict command takes a generated gate macro (\\<Claim>Gate from numbers.tex) only", cmd, a);
}

/* A number of the text at s[i..e): a generated macro's job, or a design constant. */
static void tex_number(tex_scan *t, size_t i, size_t e)
{
    const char *s = t->text;
    if (t->collect) return;
    char tok[64];
    snprintf(tok, sizeof tok, "%.*s", (int)(e - i), s + i);
    double x = strtod(tok, NULL);
    int dec, sig;
    token_digits(tok, strlen(tok), &dec, &sig);
    size_t b = i;
    while (b > 0 && (s[b - 1] == '$' || s[b - 1] == ' ' || s[b - 1] == '{')) b--;
    int neg = (b > 0 && s[b - 1] == '-') || (b >= 3 && !memcmp(s + b - 3, "\xe2\x88\x92", 3));
    if (dec > 0 && sig >= 2)
        for (size_t q = 0; q < t->nv; q++)
            if (rounds_to(x, dec, sig, neg, t->vals[q])) {
                char m[300];
                snprintf(m, sizeof m, "'%s' typed by hand rounds the measured value %.6g; use \\%s; claim: %s", tok,
                         t->vals[q], t->who[q], t->who[q]);
                tex_fail(t, i, "hand-typed numbers", "%s%s", m, "");
                return;
            }
    tex_fail(t, i, "hand-typed numbers",
             "'%s' is typed in the text: a measured value prints through its macro of numbers.tex, a design constant "
             "through its macro of constants.tex (" PATHS_DESIGN_NUMBERS ")%s",
             tok, "");
}

/* Comments blanked (an exemption request is itself a failure); returns the copy. */
static char *tex_strip(tex_scan *t, const char *raw, size_t n)
{
    char *s = malloc(n + 1);
    if (!s) return NULL;
    memcpy(s, raw, n + 1);
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '\\' && s[i + 1]) { i++; continue; }
        if (s[i] != '%') continue;
        size_t e = i;
        while (e < n && s[e] != '\n') e++;
        char com[4096];
        snprintf(com, sizeof com, "%.*s", (int)(e - i - 1), s + i + 1);
        if (exemption_comment(com) && !t->collect) {
            checklist_add(t->cl, VERDICT_FAIL, "paper self-exemption",
                          "%s:%d: comment '%.80s' asks for an exemption from the audit: none is honoured; remove it",
                          t->path, tex_lex_line(raw, i), com);
            t->bad++;
        }
        memset(s + i, ' ', e - i);
        i = e;
    }
    return s;
}

/* A branch of the text's own: the render could show one side only. The text
 * branches through the generated \ifpass and \ifsame, whose both sides the
 * render prints. */
static void tex_control(tex_scan *t, size_t pos, const char *cs)
{
    if (!strcmp(cs, "ifpass") || !strcmp(cs, "ifsame")) return;
    if (!strncmp(cs, "if", 2) || !strncmp(cs, "If", 2) || !strcmp(cs, "unless") || !strcmp(cs, "else") ||
        !strcmp(cs, "fi") || !strcmp(cs, "or"))
        tex_fail(t, pos, "paper text",
                 "\\%s: the text branches only through \\ifpass or \\ifsame (generated), whose both sides the audit's "
                 "render shows%s",
                 cs, "");
}

static void tex_scan_text(tex_scan *t)
{
    const char *s = t->text;
    for (size_t i = 0; s[i];) {
        if (s[i] == '\\') {
            char cs[80];
            size_t j = tex_lex_cs(s, i, cs, sizeof cs), at = i;
            if (!strcmp(cs, "catcode"))
                tex_fail(t, at, "paper text",
                         "\\%s changes how TeX reads the characters that follow: not allowed in the text%s", cs, "");
            if (!strcmp(cs, "csname")) {
                char nm[80];
                j = tex_lex_csname(s, j, nm, sizeof nm);
                if (nm[0]) { tex_use(t, at, nm); tex_control(t, at, nm); }
                i = j;
                continue;
            }
            if (tex_lex_is_definer(cs) || tex_lex_is_namedef(cs)) {
                tex_fail(t, at, "paper text",
                         "\\%s: the text defines no command of its own (its helpers, \\verdict \\ifpass \\ifsame "
                         "\\bandpos \\fig, are generated in numbers.tex)%s",
                         cs, "");
                i = tex_definition(t, cs, j);
                continue;
            }
            tex_control(t, at, cs);
            if (is_verdict_cmd(t, cs) && !t->collect) tex_verdict_arg(t, at, cs, j);
            if (tex_lex_names_arg(cs)) {
                size_t k = tex_lex_space(s, j);
                while (s[k] == '[') k = tex_lex_space(s, tex_lex_group(s, k, '[', ']'));
                if (s[k] == '{') {
                    size_t e = tex_lex_group(s, k, '{', '}');
                    char arg[512];
                    snprintf(arg, sizeof arg, "%.*s", (int)(e > k + 2 ? e - k - 2 : 0), s + k + 1);
                    tex_pull(t, at, cs, arg);
                    /* a name argument holds no text, but a macro in it is still used */
                    for (size_t q = k; q < e; q++)
                        if (s[q] == '\\') {
                            char u[80];
                            q = tex_lex_cs(s, q, u, sizeof u) - 1;
                            if (u[0] && isalpha((unsigned char)u[0])) tex_use(t, q, u);
                        }
                    j = e;
                }
            } else if (isalpha((unsigned char)cs[0])) tex_use(t, at, cs);
            i = j;
            continue;
        }
        if ((!strncmp(s + i, "PASS", 4) || !strncmp(s + i, "FAIL", 4)) &&
            (i == 0 || !isalnum((unsigned char)s[i - 1])) && !isalnum((unsigned char)s[i + 4])) {
            if (i >= t->body_end)
                tex_fail(t, i, "paper verdicts",
                         "'%.4s' typed in the text: a verdict comes from a generated gate macro only%s", s + i, "");
            i += 4;
            continue;
        }
        if (isdigit((unsigned char)s[i])) {
            size_t e = i;
            while (isdigit((unsigned char)s[e])) e++;
            if (s[e] == '.' && isdigit((unsigned char)s[e + 1])) { e++; while (isdigit((unsigned char)s[e])) e++; }
            char p = i ? s[i - 1] : ' ';
            int ident = isalnum((unsigned char)p) || p == '_' || p == '#' || p == '!' || p == '.' || s[e] == '!' ||
                        isalpha((unsigned char)s[e]) || (p == '-' && i >= 2 && isalnum((unsigned char)s[i - 2])) ||
                        tex_lex_is_unit(s + e);
            if (!ident) tex_number(t, i, e);
            i = e;
            continue;
        }
        i++;
    }
}

static size_t tex_scan_path(tex_scan *t, const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        if (!t->collect) {
            checklist_add(t->cl, VERDICT_FAIL, "paper text", "%s: cannot read", path);
            t->bad++;
        }
        return 1;
    }
    size_t cap = 1 << 16, n = 0;
    char *raw = malloc(cap);
    for (size_t k; raw && (k = fread(raw + n, 1, cap - n - 1, f)) > 0;) {
        n += k;
        if (n + 1 == cap) { char *nr = cap < (1u << 24) ? realloc(raw, cap *= 2) : NULL; if (!nr) break; raw = nr; }
    }
    fclose(f);
    if (!raw) return 1;
    raw[n] = '\0';
    size_t before = t->bad;
    t->path = path;
    t->body_end = 0;
    char *text = tex_strip(t, raw, strlen(raw));
    if (text) { t->text = text; tex_scan_text(t); }
    free(text);
    free(raw);
    return t->bad - before;
}

size_t paper_scan_file(const char *path, const claims *c, const double *vals, const char *const *who, size_t nv,
                       checklist *cl, size_t *used)
{
    static char verdicts[64][64];
    paths_list pulled = {0};
    snprintf(verdicts[0], 64, "verdict");
    snprintf(verdicts[1], 64, "ifpass");
    tex_scan t = {c, vals, who, nv, NULL, 0, cl, used, 0, 1, verdicts, 2, &pulled, path, "", 0};
    tex_scan_path(&t, path);
    t.collect = 0;
    size_t bad = tex_scan_path(&t, path);
    paths_list_free(&pulled);
    return bad;
}

void audit_paper_text(const claims *c, const claim_result *res, checklist *cl)
{
    paths_list files = {0};
    paths_list_files(PATHS_PAPER_DIR, ".tex", 1, &files);
    size_t used = 0;
    /* the measured values a number in the text must not round */
    double *vals = calloc(2 * (c->n ? c->n : 1), sizeof *vals);
    design_const *design = NULL;
    const char **who = calloc(2 * (c->n ? c->n : 1), sizeof *who);
    size_t nv = 0, before = cl->n;
    for (size_t r = 0; vals && who && r < c->n; r++) {
        if (strcmp(c->rows[r].kind, "measured") && strcmp(c->rows[r].kind, "needs-data") &&
            strcmp(c->rows[r].kind, "probe") && !claims_kind_beside(c->rows[r].kind))
            continue;
        char *end;
        double ref = strtod(c->rows[r].reference, &end);
        if (res[r].status == VERDICT_PASS && isfinite(res[r].value)) {
            vals[nv] = res[r].value;
            who[nv++] = c->rows[r].macro;
        }
        if (end != c->rows[r].reference && !*end && isfinite(ref)) { vals[nv] = ref; who[nv++] = c->rows[r].macro; }
    }
    size_t nd = audit_design_consts(cl, &design);
    static char verdicts[64][64];
    snprintf(verdicts[0], 64, "verdict");
    snprintf(verdicts[1], 64, "ifpass");
    tex_scan t = {c, vals, (const char *const *)who, nv, design, nd, cl, &used, 0, 1, verdicts, 2, &files, "", "", 0};
    /* pass 1 follows every \input, \include and local package and collects the
     * verdict commands; pass 2 checks every file so found */
    for (size_t i = 0; i < files.n; i++) if (!paper_is_generated(files.p[i])) tex_scan_path(&t, files.p[i]);
    t.collect = 0;
    size_t scanned = 0;
    for (size_t i = 0; i < files.n; i++) {
        if (paper_is_generated(files.p[i])) continue; /* compared with a fresh generation instead */
        tex_scan_path(&t, files.p[i]);
        scanned++;
    }
    free(vals);
    free(who);
    free(design);
    int bad = 0;
    for (size_t i = before; i < cl->n; i++) bad |= cl->items[i].v == VERDICT_FAIL;
    if (!bad)
        checklist_add(cl, VERDICT_PASS, "paper text",
                      "%zu hand-written paper files read as TeX reads them (every file pulled in): %zu claim-macro "
                      "uses, all registered; no command defined, no branch but the generated ones; %zu verdict "
                      "commands, each with a generated gate macro; no number typed (each a macro of numbers.tex or one "
                      "of %zu design constants of constants.tex); no exemption comment",
                      scanned, used, t.nverd, nd);
    paths_list_free(&files);
}
