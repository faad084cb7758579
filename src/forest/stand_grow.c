/* stand_grow: see stand_grow.h. */
#include "stand_grow.h"

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
