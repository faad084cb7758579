/* audit_docs: the documentation pages against frozen/ (design.md §9): their
 * generated regions equal a fresh generation, no measured number is typed
 * outside them (the rounding rule of the paper text), no comment asks for an
 * exemption, every relative link resolves. Limits: a marker lies on one line;
 * a number is a plain decimal token ("1.2.0" and "127.0.0.1" are not numbers). */
#include "audit_docs.h"
#include "afile.h"
#include "docs_render.h"
#include "tsv.h"
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* ---- the typed-number rule (as for the paper text) ---- */
/* Does "code FILE" hold lit as a whole token? */
static int code_holds(const char *src, const char *lit)
{
    if (strncmp(src, "code ", 5) || !lit || !*lit) return 0;
    FILE *f = fopen(src + 5, "r");
    if (!f) return 0;
    char *line = NULL;
    size_t cap = 0, ll = strlen(lit);
    int found = 0;
    while (!found && getline(&line, &cap, f) > 0)
        for (char *p = line; !found && (p = strstr(p, lit)); p++)
            found = (p == line || !(isalnum((unsigned char)p[-1]) || p[-1] == '.')) &&
                    !(isalnum((unsigned char)p[ll]) || (p[ll] == '.' && isdigit((unsigned char)p[ll + 1])));
    free(line);
    fclose(f);
    return found;
}

/* The values a typed decimal must not round: ours (text: what a marker
 * shows) and the reference paper's (paper = 1); and the design constants it
 * may equal all the same (d, nd). */
typedef struct { double *v; const char **who, **text; int *paper; size_t n; double *d; size_t nd; } measured;

/* A design constant a page may type although a measured value rounds to it:
 * every value of the paper's list (PATHS_DESIGN_NUMBERS, checked at its
 * sources by the paper audit) and of PATHS_DOC_NUMBERS, whose source "code
 * FILE" must hold the number as a literal. A bad row fails naming its line. */
static size_t design_constants(double **out, checklist *cl, size_t *bad)
{
    const char *files[2] = {PATHS_DESIGN_NUMBERS, PATHS_DOC_NUMBERS};
    size_t n = 0, cap = 0;
    *out = NULL;
    *bad = 0;
    for (int fi = 0; fi < 2; fi++) {
        tsv *t;
        if (tsv_read(files[fi], &t)) {
            if (fi && cl) checklist_add(cl, VERDICT_FAIL, "docs: design constants", "%s", cs_errmsg());
            *bad += fi;
            continue;
        }
        for (size_t r = 0; r < tsv_nrows(t); r++) {
            double x;
            const char *src = tsv_str(t, r, "source");
            if (tsv_double(t, r, "value", &x) || !src) continue;
            if (fi && (!code_holds(src, tsv_str(t, r, "value")) || !tsv_str(t, r, "what"))) {
                if (cl)
                    checklist_add(cl, VERDICT_FAIL, "docs: design constants",
                                  "%s:%d: source '%s' does not hold %s as a literal (or no 'what')", files[fi],
                                  tsv_line(t, r), src, tsv_str(t, r, "value"));
                (*bad)++;
                continue;
            }
            if (n == cap) {
                double *d = realloc(*out, (cap = cap ? 2 * cap : 64) * sizeof *d);
                if (!d) break;
                *out = d;
            }
            (*out)[n++] = x;
        }
        tsv_free(t);
    }
    return n;
}

static void measured_collect(const claims *c, const claim_result *res, measured *m)
{
    m->n = 0;
    m->v = calloc(2 * (c->n ? c->n : 1), sizeof *m->v);
    m->who = calloc(2 * (c->n ? c->n : 1), sizeof *m->who);
    m->text = calloc(2 * (c->n ? c->n : 1), sizeof *m->text);
    m->paper = calloc(2 * (c->n ? c->n : 1), sizeof *m->paper);
    for (size_t r = 0; m->v && m->who && m->text && m->paper && r < c->n; r++) {
        const char *k = c->rows[r].kind;
        if (strcmp(k, "measured") && strcmp(k, "needs-data") && strcmp(k, "probe") && !claims_kind_beside(k)) continue;
        char *end;
        double ref = strtod(c->rows[r].reference, &end);
        if (res[r].status == VERDICT_PASS && isfinite(res[r].value)) {
            m->v[m->n] = res[r].value;
            m->who[m->n] = c->rows[r].macro;
            m->text[m->n] = res[r].text;
            m->paper[m->n++] = 0;
        }
        if (end != c->rows[r].reference && !*end && isfinite(ref)) {
            m->v[m->n] = ref;
            m->who[m->n] = c->rows[r].macro;
            m->text[m->n] = c->rows[r].reference;
            m->paper[m->n++] = 1;
        }
    }
}

/* Does x (dec decimals, sig significant digits; neg: a minus precedes it)
 * round v? A value of the other sign counts from 3 significant digits. */
static int rounds(double x, int dec, int sig, int neg, double v)
{
    if (!isfinite(v) || dec > 12) return 0;
    double scale = pow(10.0, dec);
    if (fabs(fabs(x) - fabs(round(v * scale) / scale)) >= 0.25 / scale) return 0;
    return ((v < 0) == neg) || sig >= 3;
}

static int exemption(const char *comment, size_t len)
{
    char low[512];
    size_t i = 0;
    for (; i < len && i < sizeof low - 1; i++) low[i] = (char)tolower((unsigned char)comment[i]);
    low[i] = '\0';
    static const char *words[] = {"exempt",     "nocheck",   "no-check",   "no check", "ignore",
                                  "skip-audit", "audit-off", "audit: off", NULL};
    for (int k = 0; words[k]; k++) if (strstr(low, words[k])) return 1;
    return 0;
}

/* The numbers of one line typed by hand (markers already blanked). */
static size_t scan_numbers(const char *path, int lineno, const char *line, const measured *m, checklist *cl)
{
    size_t bad = 0;
    for (const char *s = line; *s; ) {
        if (!isdigit((unsigned char)*s) || (s > line && (isalnum((unsigned char)s[-1]) || strchr("\\_.", s[-1])))) {
            s++;
            continue;
        }
        /* a section reference (§3.1, § 5.2) is no number of the study */
        {
            const char *q = s;
            if (q > line && q[-1] == ' ') q--;
            if (q - line >= 2 && (unsigned char)q[-2] == 0xC2 && (unsigned char)q[-1] == 0xA7) {
                while (isdigit((unsigned char)*s) || (*s == '.' && isdigit((unsigned char)s[1]))) s++;
                continue;
            }
        }
        const char *e = s;
        while (isdigit((unsigned char)*e)) e++;
        int dec = 0, sig = 0, lead = 1;
        if (*e == '.' && isdigit((unsigned char)e[1])) { e++; while (isdigit((unsigned char)e[dec])) dec++; e += dec; }
        int dotted = *e == '.' && isdigit((unsigned char)e[1]);
        for (const char *q = s; q < e; q++) if (isdigit((unsigned char)*q) && !(lead && *q == '0')) { lead = 0; sig++; }
        if (dec > 0 && sig >= 2 && !dotted && !isalpha((unsigned char)*e)) {
            double x = strtod(s, NULL);
            const char *b = s;
            while (b > line && (b[-1] == '$' || b[-1] == ' ' || b[-1] == '*' || b[-1] == '`')) b--;
            int neg = (b > line && b[-1] == '-') || (b - line >= 3 && !memcmp(b - 3, "\xe2\x88\x92", 3));
            int constant = 0;
            for (size_t q = 0; q < m->nd && !constant; q++) constant = fabs(x - m->d[q]) <= 1e-9 * fmax(1.0, fabs(x));
            for (size_t q = 0; q < m->n && !constant; q++)
                if (rounds(x, dec, sig, neg, m->v[q])) {
                    checklist_add(cl, VERDICT_FAIL, "docs: typed numbers",
                                  "%s:%d: '%.*s' typed by hand rounds %s %.6g; write <!--%s%s-->%s" DOCS_MARK_END
                                  " (crownshy numbers fills it); claim: %s",
                                  path, lineno, (int)(e - s), s,
                                  m->paper[q] ? "the reference paper's value" : "the measured value", m->v[q],
                                  m->who[q], m->paper[q] ? "Paper" : "", m->text[q], m->who[q]);
                    bad++;
                    break;
                }
        }
        while (*e == '.' && isdigit((unsigned char)e[1])) { e++; while (isdigit((unsigned char)*e)) e++; }
        s = e;
    }
    return bad;
}

/* Relative links [text](target) must name an existing file or folder. */
static size_t scan_links(const char *path, int lineno, const char *line, checklist *cl)
{
    size_t bad = 0;
    const char *slash = strrchr(path, '/');
    for (const char *s = line; (s = strstr(s, "](")); s += 2) {
        const char *t = s + 2, *e = t;
        while (*e && *e != ')' && *e != ' ' && *e != '#') e++;
        size_t tl = (size_t)(e - t);
        if (!tl || !strncmp(t, "http://", 7) || !strncmp(t, "https://", 8) || !strncmp(t, "mailto:", 7)) continue;
        char p[1024];
        snprintf(p, sizeof p, "%.*s%.*s", slash ? (int)(slash - path + 1) : 0, path, (int)tl, t);
        struct stat sb;
        if (stat(p, &sb) != 0) {
            checklist_add(cl, VERDICT_FAIL, "docs: links", "%s:%d: link to '%.*s': %s does not exist", path, lineno,
                          (int)tl, t, p);
            bad++;
        }
    }
    return bad;
}

/* The hand-written lines: markers blanked, comments read for exemptions. */
static size_t scan_page(const char *path, const measured *m, checklist *cl)
{
    FILE *f = fopen(path, "r");
    if (!f) { checklist_add(cl, VERDICT_FAIL, "docs", "%s: cannot read", path); return 1; }
    size_t bad = 0, cap = 0;
    char *line = NULL;
    int lineno = 0, in_block = 0;
    while (getline(&line, &cap, f) > 0) {
        lineno++;
        if (in_block) { in_block = strncmp(line, DOCS_FIND_END, strlen(DOCS_FIND_END)) != 0; continue; }
        if (!strncmp(line, DOCS_FIND_BEGIN, strlen(DOCS_FIND_BEGIN))) { in_block = 1; continue; }
        for (char *s = line; (s = strstr(s, "<!--")); ) {
            size_t nl;
            const char *v, *ve;
            if (docs_render_marker(line, s, &nl, &v, &ve)) {
                size_t k = (size_t)(ve + strlen(DOCS_MARK_END) - s);
                memset(s, ' ', k);
                s += k;
                continue;
            }
            char *e = strstr(s + 4, "-->");
            size_t len = e ? (size_t)(e - s - 4) : strlen(s + 4);
            if (exemption(s + 4, len)) {
                checklist_add(cl, VERDICT_FAIL, "docs: self-exemption",
                              "%s:%d: comment '%.*s' asks for an exemption from the audit: none is honoured; remove it",
                              path, lineno, (int)(len < 80 ? len : 80), s + 4);
                bad++;
            }
            s += 4;
        }
        bad += scan_links(path, lineno, line, cl);
        bad += scan_numbers(path, lineno, line, m, cl);
    }
    free(line);
    fclose(f);
    return bad;
}

/* First line where text and the file differ (0: none); that file line in lb,
 * and in *col the first column where they differ. */
static int first_diff(const char *path, const char *text, char *lb, size_t n, size_t *col)
{
    *col = 0;
    FILE *f = fopen(path, "r");
    if (!f) return 1;
    char *line = NULL;
    size_t cap = 0;
    int lineno = 0, diff = 0;
    const char *t = text;
    for (;;) {
        ssize_t k = getline(&line, &cap, f);
        lineno++;
        size_t tl = strcspn(t, "\n");
        if (k <= 0) { diff = *t ? lineno : 0; lb[0] = '\0'; break; }
        size_t ll = strcspn(line, "\n");
        if (!*t || ll != tl || strncmp(line, t, tl)) {
            diff = lineno;
            snprintf(lb, n, "%.*s", (int)ll, line);
            while (*col < ll && *col < tl && line[*col] == t[*col]) (*col)++;
            break;
        }
        t += tl + (t[tl] == '\n');
    }
    free(line);
    fclose(f);
    return diff;
}

size_t docs_check_page(const char *path, const claims *c, const claim_result *res, checklist *cl)
{
    char *fresh;
    size_t bad = 0;
    if (docs_render(path, c, res, &fresh)) {
        checklist_add(cl, VERDICT_FAIL, "docs: generated", "%s", cs_errmsg());
        return 1;
    }
    char lb[4096];
    size_t col;
    int d = first_diff(path, fresh, lb, sizeof lb, &col);
    free(fresh);
    if (d) {
        /* the claim of the marker where the line first differs */
        char claim[96] = "";
        for (const char *s = lb; (s = strstr(s, "<!--")) && (size_t)(s - lb) <= col; s += 4) {
            size_t nl;
            const char *v, *ve;
            if (docs_render_marker(lb, s, &nl, &v, &ve)) snprintf(claim, sizeof claim, "; claim: %.*s", (int)nl, s + 4);
        }
        checklist_add(cl, VERDICT_FAIL, "docs: generated",
                      "%s:%d differs from a fresh generation ('%.200s'): edited by hand or stale (crownshy numbers "
                      "regenerates it)%s",
                      path, d, lb, claim);
        bad++;
    }
    measured m;
    measured_collect(c, res, &m);
    size_t dbad;
    m.nd = design_constants(&m.d, NULL, &dbad);
    bad += scan_page(path, &m, cl);
    free(m.d);
    free(m.v);
    free(m.who);
    free(m.text);
    free(m.paper);
    return bad;
}

cs_status docs_pages(paths_list *out)
{
    memset(out, 0, sizeof *out);
    cs_status st = paths_list_add(out, PATHS_README);
    static const char *const dirs[] = PATHS_DOCS_DIRS;
    for (int i = 0; !st && dirs[i]; i++) {
        paths_list l;
        if ((st = paths_list_files(dirs[i], ".md", 1, &l))) break;
        for (size_t k = 0; !st && k < l.n; k++)
            if (strcmp(l.p[k], PATHS_CHANGELOG)) st = paths_list_add(out, l.p[k]);
        paths_list_free(&l);
    }
    if (st) paths_list_free(out);
    return st;
}

void audit_docs(const claims *c, const claim_result *res, checklist *cl)
{
    paths_list pages;
    if (docs_pages(&pages)) { checklist_add(cl, VERDICT_FAIL, "docs", "%s", cs_errmsg()); return; }
    size_t bad = 0, regions = 0;
    double *d;
    design_constants(&d, cl, &bad); /* its rows checked once, here */
    free(d);
    struct stat sb;
    if (stat(PATHS_README, &sb) != 0) { checklist_add(cl, VERDICT_FAIL, "docs", "%s missing", PATHS_README); bad++; }
    for (size_t i = 0; i < pages.n; i++) {
        if (stat(pages.p[i], &sb) != 0) continue;
        bad += docs_check_page(pages.p[i], c, res, cl);
        FILE *f = fopen(pages.p[i], "r");
        char *line = NULL;
        size_t cap = 0;
        while (f && getline(&line, &cap, f) > 0)
            for (const char *s = line; (s = strstr(s, "<!--")); s += 4) {
                size_t nl;
                const char *v, *ve;
                regions +=
                    docs_render_marker(line, s, &nl, &v, &ve) || !strncmp(s, DOCS_FIND_BEGIN, strlen(DOCS_FIND_BEGIN));
            }
        free(line);
        if (f) fclose(f);
    }
    if (!bad)
        checklist_add(cl, VERDICT_PASS, "docs",
                      "%zu documentation pages (%s and the reference pages): %zu generated regions equal a fresh "
                      "generation; no measured number typed; no exemption comment; every relative link resolves",
                      pages.n, PATHS_README, regions);
    paths_list_free(&pages);
}

cs_status docs_refresh(const claims *c, const claim_result *res, size_t *changed)
{
    *changed = 0;
    paths_list pages;
    cs_status st = docs_pages(&pages);
    if (st) return st;
    for (size_t i = 0; !st && i < pages.n; i++) {
        struct stat sb;
        if (stat(pages.p[i], &sb) != 0) continue;
        char *fresh, lb[8];
        size_t col;
        if ((st = docs_render(pages.p[i], c, res, &fresh))) break;
        if (first_diff(pages.p[i], fresh, lb, sizeof lb, &col)) {
            afile a;
            if (!(st = afile_open(&a, pages.p[i]))) {
                if (fputs(fresh, a.f) < 0) a.err = 1;
                st = afile_commit(&a);
                (*changed)++;
            }
        }
        free(fresh);
    }
    paths_list_free(&pages);
    return st;
}
