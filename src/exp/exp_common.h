/* exp_common: what the teacher experiments' units share (SPEC §7, §9, §12).
 * A unit writes <out>/<experiment>/<file>.tsv atomically, starting with the
 * provenance block; the figure units also write the crowns and outlines the
 * gnuplot scripts read. Choices the spec leaves open, written down here and
 * in each file's provenance:
 *  - stands per cell: 8 (--stands), stand k of spacing d uses
 *    seed_derive(<experiment key>, d, k, "stems"/"crowns"); the E1 sweep rows
 *    of one spacing and the ablation share stands (identical stems and draws);
 *  - statistics pool interior trees (>= 2 d from the edge) over the stands of
 *    a cell: k-th NN clearance = median of the pooled values; cover = mean
 *    over stands of the interior-square cover;
 *  - figures: hard-core stems c = 0.5, L = 36 m. */
#ifndef EXP_COMMON_H
#define EXP_COMMON_H
#include "cs.h"
#include "fieldsim.h"
#include "prov.h"
#include "stand.h"
#include "tsv.h"
#include <stddef.h>

typedef struct {
    const char *out;  /* results root, e.g. build/results */
    int stands;       /* stands per cell */
    double beta;      /* NAN: the gate's dieback_train (E2), no beta_field row (hero) */
    const char *tag;  /* E2 output tag: "train" | "field" */
    int argc;         /* the command line, for the provenance block */
    char **argv;
} exp_opts;

/* Stand counts used when --stands is not given (recorded in provenance). */
#define EXP_STANDS_DEFAULT 8
/* The canopy figures' stands (SPEC §2, §7 E1/E8/E9): hard-core, L = 36 m. */
#define EXP_FIG_L 36.0
#define EXP_FIG_C 0.5

/* Growable double array. */
typedef struct { double *v; size_t n, cap; } exp_dvec;
cs_status exp_dvec_push(exp_dvec *a, double x);

/* k = 1..3 NN clearances of the interior trees, appended to g[0..2];
 * interior cover (cover may be NULL); *ntrees (may be NULL) += interior trees. */
cs_status exp_stand_metrics(const stand *sd, const double *r, exp_dvec g[3], double *cover, size_t *ntrees);
/* Median k1 clearance of the interior trees of one stand (NAN on failure). */
double exp_stand_k1(const stand *sd, const double *r);

/* Open <o->out>/<experiment>/<file> for an atomic write; path receives it. */
cs_status exp_open_out(const exp_opts *o, const char *experiment, const char *file, tsv_writer **w,
                       char *path, size_t pathsz);
/* Commit and report "wrote PATH (s)". */
cs_status exp_finish(tsv_writer *w, prov *pv, const char *path);
/* Metadata lines shared by all units (after the provenance block). */
void exp_common_meta(tsv_writer *w, const exp_opts *o);

/* Figure crowns: columns panel spacing_m tree x_m y_m h_m interior r0..r23,
 * one row per tree of one panel. */
void exp_crown_columns(tsv_writer *w);
void exp_write_crowns(tsv_writer *w, const char *panel, double d, const stand *sd, const double *r);
/* <experiment>/figure_poly_<panel>_<d>.tsv: the outlines of one panel. */
cs_status exp_write_polygons(const exp_opts *o, prov *pv, const char *experiment, const char *panel, double d,
                             const stand *sd, const double *r, double k1);

/* E5/E6: grow stand sd with the teacher (beta; coupled or the uncoupled
 * twin) and append its interior trees tagged (coupled, level, stand index).
 * *worst (may be NULL) is raised to the self-check overlap of the growth. */
cs_status exp_field_grow_append(const stand *sd, double beta, int coupled, double level, unsigned index,
                                fs_trees *acc, double *worst);

#endif
