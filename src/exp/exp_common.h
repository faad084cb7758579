/* exp_common: what the teacher experiments' units share (design.md §7, §9, §12).
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

/* ---- readings (design.md §7 E0): the teacher rule and the E5/E6 field layout ----
 * A reading is a runnable switch, never a copied file: --teacher teacher-1|
 * teacher-2 (default teacher-2, design.md §4) on every teacher unit, --layout r1|r2
 * (default r2, design.md §7 E5) on the field/anisotropy units. The provenance's
 * teacher_version names the reading that made the file. */
typedef enum { EXP_LAYOUT_R2 = 0, EXP_LAYOUT_R1 = 1 } exp_layout;
typedef struct { int one_sided; exp_layout layout; } exp_reading;
/* Parse the two switches (NULL: the default); CS_EUSAGE-like CS_EINPUT naming the option. */
cs_status exp_reading_parse(const char *teacher, const char *layout, exp_reading *r);
/* A unit sets its teacher_params from the reading with
 * teacher_params_default(&p); p.one_sided = rd.one_sided; (exp_common.h does
 * not include the teacher, so the include depth stays within the layout's). */
/* prov_begin for a teacher unit, recording the reading's teacher_version
 * (not the pinned default) so a teacher-1 run says which teacher made it. */
void exp_prov_begin(prov *p, const char *experiment, const exp_reading *r, int argc, char **argv);
/* Field stands of a layout: spacing and footprint (design.h). */
double exp_field_d(exp_layout l);
double exp_field_L(exp_layout l);
const char *exp_layout_name(exp_layout l);

typedef struct {
    const char *out;  /* results root, e.g. build/results */
    exp_reading rd;   /* the reading the unit runs (teacher rule) */
    int stands;       /* stands per cell */
    double beta;      /* NAN: the gate's dieback_train (E2), no beta_field row (hero) */
    const char *tag;  /* E2 output tag: "train" | "field" */
    int argc;         /* the command line, for the provenance block */
    char **argv;
} exp_opts;

/* Stand counts used when --stands is not given (recorded in provenance). */
#define EXP_STANDS_DEFAULT 8
/* The canopy figures' stands (design.md §2, §7 E1/E8/E9): hard-core, L = 36 m. */
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
cs_status exp_field_grow_append(const stand *sd, const exp_reading *rd, double beta, int coupled, double level,
                                unsigned index, fs_trees *acc, double *worst);

/* ---- E5/E6 (exp_field.c, exp_aniso.c): field stands, options and tables ----
 * Field stands: the controlled lattice (or a hard-core family) at
 * d = exp_field_d(layout), L = exp_field_L(layout) (r2: 4 m on 36 m; r1: 5 m
 * on 60 m), teacher at N = 48, gamma = 1; each command's seeds and outputs
 * are described in its file. */

/* The arguments of the E5/E6 entry points (filled by src/cli/cli_field.c);
 * each command uses the ones it needs. */
typedef struct {
    const char *out, *calibration, *sweep, *jitter_calibration;
    const char *teacher, *layout; /* --teacher, --layout as given (NULL: defaults) */
    long stands_opt;  /* --stands as parsed */
    unsigned stands;  /* stands per level */
    exp_reading rd;   /* the reading from teacher and layout */
    int argc;         /* the command line, for the provenance */
    char **argv;
} exp_field_opts;
/* The canonical jitter of the field stands (gates/anisotropy.gate). */
cs_status exp_canonical_jitter(double *a);

/* One group of stands: `nstands` stands of one stem process at one level. */
typedef struct {
    const char *seed_exp;
    stand_kind kind;
    double shape, level, beta;
    unsigned nstands;
    int twins;          /* also grow the uncoupled twin of each stand */
    size_t failed;      /* out: stands that could not be built (hard-core "unbuildable") */
    exp_reading rd;     /* teacher rule and layout (zero: teacher-2, r2) */
} exp_field_job;

/* Grow the stands of j (and their uncoupled twins) and append their interior
 * trees to acc; a hard-core stand that cannot be built counts in j->failed. */
cs_status exp_field_run_job(exp_field_job *j, fs_trees *acc, double *worst);

typedef void (*exp_field_meta_fn)(tsv_writer *w, void *ctx);
/* Write X_trees.tsv then X.tsv (one summary row per job and arm); meta (may
 * be NULL) adds the metadata lines of the summary. */
cs_status exp_field_write(const char *out, prov *p, const fs_trees *acc, const exp_field_job *jobs, size_t nj,
                          exp_field_meta_fn meta, void *ctx);
/* The metadata of most E5/E6 tables ("what", "beta_field"): ctx is an exp_meta_ctx. */
typedef struct { double beta_field, a; const char *what; } exp_meta_ctx;
void exp_meta_generic(tsv_writer *w, void *ctx);
/* With FIELD_TABLE: print sim/field spread ratios (informational; the claims
 * recompute them from the frozen table and the same field table). */
void exp_print_spread_ratios(const char *cmd, const fs_trees *acc, double level, int twins);

#endif
