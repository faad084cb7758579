/* study: see study.h; the table is the manifest's EXPERIMENT rows. */
#include "study.h"
#include <string.h>

static const study_experiment STUDY[] = {
#define EXPERIMENT(name, code, source, gate, claims, figure, deep, what)                                               \
    {#name, code, source, gate, claims, figure, deep, what},
#include "manifest.h"
};
#define NSTUDY (sizeof STUDY / sizeof STUDY[0])

const study_experiment *study_of_path(const char *path)
{
    const char *p = strstr(path, "frozen/");
    p = p ? p + strlen("frozen/") : path;
    for (size_t i = 0; i < NSTUDY; i++) {
        size_t k = strlen(STUDY[i].name);
        if (!strncmp(p, STUDY[i].name, k) && p[k] == '/') return &STUDY[i];
    }
    return NULL;
}
