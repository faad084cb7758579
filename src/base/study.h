/* study: the experiments of the manifest (src/base/manifest.h) as data, for
 * the commands that name an experiment (trace, the layout checks through
 * `manifest.sh rows`). Limits: the manifest's make text is not here; the
 * build reads it through src/base/manifest.sh. */
#ifndef STUDY_H
#define STUDY_H
#include <stddef.h>

typedef struct {
    const char *name, *code, *source, *gate, *claims, *figure, *deep, *what;
} study_experiment;

/* The experiment whose frozen folder holds path ("frozen/<name>/..." or
 * "<root>/<name>/..."), or NULL. */
const study_experiment *study_of_path(const char *path);

#endif
