/* claims: registry rows (read from a registry file, or validated for
 * claims_registry), evaluation and numbers.tex (design.md §9). */
#include "claims.h"
#include "paths.h"
#include "study.h"
#include "tsv.h"
#include "afile.h"
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* claims_list.h is generated (the Makefile): X(f) for every claim function
 * defined in src/claims/. A function named by no row of the claim tables is an
 * orphan and fails the audit; a row naming no such function is PENDING. */
#define X(f) cs_status f(const claim_row *row, claim_result *res);
#include "claims_list.h"
#undef X

static const struct { const char *name; claim_fn fn; } claim_table[] = {
#define X(f) {#f, f},
#include "claims_list.h"
#undef X
};
#define NFN (sizeof claim_table / sizeof claim_table[0])

claim_fn claims_lookup_fn(const char *name)
{
    for (size_t i = 0; i < NFN; i++) if (!strcmp(claim_table[i].name, name)) return claim_table[i].fn;
    return NULL;
}

const char *const *claims_fn_names(void)
{
    static const char *names[NFN + 1];
    for (size_t i = 0; i < NFN; i++) names[i] = claim_table[i].name;
    names[NFN] = NULL;
    return names;
}

void claims_free(claims *c)
{
    free(c->rows);
    c->rows = NULL;
    c->n = 0;
}

static int gate_ref_ok(const char *g)
{
    if (!strcmp(g, "-")) return 1;
    const char *colon = strchr(g, ':');
    return colon && colon - g >= 6 && !strncmp(colon - 5, ".gate", 5) && colon[1] && !strchr(colon + 1, ':');
}

static cs_status copy_field(const tsv *t, size_t r, const char *col, char *dst, size_t n)
{
    const char *s = tsv_str(t, r, col);
    if (!s) return cs_err(CS_EINPUT, "%s: field '%s': no such column", tsv_path(t), col);
    if (!s[0] || strlen(s) >= n)
        return cs_err(CS_EINPUT, "%s:%d: field '%s': %s", tsv_path(t), tsv_line(t, r), col,
                      s[0] ? "too long" : "empty");
    strcpy(dst, s);
    return CS_OK;
}

/* A row's fields checked, however it was read; the duplicates are the caller's. */
static cs_status row_check(const char *path, claim_row *w)
{
    for (size_t k = 0; w->macro[k]; k++)
        if (!((w->macro[k] >= 'A' && w->macro[k] <= 'Z') || (w->macro[k] >= 'a' && w->macro[k] <= 'z')))
            return cs_err(CS_EINPUT, "%s:%d: field 'macro': '%s' is not a LaTeX macro name (letters only)", path,
                          w->line, w->macro);
    if (strcmp(w->kind, "measured") && strcmp(w->kind, "design") && strcmp(w->kind, "field") &&
        strcmp(w->kind, "needs-data") && strcmp(w->kind, "probe") && !claims_kind_beside(w->kind))
        return cs_err(CS_EINPUT,
                      "%s:%d: field 'kind': unknown kind '%s' (measured, design, field, needs-data, probe, "
                      "extension, variant)",
                      path, w->line, w->kind);
    /* probe: measured like a claim, added after the first verdict, never gated */
    if (!strcmp(w->kind, "probe") && strcmp(w->gate, "-"))
        return cs_err(CS_EINPUT, "%s:%d: field 'gate': a probe row is never gated ('-'), not '%s'", path, w->line,
                      w->gate);
    if (!gate_ref_ok(w->gate))
        return cs_err(CS_EINPUT, "%s:%d: field 'gate': '%s' is not 'file.gate:key'", path, w->line, w->gate);
    strcpy(w->gate_reg, w->gate);
    if (strcmp(w->format, "text") && (w->format[0] != '%' || strchr(w->format + 1, '%')))
        return cs_err(CS_EINPUT, "%s:%d: field 'format': '%s' is not one printf conversion or 'text'", path,
                      w->line, w->format);
    return CS_OK;
}

/* One row of a registry file. */
static cs_status row_read(const tsv *t, size_t r, const char *path, claim_row *w)
{
    cs_status st;
    w->line = tsv_line(t, r);
    if ((st = copy_field(t, r, "macro", w->macro, sizeof w->macro)) ||
        (st = copy_field(t, r, "kind", w->kind, sizeof w->kind)) ||
        (st = copy_field(t, r, "source", w->source, sizeof w->source)) ||
        (st = copy_field(t, r, "function", w->function, sizeof w->function)) ||
        (st = copy_field(t, r, "gate", w->gate, sizeof w->gate)) ||
        (st = copy_field(t, r, "test", w->test, sizeof w->test)) ||
        (st = copy_field(t, r, "section", w->section, sizeof w->section)) ||
        (st = copy_field(t, r, "format", w->format, sizeof w->format)) ||
        (st = copy_field(t, r, "reference", w->reference, sizeof w->reference)))
        return st;
    char params[512];
    if ((st = copy_field(t, r, "params", params, sizeof params)) ||
        (st = claim_params_parse(params, path, w->line, &w->param)))
        return st;
    return row_check(path, w);
}

/* The index of the row named name among rows[0..n), n when none: a claim is
 * found by its whole name, the registry's one key. */
static size_t row_index(const claim_row *rows, size_t n, const char *name)
{
    size_t i = 0;
    while (i < n && strcmp(rows[i].macro, name)) i++;
    return i;
}

cs_status claims_adopt(claim_row *rows, size_t n, const char *path, int maps, claims *out)
{
    cs_status st = CS_OK;
    for (size_t r = 0; r < n && !st; r++) {
        if ((st = row_check(path, &rows[r]))) break;
        const size_t q = row_index(rows, r, rows[r].macro);
        if (q < r)
            st = cs_err(CS_EINPUT, "%s:%d: field 'macro': duplicate of line %d", path, rows[r].line, rows[q].line);
    }
    /* a variant names the claim it stands for: a row of this registry */
    for (size_t r = 0; r < n && !st; r++) {
        const claim_row *w = &rows[r];
        if (!(w->param.set & PARAM_OF)) continue;
        const size_t q = row_index(rows, n, w->param.of);
        if (q == n || q == r)
            st = cs_err(CS_EINPUT, "%s:%d: field 'params': of=%s names %s", path, w->line, w->param.of,
                        q == r ? "the row itself" : "no row of the registry");
    }
    if (st) { free(rows); return st; }
    out->rows = rows;
    out->n = n;
    if (maps && (st = claims_apply_gate_maps(out, PATHS_GATE_MAP, PATHS_GATE_MAP_EXT))) {
        claims_free(out);
        return st;
    }
    return CS_OK;
}

cs_status claims_load(const char *path, claims *out)
{
    out->rows = NULL;
    out->n = 0;
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    size_t n = tsv_nrows(t);
    claim_row *rows = calloc(n ? n : 1, sizeof *rows);
    if (!rows) { tsv_free(t); return cs_err(CS_ENOMEM, "%s: out of memory", path); }
    for (size_t r = 0; r < n && !st; r++) {
        claim_row *w = &rows[r];
        if ((st = row_read(t, r, path, w))) break;
        const size_t q = row_index(rows, r, w->macro);
        if (q < r) st = cs_err(CS_EINPUT, "%s:%d: field 'macro': duplicate of line %d", path, w->line, rows[q].line);
    }
    tsv_free(t);
    if (st) { free(rows); return st; }
    return claims_adopt(rows, n, path, !strcmp(path, PATHS_CLAIMS), out);
}

int claims_kind_beside(const char *kind)
{
    return !strcmp(kind, "extension") || !strcmp(kind, "variant");
}

int claims_is_beside(const claim_row *row)
{
    return claims_kind_beside(row->kind);
}

int claims_awaited_source(const char *source)
{
    static const char *dirs[] = {PATHS_FROZEN_DIR "/paper-reading/", PATHS_FROZEN_DIR "/extension-pair/main/",
                                 PATHS_FROZEN_DIR "/extension-pair/extrapolation/", PATHS_FROZEN_DIR "/model-readings/",
                                 PATHS_FROZEN_DIR "/generator-probes/"};
    size_t l = strlen(source), k = strlen("/run_s*_*.tsv");
    if (l > k && !strcmp(source + l - k, "/run_s*_*.tsv")) return 1;
    for (size_t i = 0; i < sizeof dirs / sizeof *dirs; i++)
        if (!strncmp(source, dirs[i], strlen(dirs[i]))) return 1;
    return 0;
}

/* ext: 0 the main map (no extension row), 1 the extension map (only those);
 * reset: clear every row's gate first. */
static cs_status apply_map(claims *c, const char *map_path, int ext, int reset)
{
    tsv *t;
    cs_status st = tsv_read(map_path, &t);
    if (st) return st;
    if (tsv_col(t, "macro") < 0 || tsv_col(t, "gate") < 0) {
        st = cs_err(CS_EINPUT, "%s: header must name the columns 'macro' and 'gate'", map_path);
        tsv_free(t);
        return st;
    }
    for (size_t i = 0; i < c->n && reset; i++) {
        strcpy(c->rows[i].gate, "-");
        c->rows[i].gate_map_line = 0;
        c->rows[i].gate_map_ext = 0;
    }
    for (size_t r = 0; r < tsv_nrows(t) && !st; r++) {
        const char *m = tsv_str(t, r, "macro"), *g = tsv_str(t, r, "gate");
        int line = tsv_line(t, r);
        const size_t i = row_index(c->rows, c->n, m);
        claim_row *row = i < c->n ? &c->rows[i] : NULL;
        if (!row)
            st = cs_err(CS_EINPUT, "%s:%d: field 'macro': '%s' is not a claim of the registry", map_path, line, m);
        else if (row->gate_map_line)
            st = cs_err(CS_EINPUT, "%s:%d: field 'macro': %s is mapped twice (line %d)", map_path, line, m,
                        row->gate_map_line);
        else if (ext >= 0 && claims_is_beside(row) != ext)
            st = cs_err(CS_EINPUT, "%s:%d: field 'macro': %s is of kind %s: %s", map_path, line, m, row->kind,
                        ext ? "this map judges the extension claims only"
                            : "an extension claim is judged through " PATHS_GATE_MAP_EXT);
        else if (!strcmp(g, "-") || !gate_ref_ok(g) || strlen(g) >= sizeof row->gate)
            st = cs_err(CS_EINPUT, "%s:%d: field 'gate': '%s' is not 'file.gate:key'", map_path, line, g);
        else { strcpy(row->gate, g); row->gate_map_line = line; row->gate_map_ext = ext > 0; }
    }
    tsv_free(t);
    return st;
}

cs_status claims_apply_gate_map(claims *c, const char *map_path)
{
    return apply_map(c, map_path, -1, 1);
}

cs_status claims_apply_gate_maps(claims *c, const char *main_map, const char *ext_map)
{
    cs_status st = apply_map(c, main_map, 0, 1);
    return st ? st : apply_map(c, ext_map, 1, 0);
}

const claim_row *claims_find(const claims *c, const char *macro)
{
    const size_t i = row_index(c->rows, c->n, macro);
    return i < c->n ? &c->rows[i] : NULL;
}

void claim_pending(claim_result *res, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(res->why, sizeof res->why, fmt, ap);
    va_end(ap);
    res->status = VERDICT_PENDING;
}

void claim_set_value(const claim_row *row, claim_result *res, double v)
{
    res->value = v;
    if (strcmp(row->format, "text")) {
        snprintf(res->text, sizeof res->text, row->format, v);
        /* "-0.00" and "+0.00" both mean zero at this precision: print it unsigned */
        const char *p = res->text + (res->text[0] == '-' || res->text[0] == '+');
        int allzero = *p != '\0';
        for (const char *q = p; *q; q++) if (*q != '0' && *q != '.') allzero = 0;
        if (allzero && res->text[0] == '-') memmove(res->text, res->text + 1, strlen(res->text));
    }
}

cs_status claim_gate_load(const char *file, gate **g)
{
    char path[300];
    snprintf(path, sizeof path, PATHS_GATES_DIR "/%s", file);
    return gate_load(path, g);
}

void claim_judge(const claim_row *row, claim_result *res, gate_op op, double observed)
{
    char file[128];
    const char *colon = strchr(row->gate, ':');
    if (!colon) { res->gate = VERDICT_PENDING; return; }
    snprintf(file, sizeof file, "%.*s", (int)(colon - row->gate), row->gate);
    gate *g;
    if (claim_gate_load(file, &g)) {
        res->gate = VERDICT_FAIL;
        snprintf(res->gate_detail, sizeof res->gate_detail, "%s", cs_errmsg());
        return;
    }
    double lo = 0, hi = 0;
    cs_status st = CS_OK;
    if (op != GATE_TRUE) st = gate_value(g, colon + 1, 0, &lo);
    if (!st && (op == GATE_IN || op == GATE_OUT)) st = gate_value(g, colon + 1, 1, &hi);
    gate_free(g);
    if (st) {
        res->gate = VERDICT_FAIL;
        snprintf(res->gate_detail, sizeof res->gate_detail, "%s", cs_errmsg());
        return;
    }
    res->gate = gate_judge(op, observed, lo, hi);
    res->gate_observed = observed;
    res->has_observed = op != GATE_TRUE;
    if (op == GATE_IN || op == GATE_OUT)
        snprintf(res->gate_detail, sizeof res->gate_detail, "%.6g %s [%g, %g]", observed, gate_op_text(op), lo, hi);
    else if (op == GATE_TRUE)
        snprintf(res->gate_detail, sizeof res->gate_detail, "%s", observed != 0 ? "holds" : "does not hold");
    else
        snprintf(res->gate_detail, sizeof res->gate_detail, "%.6g %s %g", observed, gate_op_text(op), lo);
}

void claims_eval(const claim_row *row, claim_result *res)
{
    memset(res, 0, sizeof *res);
    res->status = VERDICT_PASS;
    res->gate = VERDICT_PENDING;
    res->value = NAN;
    snprintf(res->where, sizeof res->where, "%s", row->source);
    claim_fn fn = claims_lookup_fn(row->function);
    if (!fn) {
        claim_pending(res, "computing function %s not implemented yet", row->function);
        return;
    }
    if (!strncmp(row->source, "frozen/", 7) && claims_awaited_source(row->source) && access(row->source, F_OK) != 0) {
        /* a unit set is gathered by its function, which says what is missing;
         * a reading's table not frozen yet is pending with its unit named */
        if (!strstr(row->source, "*")) {
            const study_experiment *ex = study_of_path(row->source);
            claim_pending(res,
                          "%s: not frozen yet (a unit of the generator readings, design.md §8, still to run: make %s, "
                          "then make freeze)",
                          row->source, ex ? ex->name : "reproduce");
            return;
        }
    } else if (!strncmp(row->source, "frozen/", 7)) {
        struct stat sb;
        if (stat(row->source, &sb) != 0) {
            /* a registered file is never optional: deleting it (and
             * re-sealing) must not turn a verdict into PENDING */
            res->status = VERDICT_FAIL;
            snprintf(res->why, sizeof res->why,
                     "%s: registered frozen file missing (the registry names it; run the experiment and make freeze)",
                     row->source);
            return;
        }
        if (!S_ISREG(sb.st_mode)) {
            res->status = VERDICT_FAIL;
            snprintf(res->why, sizeof res->why, "%s: not a regular file", row->source);
            return;
        }
    }
    cs_errclear();
    cs_status st = fn(row, res);
    if (st) {
        res->status = VERDICT_FAIL;
        res->err = st;
        snprintf(res->why, sizeof res->why, "%s", cs_errmsg());
        return;
    }
    if (res->status == VERDICT_PASS && strcmp(row->format, "text") && !isfinite(res->value)) {
        /* never print inf or nan into numbers.tex: an input out of range */
        res->status = VERDICT_FAIL;
        snprintf(res->why, sizeof res->why, "%.400s: the computed value is not finite (%g): an input out of range",
                 res->where, res->value);
        return;
    }
    if (res->status == VERDICT_PASS && !res->text[0])
        claim_set_value(row, res, res->value);
}

void claims_expected_text(const claim_row *row, const claim_result *res, char *buf, size_t n)
{
    if (res->status == VERDICT_PASS) snprintf(buf, n, "%s", res->text);
    else snprintf(buf, n, CLAIMS_PENDING_FMT, row->macro);
}

/* The commands the write-up may branch and print through (it defines none of
 * its own, design.md §9): written as \newcommand\name so numbers_read, which
 * reads claims only, passes them by. Shown: what the reader sees. Hidden: the
 * audit's render, where every generated value, verdict and counter prints as
 * \hiddenvalue and a branch prints both its sides, so the rendered text holds
 * no number or verdict of the hand-written text's own making. */
static void write_helpers(FILE *f, int hide)
{
    if (!hide) {
        fprintf(
            f, "\\providecommand{\\pending}[1]{\\textbf{[pending]}}\n"
               "\\newcommand\\verdict[1]{\\ifthenelse{\\equal{#1}{PASS}}{\\textcolor{green!45!black}{pass}}{"
               "\\ifthenelse{\\equal{#1}{FAIL}}{\\textcolor{red!70!black}{\\textbf{fail}}}{\\textit{pending}}}}\n"
               "\\newcommand\\ifpass[3]{\\ifthenelse{\\equal{#1}{PASS}}{#2}{#3}}\n"
               "\\newcommand\\ifsame[4]{\\ifthenelse{\\equal{#1}{#2}}{#3}{#4}}\n"
               "\\newcommand\\bandpos[3]{\\ifdim#1pt<#2pt below\\else\\ifdim#1pt>#3pt above\\else inside\\fi\\fi}\n"
               "\\newcommand\\fig[2]{\\IfFileExists{../figures/"
               "#1.pdf}{\\includegraphics[width=#2,height=0.78\\textheight,keepaspectratio]{../figures/#1.pdf}}"
               "{\\fbox{\\parbox{#2}{\\centering figure \\texttt{#1} not drawn yet: its frozen data are pending}}}}\n");
        return;
    }
    fprintf(f, "\\newcommand\\hiddenvalue{\\mbox{" CLAIMS_HIDDEN_WORD "}}\n"
               "\\providecommand{\\pending}[1]{\\hiddenvalue}\n"
               "\\newcommand\\verdict[1]{\\hiddenvalue}\n"
               "\\newcommand\\ifpass[3]{#2 \\hiddenvalue{} #3}\n"
               "\\newcommand\\ifsame[4]{#3 \\hiddenvalue{} #4}\n"
               "\\newcommand\\bandpos[3]{\\hiddenvalue}\n"
               "\\newcommand\\fig[2]{\\hiddenvalue}\n"
               "\\pagenumbering{gobble}\n");
    static const char *counters[] = {"section",  "subsection", "subsubsection", "paragraph", "table",   "figure",
                                     "equation", "footnote",   "enumi",         "enumii",    "enumiii", "enumiv",
                                     NULL};
    for (int i = 0; counters[i]; i++) fprintf(f, "\\renewcommand\\the%s{\\hiddenvalue}\n", counters[i]);
}

cs_status claims_write_numbers(const char *path, const claims *c, const claim_result *res, int hide)
{
    afile a;
    cs_status st = afile_open(&a, path);
    if (st) return st;
    FILE *f = a.f;
    fprintf(f, "%% paper/numbers.tex: GENERATED by `crownshy numbers` from frozen/, gates/ and audit/claims.tsv.\n"
               "%% Never edit by hand: `make verify` fails when it differs from a fresh generation.\n"
               "%% A claim whose experiment has not run (or whose input data are missing) prints as pending.\n");
    if (hide) fprintf(f, "%% The audit's render: every value hidden, every branch shown.\n");
    write_helpers(f, hide);
    for (size_t i = 0; i < c->n; i++) {
        char v[256];
        if (hide) snprintf(v, sizeof v, "\\hiddenvalue{}");
        else claims_expected_text(&c->rows[i], &res[i], v, sizeof v);
        fprintf(f, "\\newcommand{\\%s}{%s}\n", c->rows[i].macro, v);
        if (strcmp(c->rows[i].gate, "-"))
            fprintf(f, "\\newcommand{\\%sGate}{%s}\n", c->rows[i].macro,
                    hide ? "\\hiddenvalue{}" : verdict_name(res[i].gate));
    }
    return afile_commit(&a);
}

void numbers_free(numbers_tex *nt)
{
    free(nt->name); free(nt->value); free(nt->line);
    memset(nt, 0, sizeof *nt);
}

cs_status numbers_read(const char *path, numbers_tex *out)
{
    memset(out, 0, sizeof *out);
    FILE *f = fopen(path, "r");
    if (!f) return cs_err(CS_EINPUT, "%s: cannot open (run `crownshy numbers` to generate it)", path);
    size_t cap = 1024;
    out->name = malloc(cap * sizeof *out->name);
    out->value = malloc(cap * sizeof *out->value);
    out->line = malloc(cap * sizeof *out->line);
    if (!out->name || !out->value || !out->line) {
        fclose(f);
        numbers_free(out);
        return cs_err(CS_ENOMEM, "out of memory");
    }
    char buf[1024];
    int lineno = 0;
    cs_status st = CS_OK;
    while (fgets(buf, sizeof buf, f)) {
        lineno++;
        if (strncmp(buf, "\\newcommand{\\", 13)) continue;
        char *name = buf + 13, *close = strchr(name, '}');
        if (!close || close[1] != '{') { st = cs_err(CS_EINPUT, "%s:%d: malformed \\newcommand", path, lineno); break; }
        *close = '\0';
        char *v = close + 2;
        int depth = 1;
        char *e = v;
        for (; *e && depth > 0; e++) {
            if (*e == '{') depth++;
            else if (*e == '}') depth--;
        }
        if (depth != 0) {
            st = cs_err(CS_EINPUT, "%s:%d: field '%s': unbalanced braces (truncated?)", path, lineno, name);
            break;
        }
        e[-1] = '\0';
        if (strlen(name) >= 80 || strlen(v) >= 192) {
            st = cs_err(CS_EINPUT, "%s:%d: field '%s': too long", path, lineno, name);
            break;
        }
        if (out->n == cap) { st = cs_err(CS_EINPUT, "%s: more than %zu macros", path, cap); break; }
        strcpy(out->name[out->n], name);
        strcpy(out->value[out->n], v);
        out->line[out->n] = lineno;
        out->n++;
    }
    fclose(f);
    if (st) numbers_free(out);
    return st;
}

const char *numbers_get(const numbers_tex *nt, const char *name, int *line)
{
    for (size_t i = 0; i < nt->n; i++)
        if (!strcmp(nt->name[i], name)) { if (line) *line = nt->line[i]; return nt->value[i]; }
    return NULL;
}

/* LaTeX-escape a short cell. */
void claims_tex_escape(const char *in, char *out, size_t n)
{
    size_t o = 0;
    for (; *in && o + 3 < n; in++) {
        if (strchr("%&_#$", *in)) out[o++] = '\\';
        out[o++] = *in;
    }
    out[o] = '\0';
}

/* Distance to the reference paper (design.md §9): measured claims whose value
 * was computed and whose reference is a plain non-zero number. */
int claims_rel_diff(const claim_row *row, const claim_result *res, double *ref, double *rel)
{
    if (strcmp(row->kind, "measured") || res->status != VERDICT_PASS || !isfinite(res->value)) return 0;
    char *end;
    double r = strtod(row->reference, &end);
    while (*end == ' ') end++;
    if (end == row->reference || *end || !isfinite(r) || r == 0.0) return 0;
    *ref = r;
    *rel = (res->value - r) / fabs(r);
    return 1;
}

int claims_src_line(const char *prefix, int indented, char *path, size_t pathsz, int *line)
{
    paths_list files;
    if (paths_list_files(PATHS_CLAIMS_SRC_DIR, ".c", 0, &files)) return -1;
    const size_t n = strlen(prefix);
    char buf[1024];
    int found = 0;
    for (size_t i = 0; i < files.n && !found; i++) {
        FILE *f = fopen(files.p[i], "r");
        for (int ln = 1; f && !found && fgets(buf, sizeof buf, f); ln++) {
            const char *p = indented ? buf + strspn(buf, " ") : buf;
            if (strncmp(p, prefix, n)) continue;
            snprintf(path, pathsz, "%s", files.p[i]);
            *line = ln;
            found = 1;
        }
        if (f) fclose(f);
    }
    paths_list_free(&files);
    return found ? 0 : 1;
}

cs_status claims_function_file(const char *function, char *path, size_t pathsz, int *line)
{
    char want[160];
    snprintf(want, sizeof want, "cs_status %s(", function);
    const int r = claims_src_line(want, 0, path, pathsz, line);
    if (r < 0) return cs_err(CS_ENOMEM, "out of memory");
    return r ? cs_err(CS_EINPUT, "%s: no file of %s/ defines %s", PATHS_CLAIMS, PATHS_CLAIMS_SRC_DIR, function) : CS_OK;
}
