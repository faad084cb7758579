/* tsv: frozen-result tables. Text TSV with "# key: value" provenance lines
 * before one header row of column names; doubles written as %.17g so a read
 * gives back the same bits. Reads validate everything and name file, line and
 * field on error; writes go to "<path>.tmp" and are renamed on commit (atomic:
 * a killed run never leaves a half-written table that later counts as done). */
#ifndef TSV_H
#define TSV_H
#include "cs.h"
#include <stddef.h>

typedef struct tsv tsv;

/* Parse `path`. Errors (CS_EINPUT, message in cs_errmsg()): missing file,
 * no header row, a row with a different number of fields than the header
 * ("truncated line"), a provenance line without ": ". */
cs_status tsv_read(const char *path, tsv **out);
void tsv_free(tsv *t);

const char *tsv_path(const tsv *t);
size_t tsv_nrows(const tsv *t);
size_t tsv_ncols(const tsv *t);
const char *tsv_colname(const tsv *t, size_t c);
/* Column index of `name`, or -1. */
int tsv_col(const tsv *t, const char *name);
/* Provenance value for `key` ("# key: value"), or NULL. */
const char *tsv_meta(const tsv *t, const char *key);
/* File line number (1-based) of data row `row`, for messages. */
int tsv_line(const tsv *t, size_t row);

/* Cell as text; NULL if the column does not exist. */
const char *tsv_str(const tsv *t, size_t row, const char *col);
/* Cell as text; CS_EINPUT naming file, line and field when the column or row
 * does not exist (tsv_str's NULL, turned into a message). */
cs_status tsv_text(const tsv *t, size_t row, const char *col, const char **out);
/* Cell as a finite double ("nan"/"inf" rejected unless allow_nonfinite).
 * Error names file, line and field: "f.tsv:12: field 'w1': not a number: 'abc'". */
cs_status tsv_double(const tsv *t, size_t row, const char *col, double *out);
cs_status tsv_double_nf(const tsv *t, size_t row, const char *col, double *out);
cs_status tsv_long(const tsv *t, size_t row, const char *col, long *out);
/* Find the first row whose column `col` equals `value` (text); -1 if none. */
long tsv_find(const tsv *t, const char *col, const char *value);

typedef struct tsv_writer tsv_writer;
/* Creates parent directories; writes to "<path>.tmp". */
cs_status tsv_writer_open(tsv_writer **w, const char *path);
/* "# key: value" provenance line; must come before tsv_writer_columns. */
void tsv_writer_meta(tsv_writer *w, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* Header row; `cols` is tab-separated, e.g. "spacing\tbeta\tk1". */
void tsv_writer_columns(tsv_writer *w, const char *cols);
void tsv_writer_str(tsv_writer *w, const char *s);
void tsv_writer_dbl(tsv_writer *w, double x); /* %.17g */
void tsv_writer_long(tsv_writer *w, long x);
void tsv_writer_endrow(tsv_writer *w);
/* Flush, fsync, rename over `path`. Frees w either way. */
cs_status tsv_writer_commit(tsv_writer *w);
/* Remove the temp file. Frees w. */
void tsv_writer_abort(tsv_writer *w);

#endif
