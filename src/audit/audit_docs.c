/* audit_docs: the documentation pages against frozen/ (design.md §9): their
 * generated regions equal a fresh generation, no measured number is typed
 * outside them (the rounding rule of the paper text), no comment asks for an
 * exemption, every relative link resolves. Limits: a marker lies on one line;
 * a number is a plain decimal token ("1.2.0" and "127.0.0.1" are not numbers). */
#include "audit_docs.h"
#include "agree.h"
#include "afile.h"
#include "audit_evidence.h"
#include "tsv.h"
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define FIND_BEGIN "<!-- findings"
#define FIND_END "<!-- /findings -->"
#define MARK_END "<!--/-->"

/* ---- a growing string ---- */
typedef struct { char *s; size_t n, cap; int err; } sbuf;

static void sb_printf(sbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void sb_printf(sbuf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (k < 0 || b->err) { b->err = 1; return; }
    if (b->n + (size_t)k + 1 > b->cap) {
        size_t cap = (b->cap ? 2 * b->cap : 4096) + (size_t)k;
        char *s = realloc(b->s, cap);
        if (!s) { b->err = 1; return; }
        b->s = s;
        b->cap = cap;
    }
    va_start(ap, fmt);
    vsnprintf(b->s + b->n, b->cap - b->n, fmt, ap);
    va_end(ap);
    b->n += (size_t)k;
}

/* ---- generated text ---- */
/* The text a marker stands for: the claim's numbers.tex text, or its verdict. */
static int marker_text(const char *name, const claims *c, const claim_result *res, char *buf, size_t n)
{
    char base[80];
    snprintf(base, sizeof base, "%s", name);
    size_t bl = strlen(base);
    int gate = bl > 4 && !strcmp(base + bl - 4, "Gate"), paper = bl > 5 && !strcmp(base + bl - 5, "Paper");
    if (gate) base[bl - 4] = '\0';
    if (paper) base[bl - 5] = '\0';
    const claim_row *row = claims_find(c, base);
    if (!row || (gate && !strcmp(row->gate, "-")) || (paper && !strcmp(row->reference, "-"))) return 0;
    const claim_result *r = &res[row - c->rows];
    if (gate) snprintf(buf, n, "%s", verdict_name(r->gate));
    else if (paper) snprintf(buf, n, "%s", row->reference);
    else if (r->status == VERDICT_PASS) snprintf(buf, n, "%s", r->text);
    else snprintf(buf, n, "pending");
    return 1;
}

/* A claim computed from a table made by a superseded reading: pending until
 * its unit is re-run (as verify counts it). */
static int superseded(const claim_row *row)
{
    return !strncmp(row->source, PATHS_FROZEN_DIR "/", strlen(PATHS_FROZEN_DIR) + 1) &&
           audit_table_superseded(row->source);
}

/* A gated claim's verdict as verify counts it: 0 reproduced, 1 not, 2 pending. */
static int judged(const claim_row *row, const claim_result *r)
{
    if (superseded(row)) return 2;
    return r->gate == VERDICT_PASS ? 0 : r->gate == VERDICT_FAIL ? 1 : 2;
}

/* Where the gate judges another quantity than the one shown (a ratio formed
 * from the shown value): " (gate: <quantity> <op> <threshold>)", from the
 * gate's own detail; "" where the shown value is what the gate judged. */
static void gate_judged_text(const claim_row *row, const claim_result *r, char *buf, size_t n)
{
    buf[0] = '\0';
    if (r->status != VERDICT_PASS || !r->has_observed || !isfinite(r->gate_observed) || !strcmp(row->format, "text"))
        return;
    char t[64];
    snprintf(t, sizeof t, row->format, r->gate_observed);
    if (!strcmp(t, r->text) || fabs(r->gate_observed * 100 - r->value) <= 1e-9 * fabs(r->value)) return;
    /* the detail reads "<observed> <op> <threshold>[ (...)|; ...]": keep op and threshold */
    const char *op = strchr(r->gate_detail, ' ');
    size_t len = op ? strcspn(op, "(;") : 0;
    while (len && op[len - 1] == ' ') len--;
    snprintf(buf, n, " (judged %.3g%.*s)", r->gate_observed, (int)len, op ? op : "");
}

/* The group a gated claim is tallied in: 0 the reference paper's, 1 the pair
 * extension's, 2 a training choice's at the gate's seeds (kind variant). */
static int group_of(const claim_row *row)
{
    return !claims_is_beside(row) ? 0 : !strcmp(row->kind, "extension") ? 1 : 2;
}

/* One table row per gate file: the gated claims of group ext with our value
 * beside the paper's. */
static void findings_rows(sbuf *b, const claims *c, const claim_result *res, int ext)
{
    for (size_t i = 0; i < c->n; i++) {
        const char *g = c->rows[i].gate;
        size_t gl = strcspn(g, ":");
        if (!strcmp(g, "-") || group_of(&c->rows[i]) != ext) continue;
        int first = 1;
        for (size_t j = 0; j < i && first; j++)
            first = group_of(&c->rows[j]) != ext || strncmp(c->rows[j].gate, g, gl) || c->rows[j].gate[gl] != ':';
        if (!first) continue;
        size_t k[3] = {0};
        sbuf cl = {0};
        for (size_t j = i; j < c->n; j++) {
            if (group_of(&c->rows[j]) != ext || strncmp(c->rows[j].gate, g, gl) || c->rows[j].gate[gl] != ':') continue;
            k[judged(&c->rows[j], &res[j])]++;
            char judged_as[96];
            gate_judged_text(&c->rows[j], &res[j], judged_as, sizeof judged_as);
            sb_printf(&cl, "%s`%s` %s%s%s / %s", cl.n ? "; " : "", c->rows[j].macro,
                      res[j].status == VERDICT_PASS ? res[j].text : "pending", judged_as,
                      res[j].status == VERDICT_PASS && superseded(&c->rows[j]) ? " (superseded reading)" : "",
                      c->rows[j].reference);
        }
        sb_printf(b, "| `" PATHS_GATES_DIR "/%.*s`%s | %zu | %zu | %zu | %s |\n", (int)gl, g, ext ? " (pair)" : "",
                  k[0], k[1], k[2],
                  cl.err ? "(out of memory)"
                  : cl.s ? cl.s
                         : "");
        free(cl.s);
    }
}

/* The findings: the gated claims per gate file, our value beside the paper's;
 * the extension's claims in rows of their own, never in the paper's tally. */
static void findings(sbuf *b, const claims *c, const claim_result *res)
{
    size_t k[3] = {0}, ke[3] = {0}, kv[3] = {0}, sup = 0;
    for (size_t i = 0; i < c->n; i++) {
        if (!strcmp(c->rows[i].gate, "-")) continue;
        const int grp = group_of(&c->rows[i]);
        if (grp) { (grp == 1 ? ke : kv)[judged(&c->rows[i], &res[i])]++; continue; }
        k[judged(&c->rows[i], &res[i])]++;
        sup += superseded(&c->rows[i]) != 0;
    }
    /* the agreement classes against our own intervals (design.md §6.1) */
    const claim_interval *ci = NULL;
    agree_counts ak = {0};
    attrib_data at = {0};
    if (!agree_intervals_cached(c, res, &ci) && !attrib_load(PATHS_READINGS_SUMMARY, PATHS_SENS_SUMMARY, &at)) {
        attrib_bind(&at, c, res, ci);
        agree_count(&at, c, res, ci, &ak);
        attrib_free(&at);
    }
    sb_printf(b,
              "Gates (does our value meet the paper's preregistered threshold?) on the reference paper's claims: "
              "**%zu reproduced, %zu not reproduced, %zu pending** (pending: data not on this machine, or units still "
              "running%s). "
              "The pair extension, same thresholds (rows marked pair): %zu meet, %zu do not, %zu pending. "
              "Two training choices at the gate's seeds (variants, same thresholds; `make verify` lists them): %zu "
              "meet, %zu do not, %zu pending. "
              "Agreement (is the paper's value inside our 95 %% interval? `crownshy report`): %zu inside, %zu reached "
              "by a reading or choice, "
              "%zu unexplained, %zu without an interval. A claim can meet its gate and still disagree.\n\n",
              k[0], k[1], k[2],
              sup ? ", or a table made by a superseded reading of the pinned code, until its unit is re-run" : "",
              ke[0], ke[1], ke[2], kv[0], kv[1], kv[2], ak.inside, ak.reached, ak.unexplained, ak.nointerval);
    sb_printf(b, "| gate | reproduced | not reproduced | pending | claims: ours / paper |\n|---|---|---|---|---|\n");
    findings_rows(b, c, res, 0);
    findings_rows(b, c, res, 1);
}

/* Is s inside a code span of line (an odd number of backticks before it)? A
 * marker there is literal text, as Markdown renders it. */
static int in_code(const char *line, const char *s)
{
    int k = 0;
    for (const char *q = line; q < s; q++) k += *q == '`';
    return k & 1;
}

/* The inline marker at s ("<!--Name-->") of line: its name length and where
 * its value starts and ends; 0 when s is no marker. */
static int marker_at(const char *line, const char *s, size_t *nl, const char **v, const char **ve)
{
    if (strncmp(s, "<!--", 4) || in_code(line, s)) return 0;
    size_t k = 0;
    while (isalnum((unsigned char)s[4 + k])) k++;
    if (!k || !isalpha((unsigned char)s[4]) || strncmp(s + 4 + k, "-->", 3)) return 0;
    const char *e = strstr(s + 7 + k, MARK_END);
    if (!e) return 0;
    *nl = k;
    *v = s + 7 + k;
    *ve = e;
    return 1;
}

static void render_line(sbuf *b, const char *line, const claims *c, const claim_result *res, char *unknown, size_t un)
{
    for (const char *s = line; *s; ) {
        size_t nl;
        const char *v, *ve;
        if (!marker_at(line, s, &nl, &v, &ve)) { sb_printf(b, "%c", *s++); continue; }
        char name[80], text[160];
        snprintf(name, sizeof name, "%.*s", (int)(nl < 79 ? nl : 79), s + 4);
        if (marker_text(name, c, res, text, sizeof text)) sb_printf(b, "<!--%s-->%s" MARK_END, name, text);
        else {
            if (!unknown[0]) snprintf(unknown, un, "%s", name);
            sb_printf(b, "%.*s", (int)(ve + strlen(MARK_END) - s), s);
        }
        s = ve + strlen(MARK_END);
    }
}

cs_status docs_render(const char *path, const claims *c, const claim_result *res, char **out)
{
    *out = NULL;
    FILE *f = fopen(path, "r");
    if (!f) return cs_err(CS_EINPUT, "%s: cannot open", path);
    sbuf b = {0};
    char *line = NULL, unknown[80] = "";
    size_t cap = 0;
    int lineno = 0, in_block = 0, block_line = 0, bad_line = 0;
    while (getline(&line, &cap, f) > 0) {
        lineno++;
        if (in_block) {
            if (!strncmp(line, FIND_END, strlen(FIND_END))) { in_block = 0; sb_printf(&b, "%s", line); }
            continue;
        }
        if (!strncmp(line, FIND_BEGIN, strlen(FIND_BEGIN))) {
            sb_printf(&b, "%s", line);
            findings(&b, c, res);
            in_block = 1;
            block_line = lineno;
            continue;
        }
        render_line(&b, line, c, res, unknown, sizeof unknown);
        if (unknown[0] && !bad_line) bad_line = lineno;
    }
    free(line);
    fclose(f);
    if (in_block) {
        free(b.s);
        return cs_err(CS_EINPUT, "%s:%d: %s... has no closing %s", path, block_line, FIND_BEGIN, FIND_END);
    }
    if (bad_line) {
        free(b.s);
        return cs_err(CS_EINPUT, "%s:%d: marker <!--%s--> names no claim of %s", path, bad_line, unknown, PATHS_CLAIMS);
    }
    if (b.err) { free(b.s); return cs_err(CS_ENOMEM, "out of memory"); }
    *out = b.s ? b.s : calloc(1, 1);
    return *out ? CS_OK : cs_err(CS_ENOMEM, "out of memory");
}

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
                                  "%s:%d: '%.*s' typed by hand rounds %s %.6g; write <!--%s%s-->%s" MARK_END
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
        if (in_block) { in_block = strncmp(line, FIND_END, strlen(FIND_END)) != 0; continue; }
        if (!strncmp(line, FIND_BEGIN, strlen(FIND_BEGIN))) { in_block = 1; continue; }
        for (char *s = line; (s = strstr(s, "<!--")); ) {
            size_t nl;
            const char *v, *ve;
            if (marker_at(line, s, &nl, &v, &ve)) {
                size_t k = (size_t)(ve + strlen(MARK_END) - s);
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
            if (marker_at(lb, s, &nl, &v, &ve)) snprintf(claim, sizeof claim, "; claim: %.*s", (int)nl, s + 4);
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
                regions += marker_at(line, s, &nl, &v, &ve) || !strncmp(s, FIND_BEGIN, strlen(FIND_BEGIN));
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
