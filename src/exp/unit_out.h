/* unit_out: how a unit of the teacher experiments writes its tables
 * (design.md §9, §12): <out>/<experiment>/<file>.tsv opened for an atomic
 * write and committed after the provenance block; the metadata lines every
 * unit writes; the crown and outline tables the canopy figures read. */
#ifndef UNIT_OUT_H
#define UNIT_OUT_H
#include "exp_common.h"

/* Open <o->out>/<experiment>/<file> for an atomic write; path receives it. */
cs_status unit_out_open(const exp_opts *o, const char *experiment, const char *file, tsv_writer **w,
                       char *path, size_t pathsz);
/* Commit and report "wrote PATH (s)". */
cs_status unit_out_finish(tsv_writer *w, prov *pv, const char *path);
/* Metadata lines shared by all units (after the provenance block). */
void unit_out_meta(tsv_writer *w, const exp_opts *o);

/* Figure crowns: columns panel spacing_m tree x_m y_m h_m interior r0..r23,
 * one row per tree of one panel. */
void unit_out_crown_columns(tsv_writer *w);
void unit_out_crowns(tsv_writer *w, const char *panel, double d, const stand *sd, const double *r);
/* <experiment>/figure_poly_<panel>_<d>.tsv: the outlines of one panel. */
cs_status unit_out_polygons(const exp_opts *o, prov *pv, const char *experiment, const char *panel, double d,
                             const stand *sd, const double *r, double k1);

#endif
