/* exp_comp: E7, the generated-stand comparison (reference paper Fig. teaser
 * b-d and Limitations; design.md §7 E7). One 24-tree patch at 5.0 m (unseen in
 * training): teacher crowns, the joint model's and the independent arm's
 * (seed 1 of E3, the matched-capacity "attention ablated" twin), each with
 * the median nearest-neighbour clearance over the patch trees and the count
 * of crowns running into a neighbour. The dart probe: the joint model on
 * hard-core stems against the teacher on the same stands. */
#ifndef EXP_COMP_H
#define EXP_COMP_H

#include "cs.h"

/* The entry point (argv table: src/cli/cli_main.c). */
typedef struct {
    const char *joint, *indep; /* E3 seed-1 weights (or checkpoints) of each arm */
    const char *out;           /* results root: writes out/comparison/{patch,patch_crowns,dart_probe}.tsv */
    int argc;                  /* the command line, for the provenance */
    char **argv;
} exp_comp_args;
cs_status exp_comp_run(const exp_comp_args *a);

#endif
