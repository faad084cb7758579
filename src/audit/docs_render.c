/* docs_render: a documentation page with its generated regions filled from
 * the claims (design.md §9), what `crownshy numbers` writes and the docs audit
 * (audit_docs.c) compares the page with: an inline marker's claim text, gate
 * verdict or reference value, and the findings block, the gated claims per
 * gate file tallied as verify counts them, with the agreement classes of
 * design.md §6.1. Limits: a marker lies on one line; one inside a code span is
 * literal text, as Markdown renders it. */
#include "docs_render.h"
#include "agree.h"
#include "audit_evidence.h"
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

int docs_render_marker(const char *line, const char *s, size_t *nl, const char **v, const char **ve)
{
    if (strncmp(s, "<!--", 4) || in_code(line, s)) return 0;
    size_t k = 0;
    while (isalnum((unsigned char)s[4 + k])) k++;
    if (!k || !isalpha((unsigned char)s[4]) || strncmp(s + 4 + k, "-->", 3)) return 0;
    const char *e = strstr(s + 7 + k, DOCS_MARK_END);
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
        if (!docs_render_marker(line, s, &nl, &v, &ve)) { sb_printf(b, "%c", *s++); continue; }
        char name[80], text[160];
        snprintf(name, sizeof name, "%.*s", (int)(nl < 79 ? nl : 79), s + 4);
        if (marker_text(name, c, res, text, sizeof text)) sb_printf(b, "<!--%s-->%s" DOCS_MARK_END, name, text);
        else {
            if (!unknown[0]) snprintf(unknown, un, "%s", name);
            sb_printf(b, "%.*s", (int)(ve + strlen(DOCS_MARK_END) - s), s);
        }
        s = ve + strlen(DOCS_MARK_END);
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
            if (!strncmp(line, DOCS_FIND_END, strlen(DOCS_FIND_END))) { in_block = 0; sb_printf(&b, "%s", line); }
            continue;
        }
        if (!strncmp(line, DOCS_FIND_BEGIN, strlen(DOCS_FIND_BEGIN))) {
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
        return cs_err(CS_EINPUT, "%s:%d: %s... has no closing %s", path, block_line, DOCS_FIND_BEGIN, DOCS_FIND_END);
    }
    if (bad_line) {
        free(b.s);
        return cs_err(CS_EINPUT, "%s:%d: marker <!--%s--> names no claim of %s", path, bad_line, unknown, PATHS_CLAIMS);
    }
    if (b.err) { free(b.s); return cs_err(CS_ENOMEM, "out of memory"); }
    *out = b.s ? b.s : calloc(1, 1);
    return *out ? CS_OK : cs_err(CS_ENOMEM, "out of memory");
}
