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
#include "dvec.h"
#include "fieldsim.h"
#include "prov.h"
#include "stand.h"
#include "tsv.h"
#include <stddef.h>

/* ---- readings (design.md §7 E0): the teacher rule and the E5/E6 field layout ----
 * A reading is a runnable switch, never a copied file: --teacher teacher-1|
 * teacher-2 (default teacher-2, design.md §4) on every teacher unit, --layout 4m-on-36m|
 * 5m-on-60m (default 4m-on-36m, design.md §7 E5) on the field/anisotropy units. The provenance's
 * teacher_version names the reading that made the file. */
typedef enum { EXP_LAYOUT_4M_ON_36M = 0, EXP_LAYOUT_5M_ON_60M = 1 } exp_layout;

/* ---- sensitivity (design.md §7 E0): one unstated choice changed ----
 * --vary NAME=VALUE on every teacher unit (NAME from unstated.h) sets one of
 * these away from the design's value; a reading with varied = 0 is the
 * design (the zero reading stays the adopted one). */
typedef struct {
    char name[32];       /* the choice (unstated.h), "" when not varied */
    double value;        /* its value */
    crown_dist crowns;   /* the crown draws (crown.h) */
    int nres;            /* growth resolution N of every growth but E2's refinement levels */
    double start_frac;   /* start radius / target */
    double fig_c;        /* hard-core level of the figure stands */
    double field_d, field_L; /* field stands (the 4m-on-36m layout's values otherwise) */
    int dieback;         /* the die-back reading (0: the reading's own) */
} exp_variant;

/* dieback: the teacher's die-back reading (teacher.h teacher_dieback: 0 own
 * sector, Eq. 3 as written; 1 the contact arc s-1..s+1; 2 beta of the target
 * length), chosen by the --teacher suffix -arc / -target. */
typedef struct { int one_sided; exp_layout layout; int dieback; int varied; exp_variant var; } exp_reading;
/* Parse the switches (NULL: the default); CS_EINPUT naming the option.
 * vary: "NAME=VALUE" (unstated.h names) or NULL. */
cs_status exp_reading_parse(const char *teacher, const char *layout, exp_reading *r);
cs_status exp_reading_vary(const char *vary, exp_reading *r);
/* Set teacher_params *p (teacher.h) to the reading's rule: the default with
 * r's rule and, when varied, its resolution and start radius. A macro so that
 * this header need not include the teacher (the include depth of the units). */
#define EXP_TEACHER_PARAMS(r, p) do { \
        const exp_reading *exp_rd_ = (r); \
        teacher_params_default(p); \
        if (exp_rd_) { \
            (p)->one_sided = exp_rd_->one_sided; \
            (p)->dieback = (teacher_dieback)exp_rd_->dieback; \
            if (exp_rd_->varied) { (p)->nres = exp_rd_->var.nres; (p)->start_frac = exp_rd_->var.start_frac; } \
        } \
    } while (0)
/* stand_alloc_dist with the reading's crown draws (r may be NULL). */
cs_status exp_stand_alloc(const exp_reading *r, stand **out, const stems_type *kind, double d, double L, double shape,
                          const char *experiment, unsigned index);
/* Hard-core level of the figure stands (EXP_FIG_C unless varied). */
double exp_fig_c(const exp_reading *r);
/* Growth resolution of the reading (48 unless varied). */
int exp_nres(const exp_reading *r);
/* Provenance/metadata line of a varied reading ("-" for the design). */
void exp_variant_meta(tsv_writer *w, const exp_reading *r);
/* prov_begin for a teacher unit, recording the reading's teacher_version
 * (not the pinned default) so a teacher-1 run says which teacher made it. */
void exp_prov_begin(prov *p, const char *experiment, const exp_reading *r, int argc, char **argv);
/* Field stands of a reading: its layout's spacing and footprint (design.h),
 * or the varied ones. */
double exp_field_d(const exp_reading *r);
double exp_field_L(const exp_reading *r);
const char *exp_layout_name(exp_layout l);

typedef struct {
    const char *out;  /* results root, e.g. build/results */
    exp_reading rd;   /* the reading the unit runs (teacher rule) */
    int stands;       /* stands per cell */
    double beta;      /* NAN: the gate's dieback_train (E2), no beta_field row (hero) */
    const char *tag;  /* E2 output tag: "train" | "field" */
    int stand_rows;   /* E1 sweep, E2: also write the per-stand rows of the pooled tables (design.md §6.1) */
    int argc;         /* the command line, for the provenance block */
    char **argv;
} exp_opts;

/* Stand counts used when --stands is not given (recorded in provenance). */
#define EXP_STANDS_DEFAULT 8
/* The canopy figures' stands (design.md §2, §7 E1/E8/E9): hard-core, L = 36 m. */
#define EXP_FIG_L 36.0
#define EXP_FIG_C 0.5

/* k = 1..3 NN clearances of the interior trees, appended to g[0..2];
 * interior cover (cover may be NULL); *ntrees (may be NULL) += interior trees. */
cs_status exp_stand_metrics(const stand *sd, const double *r, dvec g[3], double *cover, size_t *ntrees);
/* Median k1 clearance of the interior trees of one stand (NAN on failure). */
double exp_stand_k1(const stand *sd, const double *r);

/* E5/E6: grow stand sd with the teacher (beta; coupled or the uncoupled
 * twin) and append its interior trees tagged (coupled, level, stand index).
 * *worst (may be NULL) is raised to the self-check overlap of the growth. */
cs_status exp_field_grow_append(const stand *sd, const exp_reading *rd, double beta, int coupled, double level,
                                unsigned index, fs_trees *acc, double *worst);

#endif
