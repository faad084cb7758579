/* figdata: crown outlines for the gnuplot canopy figures (see figdata.h). */
#include "figdata.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static const double *figdata_h;
static int by_height(const void *a, const void *b)
{
    size_t i = *(const size_t *)a, j = *(const size_t *)b;
    if (figdata_h[i] != figdata_h[j]) return figdata_h[i] < figdata_h[j] ? -1 : 1;
    return (i > j) - (i < j);
}

cs_status figdata_write_polygons(tsv_writer *w, size_t n, const double *x, const double *y, const double *h,
                                 const double *r, const int *flag, const char *flag_name)
{
    size_t *ord = malloc((n ? n : 1) * sizeof *ord);
    if (!ord) return cs_err(CS_ENOMEM, "figdata: out of memory");
    for (size_t i = 0; i < n; i++) ord[i] = i;
    figdata_h = h;
    qsort(ord, n, sizeof *ord, by_height);
    char cols[128];
    snprintf(cols, sizeof cols, "tree\tx_m\ty_m\th_m%s%s", flag ? "\t" : "", flag ? flag_name : "");
    tsv_writer_columns(w, cols);
    char buf[64];
    for (size_t t = 0; t < n; t++) {
        size_t i = ord[t];
        for (int q = 0; q < FIGDATA_ROWS; q++) {
            double th = (2.0 * CROWN_PI / (CROWN_NSEC * FIGDATA_PER_SECTOR)) * (double)(q % (FIGDATA_ROWS - 1));
            double rho = crown_radius_at(r + i * CROWN_NSEC, th);
            tsv_writer_long(w, (long)i);
            snprintf(buf, sizeof buf, "%.3f", x[i] + rho * cos(th));
            tsv_writer_str(w, buf);
            snprintf(buf, sizeof buf, "%.3f", y[i] + rho * sin(th));
            tsv_writer_str(w, buf);
            snprintf(buf, sizeof buf, "%.2f", h[i]);
            tsv_writer_str(w, buf);
            if (flag) tsv_writer_long(w, flag[i]);
            tsv_writer_endrow(w);
        }
    }
    free(ord);
    return CS_OK;
}
