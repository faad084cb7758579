/* afile: atomic file writes (design.md §11), and the one whole-file reader. A file is written as
 * "<path>.tmp.<pid>.<n>" (unique, so concurrent writers never collide) and renamed over <path> only on commit, after
 * flush and fsync, so a killed run never leaves a half-written result that later counts as done; a run terminated by a
 * signal the CLI asked afile to watch removes its live temp files too (a SIGKILL cannot be caught: its temp files stay,
 * never counted as done, named by their pid). Used by the TSV writer, numbers.tex / comparison.tex and
 * audit/frozen.sha256. */
#ifndef AFILE_H
#define AFILE_H
#include "cs.h"
#include <stdio.h>

typedef struct {
    FILE *f;         /* write here between open and commit */
    char *path, *tmp;
    int err;         /* set by the caller when a write fails; commit then fails */
} afile;

/* Create the parent directories of `path` (mkdir -p of its directory part). */
cs_status afile_mkdir_parents(const char *path);
/* Parent directories, then a unique "<path>.tmp.<pid>.<n>" opened for writing. */
cs_status afile_open(afile *a, const char *path);
/* Flush, fsync, close and rename into place; on any failure (a->err, a write
 * error on a->f, flush, sync, close or rename) the temp file is removed and
 * the error names it. Releases a either way. */
cs_status afile_commit(afile *a);
/* Close and remove the temp file; releases a. */
void afile_abort(afile *a);
/* From now on SIGTERM, SIGINT and SIGHUP (each unless ignored, as nohup
 * ignores SIGHUP) first remove the temp files open at that moment, then kill
 * the process with the same signal, so a caller (make, Slurm) still sees it
 * die of it. For single-threaded writers; past AFILE_LIVE files open at once
 * the extra ones are not watched. Called once, by the CLI. */
#define AFILE_LIVE 32
void afile_remove_on_signal(void);
/* A whole file read into a NUL-terminated malloc'd string (the reader's
 * counterpart, for small text files: logs, renderer records); NULL when it
 * cannot be opened or memory runs out. */
char *afile_read(const char *path);

#endif
