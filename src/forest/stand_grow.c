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

cs_status stand_grow_bench(int nres, int reps, double *ms_per_stand)
{
    double total = 0.0;
    for (int k = 0; k < reps; k++) {
        stand *sd = NULL;
        cs_status rc = stand_alloc(&sd, stems_lattice, 3.5, 12.0 * 3.5, 0.04, "bench", (unsigned)k);
        if (rc) return rc;
        double *r = malloc(sd->s->n * CROWN_NSEC * sizeof *r);
        if (!r) { stand_free(sd); return cs_err(CS_ENOMEM, "stand_grow: out of memory"); }
        teacher_params p;
        teacher_params_default(&p);
        p.nres = nres;
        double t0 = cpu_s();
        rc = stand_grow(sd, &p, NULL, r, NULL, NULL);
        total += cpu_s() - t0;
        free(r);
        stand_free(sd);
        if (rc) return rc;
    }
    *ms_per_stand = 1e3 * total / (double)reps;
    return CS_OK;
}
