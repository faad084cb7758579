/* fieldrun: the field stands of E5 (exp_field.c, reference paper §5.3) and
 * E6 (exp_anisotropy.c, §5.4), design.md §7: groups of stands grown at one level,
 * their per-tree and summary tables, the arguments of those commands.
 * Field stands: the controlled lattice (or a hard-core family) at
 * d = exp_field_d(layout), L = exp_field_L(layout) (4m-on-36m or
 * 5m-on-60m), teacher at N = 48, gamma = 1; each command's seeds and outputs
 * are described in its file. */
#ifndef FIELDRUN_H
#define FIELDRUN_H
#include "exp_common.h"


/* The arguments of the E5/E6 entry points (filled by src/cli/cli_field.c);
 * each command uses the ones it needs. */
typedef struct exp_field_opts exp_field_opts;
struct exp_field_opts {
    const char *out, *calibration, *sweep, *jitter_calibration;
    const char *teacher, *layout, *vary; /* --teacher, --layout, --vary as given (NULL: defaults) */
    long stands_opt;  /* --stands as parsed */
    unsigned stands;  /* stands per level */
    exp_reading rd;   /* the reading from teacher, layout and vary */
    int argc;         /* the command line, for the provenance */
    char **argv;
};
/* The canonical jitter of the field stands (gates/anisotropy.gate). */
cs_status fieldrun_canonical_jitter(double *a);

/* One group of stands: `nstands` stands of one stem process at one level. */
typedef struct {
    const char *seed_exp;
    const stems_type *kind;
    double shape, level, beta;
    unsigned nstands;
    int twins;          /* also grow the uncoupled twin of each stand */
    size_t failed;      /* out: stands that could not be built (hard-core "unbuildable") */
    exp_reading rd;     /* teacher rule and layout (zero: teacher-2, 4m-on-36m) */
} fieldrun_job;

/* Grow the stands of j (and their uncoupled twins) and append their interior
 * trees to acc; a hard-core stand that cannot be built counts in j->failed. */
cs_status fieldrun_run(fieldrun_job *j, fs_trees *acc, double *worst);

typedef void (*fieldrun_meta_fn)(tsv_writer *w, void *ctx);
/* Write X_trees.tsv then X.tsv (one summary row per job and arm); meta (may
 * be NULL) adds the metadata lines of the summary. */
cs_status fieldrun_write(const char *out, prov *p, const fs_trees *acc, const fieldrun_job *jobs, size_t nj,
                          fieldrun_meta_fn meta, void *ctx);
/* The metadata of most E5/E6 tables ("what", "beta_field"): ctx is an fieldrun_meta_ctx. */
typedef struct { double beta_field, a; const char *what; } fieldrun_meta_ctx;
void fieldrun_meta_generic(tsv_writer *w, void *ctx);
/* With FIELD_TABLE: print sim/field spread ratios (informational; the claims
 * recompute them from the frozen table and the same field table). */
void fieldrun_print_spread_ratios(const char *cmd, const fs_trees *acc, double level, int twins);

#endif
