/* stand_grow: see stand_grow.h. */
#include "stand_grow.h"
#include <stdlib.h>
#include <time.h>

cs_status stand_grow(const stand *sd, const teacher_params *p, const double *h, double *r,
                     teacher_info *info, double *worst)
{
    teacher_stand v;
    stand_view(sd, &v);
    if (h) v.h = h;
    teacher_info tmp;
    if (!info) info = &tmp;
    cs_status st = teacher_grow(&v, p, r, info);
    if (!st && worst && info->worst_overlap > *worst) *worst = info->worst_overlap;
    return st;
}

static double cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_dbl(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

cs_status stand_grow_bench(int nres, int reps, double ms[3])
{
    if (reps < 1) reps = 1;
    double *t = malloc(sizeof *t * (size_t)reps);
    if (!t) return cs_err(CS_ENOMEM, "stand_grow: out of memory");
    cs_status rc = CS_OK;
    for (int k = 0; k < reps && !rc; k++) {
        stand *sd = NULL;
        rc = stand_alloc(&sd, stems_lattice, 3.5, 12.0 * 3.5, 0.04, "bench", (unsigned)k);
        if (rc) break;
        double *r = malloc(sd->s->n * CROWN_NSEC * sizeof *r);
        if (!r) { stand_free(sd); rc = cs_err(CS_ENOMEM, "stand_grow: out of memory"); break; }
        teacher_params p;
        teacher_params_default(&p);
        p.nres = nres;
        double t0 = cpu_s();
        rc = stand_grow(sd, &p, NULL, r, NULL, NULL);
        t[k] = 1e3 * (cpu_s() - t0);
        free(r);
        stand_free(sd);
    }
    if (!rc) {
        qsort(t, (size_t)reps, sizeof *t, cmp_dbl);
        ms[0] = reps % 2 ? t[reps / 2] : 0.5 * (t[reps / 2 - 1] + t[reps / 2]);
        ms[1] = t[0];
        ms[2] = t[reps - 1];
    }
    free(t);
    return rc;
}
