/* tsv: frozen-result tables (design.md §9, §11). Reader holds the whole file in one
 * buffer and points cells into it; every malformed input is a CS_EINPUT with a
 * message "file:line: field 'name': what". The writer prints doubles as %.17g
 * (round-trips exactly) and publishes the file by rename only on commit. */
#include "tsv.h"
#include "afile.h"
#include "paths.h"
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct tsv {
    char *path;
    char *buf;
    size_t nmeta;
    char **mkey, **mval;
    size_t ncols, nrows;
    char **cols;
    char **cells; /* nrows * ncols */
    int *lines;   /* file line of each row */
};

void tsv_free(tsv *t)
{
    if (!t) return;
    free(t->path); free(t->buf); free(t->mkey); free(t->mval);
    free(t->cols); free(t->cells); free(t->lines); free(t);
}

static size_t split_tabs(char *s, char **out, size_t max)
{
    size_t n = 0;
    for (;;) {
        if (n < max) out[n] = s;
        n++;
        char *tab = strchr(s, '\t');
        if (!tab) break;
        if (n <= max) *tab = '\0';
        s = tab + 1;
    }
    return n;
}

/* The whole file into t->buf (NUL-terminated), refusing a non-regular,
 * unreadable or binary file; *size receives its length. */
static cs_status slurp(const char *path, tsv *t, long *size)
{
    FILE *f = fopen(path, "rb");
    if (!f) return cs_err(CS_EINPUT, "%s: cannot open: %s", path, strerror(errno));
    if (fseek(f, 0, SEEK_END) != 0) { fclose(f); return cs_err(CS_EINPUT, "%s: cannot seek", path); }
    long sz = ftell(f);
    rewind(f);
    t->path = strdup(path);
    t->buf = malloc((size_t)sz + 1);
    if (!t->path || !t->buf) { fclose(f); return cs_err(CS_ENOMEM, "%s: out of memory", path); }
    size_t got = fread(t->buf, 1, (size_t)sz, f);
    fclose(f);
    if (got != (size_t)sz) return cs_err(CS_EINPUT, "%s: short read", path);
    t->buf[sz] = '\0';
    if (memchr(t->buf, '\0', (size_t)sz)) return cs_err(CS_EINPUT, "%s: binary data (NUL byte)", path);
    *size = sz;
    return CS_OK;
}

/* One line of the table: a provenance line, the header row or a data row. */
static cs_status parse_line(tsv *t, char *line, int lineno, size_t nlines, size_t *row)
{
    const char *path = t->path;
    if (line[0] == '#') {
        if (t->cols) return cs_err(CS_EINPUT, "%s:%d: provenance line after the header row", path, lineno);
        char *sep = strstr(line, ": ");
        if (line[1] != ' ' || !sep || sep == line + 2)
            return cs_err(CS_EINPUT, "%s:%d: malformed provenance line (expected '# key: value')", path, lineno);
        *sep = '\0';
        t->mkey[t->nmeta] = line + 2;
        t->mval[t->nmeta] = sep + 2;
        t->nmeta++;
        return CS_OK;
    }
    if (line[0] == '\0') return cs_err(CS_EINPUT, "%s:%d: empty line", path, lineno);
    if (!t->cols) {
        size_t nc = 1;
        for (const char *c = line; *c; c++) nc += (*c == '\t');
        t->cols = calloc(nc, sizeof *t->cols);
        if (!t->cols) return cs_err(CS_ENOMEM, "%s: out of memory", path);
        t->ncols = split_tabs(line, t->cols, nc);
        for (size_t c = 0; c < t->ncols; c++)
            if (!t->cols[c][0])
                return cs_err(CS_EINPUT, "%s:%d: header column %zu has an empty name", path, lineno, c + 1);
        t->cells = calloc(nlines * t->ncols + 1, sizeof *t->cells);
        if (!t->cells) return cs_err(CS_ENOMEM, "%s: out of memory", path);
        return CS_OK;
    }
    size_t n = split_tabs(line, t->cells + *row * t->ncols, t->ncols);
    if (n < t->ncols)
        return cs_err(CS_EINPUT, "%s:%d: field '%s' missing (truncated line: %zu of %zu fields)", path, lineno,
                      t->cols[n], n, t->ncols);
    if (n > t->ncols) return cs_err(CS_EINPUT, "%s:%d: %zu fields, header has %zu", path, lineno, n, t->ncols);
    t->lines[(*row)++] = lineno;
    return CS_OK;
}

cs_status tsv_read(const char *path, tsv **out)
{
    *out = NULL;
    cs_status st = paths_input_file(path);
    if (st) return st;
    tsv *t = calloc(1, sizeof *t);
    if (!t) return cs_err(CS_ENOMEM, "%s: out of memory", path);
    long sz = 0;
    if ((st = slurp(path, t, &sz))) { tsv_free(t); return st; }
    size_t nlines = 0;
    for (long i = 0; i < sz; i++) if (t->buf[i] == '\n') nlines++;
    if (sz > 0 && t->buf[sz - 1] != '\n') {
        tsv_free(t);
        return cs_err(CS_EINPUT, "%s:%zu: truncated line (file does not end with a newline)", path, nlines + 1);
    }
    t->mkey = calloc(nlines + 1, sizeof *t->mkey);
    t->mval = calloc(nlines + 1, sizeof *t->mval);
    t->lines = calloc(nlines + 1, sizeof *t->lines);
    if (!t->mkey || !t->mval || !t->lines) { tsv_free(t); return cs_err(CS_ENOMEM, "%s: out of memory", path); }
    char *p = t->buf;
    /* a UTF-8 byte-order mark (spreadsheet exports) is not part of the first field */
    if (sz >= 3 && !memcmp(p, "\xef\xbb\xbf", 3)) p += 3;
    int lineno = 0;
    size_t row = 0;
    while (*p && !st) {
        char *nl = strchr(p, '\n');
        *nl = '\0';
        if (nl > p && nl[-1] == '\r') nl[-1] = '\0';
        char *line = p;
        p = nl + 1;
        /* the message is made before tsv_free: it reads the table (a use-after-free found by make fuzz) */
        st = parse_line(t, line, ++lineno, nlines, &row);
    }
    if (!st && !t->cols) st = cs_err(CS_EINPUT, "%s: no header row", path);
    if (st) { tsv_free(t); return st; }
    t->nrows = row;
    *out = t;
    return CS_OK;
}

const char *tsv_path(const tsv *t) { return t->path; }
size_t tsv_nrows(const tsv *t) { return t->nrows; }
size_t tsv_ncols(const tsv *t) { return t->ncols; }
const char *tsv_colname(const tsv *t, size_t c) { return c < t->ncols ? t->cols[c] : NULL; }
int tsv_line(const tsv *t, size_t row) { return row < t->nrows ? t->lines[row] : 0; }

int tsv_col(const tsv *t, const char *name)
{
    for (size_t c = 0; c < t->ncols; c++)
        if (!strcmp(t->cols[c], name)) return (int)c;
    return -1;
}

const char *tsv_meta(const tsv *t, const char *key)
{
    for (size_t i = 0; i < t->nmeta; i++)
        if (!strcmp(t->mkey[i], key)) return t->mval[i];
    return NULL;
}

const char *tsv_str(const tsv *t, size_t row, const char *col)
{
    int c = tsv_col(t, col);
    if (c < 0 || row >= t->nrows) return NULL;
    return t->cells[row * t->ncols + (size_t)c];
}

static cs_status cell(const tsv *t, size_t row, const char *col, const char **s)
{
    if (row >= t->nrows)
        return cs_err(CS_EINPUT, "%s: field '%s': row %zu requested, file has %zu rows", t->path, col, row + 1,
                      t->nrows);
    *s = tsv_str(t, row, col);
    if (!*s) return cs_err(CS_EINPUT, "%s:%d: field '%s': no such column", t->path, t->lines[row], col);
    return CS_OK;
}

cs_status tsv_text(const tsv *t, size_t row, const char *col, const char **out)
{
    return cell(t, row, col, out);
}

static cs_status parse_double(const tsv *t, size_t row, const char *col, double *out, int allow_nf)
{
    const char *s;
    cs_status st = cell(t, row, col, &s);
    if (st) return st;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || (errno == ERANGE && fabs(v) > 1.0))
        return cs_err(CS_EINPUT, "%s:%d: field '%s': not a number: '%s'", t->path, t->lines[row], col, s);
    if (!allow_nf && !isfinite(v))
        return cs_err(CS_EINPUT, "%s:%d: field '%s': not a finite number: '%s'", t->path, t->lines[row], col, s);
    *out = v;
    return CS_OK;
}

cs_status tsv_double(const tsv *t, size_t row, const char *col, double *out)
{
    return parse_double(t, row, col, out, 0);
}
cs_status tsv_double_nf(const tsv *t, size_t row, const char *col, double *out)
{
    return parse_double(t, row, col, out, 1);
}

cs_status tsv_long(const tsv *t, size_t row, const char *col, long *out)
{
    const char *s;
    cs_status st = cell(t, row, col, &s);
    if (st) return st;
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno == ERANGE)
        return cs_err(CS_EINPUT, "%s:%d: field '%s': not an integer: '%s'", t->path, t->lines[row], col, s);
    *out = v;
    return CS_OK;
}

long tsv_find(const tsv *t, const char *col, const char *value)
{
    int c = tsv_col(t, col);
    if (c < 0) return -1;
    for (size_t r = 0; r < t->nrows; r++)
        if (!strcmp(t->cells[r * t->ncols + (size_t)c], value)) return (long)r;
    return -1;
}

/* ---- writer ---- */
struct tsv_writer {
    afile a;   /* the temp file, published by rename on commit */
    int ncell; /* cells written in the current row */
};

cs_status tsv_writer_open(tsv_writer **out, const char *path)
{
    *out = NULL;
    tsv_writer *w = calloc(1, sizeof *w);
    if (!w) return cs_err(CS_ENOMEM, "%s: out of memory", path);
    cs_status st = afile_open(&w->a, path);
    if (st) { free(w); return st; }
    *out = w;
    return CS_OK;
}

void tsv_writer_meta(tsv_writer *w, const char *key, const char *fmt, ...)
{
    char val[4096];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(val, sizeof val, fmt, ap);
    va_end(ap);
    /* A newline or tab inside a value would corrupt the file: flatten it. */
    for (char *c = val; *c; c++) if (*c == '\n' || *c == '\r' || *c == '\t') *c = ' ';
    if (fprintf(w->a.f, "# %s: %s\n", key, val[0] ? val : "-") < 0) w->a.err = 1;
}

void tsv_writer_columns(tsv_writer *w, const char *cols)
{
    if (fprintf(w->a.f, "%s\n", cols) < 0) w->a.err = 1;
}

static void sep(tsv_writer *w)
{
    if (w->ncell++ > 0 && fputc('\t', w->a.f) == EOF) w->a.err = 1;
}

void tsv_writer_str(tsv_writer *w, const char *s)
{
    sep(w);
    for (; *s; s++)
        if (fputc(*s == '\t' || *s == '\n' ? ' ' : *s, w->a.f) == EOF) w->a.err = 1;
}

void tsv_writer_dbl(tsv_writer *w, double x)
{
    sep(w);
    if (fprintf(w->a.f, "%.17g", x) < 0) w->a.err = 1;
}

void tsv_writer_long(tsv_writer *w, long x)
{
    sep(w);
    if (fprintf(w->a.f, "%ld", x) < 0) w->a.err = 1;
}

void tsv_writer_endrow(tsv_writer *w)
{
    if (fputc('\n', w->a.f) == EOF) w->a.err = 1;
    w->ncell = 0;
}

cs_status tsv_writer_commit(tsv_writer *w)
{
    cs_status st = afile_commit(&w->a);
    free(w);
    return st;
}

void tsv_writer_abort(tsv_writer *w)
{
    afile_abort(&w->a);
    free(w);
}
