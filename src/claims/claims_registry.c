/* claims_registry: the registry as C (design.md §9). The claim tables
 * (src/claims/claim_*_table.c, one row per claim, params typed) in the order
 * of the CLAIMS rows of src/base/manifest.h are the one home of every claim:
 * read into claim_rows for evaluation (claims_registry), and printed as
 * audit/claims.tsv, the auditor's copy, which `crownshy claims-table` writes
 * and the audit checks (claims_registry_check). */
#include "claims.h"
#include "afile.h"
#include "paths.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CLAIMS(t) extern const claim_spec t[]; extern const size_t t##_n;
#include "manifest.h"

static const struct { const char *name; const claim_spec *rows; const size_t *n; } TABLES[] = {
#define CLAIMS(t) {#t, t, &t##_n},
#include "manifest.h"
};
#define NTABLES (sizeof TABLES / sizeof *TABLES)

/* The print's head: what the registry is, its kinds and columns; then the header line. */
static const char HEAD[] =
    "# what: claim registry, one row per macro of the reference paper (design.md §9)\n"
    "# kinds: measured = recomputed from frozen/; design = a preregistered or fixed constant read from "
    "its gate or header; field = a published field figure (frozen/field/reference.tsv); needs-data = "
    "requires an input this machine lacks; probe = recomputed from frozen/ like measured, a probe added "
    "after the first verdict or a diagnostic number of the write-up (section E0: the sensitivity and "
    "readings account), never gated, reference - (not in the paper); extension = measured like a claim on "
    "the pair-aware generator, a reading added after the first verdict (design.md §8), prefix Pair, gated "
    "through audit/gate_map_extension.tsv by the same thresholds and tallied apart from the reference "
    "paper's claims; variant = measured like a claim on the paper reading under one unstated training "
    "choice whose joint arm met both preconditions at four seeds, run at the gate's seeds (design.md §8), "
    "gated through the same map by the same thresholds and tallied apart from both\n"
    "# reference: the value printed in the reference paper, used only for the side-by-side comparison "
    "table\n"
    "# test: every row is one cmocka test of tests/test_claims.c, built from this file\n"
    "# params: what the row's function computes when it serves several claims, never read from the "
    "macro's spelling: key=value pairs joined by ';' (- when none) of arm, probe (shuffled/rotated), "
    "bound (lo/hi), stat (median/range/ratio), column, quantity, stand (shown/other_a/other_b point-cloud "
    "stand), of (the claim a variant row stands for), choice and x (a sensitivity choice and its value), "
    "scale (a factor, 100 for a percent), spacing (m), seeds (the seeds read of a unit set, 1..N; absent: "
    "the preregistered seeds of gates/main.gate, which a gated row always reads); src/claims/claims.h "
    "lists them\n"
    "macro\tkind\tsource\tfunction\tgate\ttest\tsection\tformat\treference\tparams\n";

#define TEST_PREFIX "tests/test_claims.c:claim_"

static int head_lines(void)
{
    int n = 0;
    for (const char *p = HEAD; *p; p++) n += *p == '\n';
    return n;
}

static cs_status copy_cell(const char *table, size_t r, int line, const char *field, const char *v, char *dst,
                           size_t n)
{
    if (!v || !v[0] || strlen(v) >= n)
        return cs_err(CS_EINPUT, "%s[%zu] (%s:%d): field '%s': %s", table, r, PATHS_CLAIMS, line, field,
                      v && v[0] ? "too long" : "empty");
    strcpy(dst, v);
    return CS_OK;
}

/* A table row as a claim_row: its params go through the registry's spelling
 * and back (claim_params_format, claim_params_parse), so a row reads exactly
 * as its print, a field given without its PARAM_* bit fails. */
static cs_status row_from_spec(const claim_spec *s, const char *table, size_t r, int line, claim_row *w)
{
    w->line = line;
    w->table = table;
    cs_status st;
    if ((st = copy_cell(table, r, line, "macro", s->macro, w->macro, sizeof w->macro)) ||
        (st = copy_cell(table, r, line, "kind", s->kind, w->kind, sizeof w->kind)) ||
        (st = copy_cell(table, r, line, "source", s->source, w->source, sizeof w->source)) ||
        (st = copy_cell(table, r, line, "function", s->function, w->function, sizeof w->function)) ||
        (st = copy_cell(table, r, line, "gate", s->gate, w->gate, sizeof w->gate)) ||
        (st = copy_cell(table, r, line, "section", s->section, w->section, sizeof w->section)) ||
        (st = copy_cell(table, r, line, "format", s->format, w->format, sizeof w->format)) ||
        (st = copy_cell(table, r, line, "reference", s->reference, w->reference, sizeof w->reference)))
        return st;
    if ((size_t)snprintf(w->test, sizeof w->test, TEST_PREFIX "%s", w->macro) >= sizeof w->test)
        return cs_err(CS_EINPUT, "%s[%zu] (%s:%d): field 'test': too long", table, r, PATHS_CLAIMS, line);
    char text[512];
    claim_params_format(&s->param, text, sizeof text);
    if ((st = claim_params_parse(text, PATHS_CLAIMS, line, &w->param))) return st;
    if (memcmp(&w->param, &s->param, sizeof w->param))
        return cs_err(CS_EINPUT,
                      "%s[%zu] (%s:%d): field 'params': the row does not read as it prints ('%s'): a field given "
                      "without its PARAM_* bit, or a number %%g does not print exactly",
                      table, r, PATHS_CLAIMS, line, text);
    return CS_OK;
}

/* Every table's rows; maps: their gates from the pinned maps. */
static cs_status registry_rows(claims *out, int maps)
{
    out->rows = NULL;
    out->n = 0;
    size_t n = 0, i = 0;
    for (size_t t = 0; t < NTABLES; t++) n += *TABLES[t].n;
    claim_row *rows = calloc(n ? n : 1, sizeof *rows);
    if (!rows) return cs_err(CS_ENOMEM, "%s: out of memory", PATHS_CLAIMS);
    const int first = head_lines() + 1;
    cs_status st = CS_OK;
    for (size_t t = 0; t < NTABLES && !st; t++)
        for (size_t r = 0; r < *TABLES[t].n && !st; r++, i++)
            st = row_from_spec(&TABLES[t].rows[r], TABLES[t].name, r, first + (int)i, &rows[i]);
    if (st) { free(rows); return st; }
    return claims_adopt(rows, n, PATHS_CLAIMS, maps, out);
}

cs_status claims_registry(claims *out)
{
    return registry_rows(out, 1);
}

cs_status claims_registry_text(char **text, size_t *len)
{
    *text = NULL;
    *len = 0;
    claims c;
    cs_status st = registry_rows(&c, 0);
    if (st) return st;
    FILE *f = open_memstream(text, len);
    if (!f) { claims_free(&c); return cs_err(CS_ENOMEM, "%s: out of memory", PATHS_CLAIMS); }
    fputs(HEAD, f);
    for (size_t r = 0; r < c.n; r++) {
        const claim_row *w = &c.rows[r];
        char params[512];
        claim_params_format(&w->param, params, sizeof params);
        fprintf(f, "%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n", w->macro, w->kind, w->source, w->function, w->gate_reg,
                w->test, w->section, w->format, w->reference, params);
    }
    claims_free(&c);
    if (fclose(f) || !*text) { free(*text); *text = NULL; return cs_err(CS_ENOMEM, "%s: out of memory", PATHS_CLAIMS); }
    return CS_OK;
}

cs_status claims_table_where(const claim_row *row, char *path, size_t pathsz, int *line)
{
    paths_list files;
    if (paths_list_files(PATHS_CLAIMS_SRC_DIR, ".c", 0, &files)) return cs_err(CS_ENOMEM, "out of memory");
    char want[96], buf[1024];
    snprintf(want, sizeof want, "{\"%s\", ", row->macro);
    const size_t wn = strlen(want);
    cs_status st = cs_err(CS_EINPUT, "%s: no file of %s/ holds the row of %s", PATHS_CLAIMS, PATHS_CLAIMS_SRC_DIR,
                          row->macro);
    for (size_t i = 0; i < files.n && st; i++) {
        FILE *f = fopen(files.p[i], "r");
        for (int ln = 1; f && fgets(buf, sizeof buf, f); ln++) {
            const char *p = buf + strspn(buf, " ");
            if (strncmp(p, want, wn)) continue;
            snprintf(path, pathsz, "%s", files.p[i]);
            *line = ln;
            cs_errclear();
            st = CS_OK;
            break;
        }
        if (f) fclose(f);
    }
    paths_list_free(&files);
    return st;
}

cs_status claims_registry_write(const char *path)
{
    char *text;
    size_t len;
    cs_status st = claims_registry_text(&text, &len);
    if (st) return st;
    afile a;
    if ((st = afile_open(&a, path))) { free(text); return st; }
    if (fwrite(text, 1, len, a.f) != len) a.err = 1;
    free(text);
    return afile_commit(&a);
}

/* The length of the line at p (up to its newline or the end). */
static size_t line_len(const char *p)
{
    const char *e = strchr(p, '\n');
    return e ? (size_t)(e - p) : strlen(p);
}

cs_status claims_registry_check(const char *path)
{
    char *want;
    size_t len;
    cs_status st = claims_registry_text(&want, &len);
    if (st) return st;
    char *have = afile_read(path);
    if (!have) { free(want); return cs_err(CS_EINVARIANT, "%s: cannot read (crownshy claims-table writes it)", path); }
    const char *h = have, *w = want;
    int line = 1;
    while (*h && *w) {
        const size_t hn = line_len(h), wn = line_len(w);
        if (hn != wn || memcmp(h, w, hn) || h[hn] != w[wn]) break;
        h += hn + (h[hn] == '\n');
        w += wn + (w[wn] == '\n');
        line++;
    }
    if (*h || *w)
        st = cs_err(CS_EINVARIANT,
                    "%s:%d: not the print of the claim tables (src/claims/claim_*_table.c): the file has '%.*s', "
                    "the tables give '%.*s' (a claim is edited in its table; crownshy claims-table writes the file)",
                    path, line, *h ? (int)line_len(h) : 5, *h ? h : "(end)", *w ? (int)line_len(w) : 5,
                    *w ? w : "(end)");
    free(have);
    free(want);
    return st;
}
