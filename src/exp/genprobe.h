/* genprobe: what a generator uses (design.md §8.4; reference paper §5.1).
 * Evaluation-only probes on frozen weights: the model generates the crowns of
 * the evaluation patches with one thing it could use taken away or falsified,
 * and the focal nearest-neighbour clearances are evaluated at the true
 * positions, W1 against the teacher's as in E3:
 *   none      the patches as they are (the unit's own reference error);
 *   self      attention masked to the tree itself (the independent arm's mask
 *             on the same weights: nothing from any other tree);
 *   rot15, rot45, rot90
 *             the patch geometry turned about the focal stem by 15, 45 or 90
 *             degrees (a lattice turned by 90 degrees is the same lattice: a
 *             model that reads only the lattice's orientation is blind to it);
 *   nnswap    the nearest neighbour's position features exchanged with those
 *             of the 2nd, 3rd or 4th nearest (drawn per patch);
 *   dejitter  every position snapped to the ideal lattice through the focal
 *             stem, oriented by the rotation that best maps the lattice
 *             coordinates onto the positions (pair offsets become exact
 *             lattice vectors: they no longer carry the jitter);
 *   sizes     the neighbours' size features (rbar/d) permuted among them.
 * The teacher's side of a probe (a perfect generator: the teacher's own
 * crowns under it) where one exists: rot15/45/90 (the crowns turned by whole
 * sectors, exact) and nnswap (the two trees' profiles exchanged, as the
 * shuffled probe's teacher side). Volume: the 16-stands evaluation volume (16
 * teacher stands and 256 generated patches per unseen spacing, mainrun.h), the same for
 * every reading; each probe samples from its own seed
 * seed_derive("generator-probes-<probe>", d, seed, "sample"), the swap
 * partners and the size permutation from seed_derive("generator-probes", d,
 * seed, "nnswap" | "sizes"). Returns cs_status; never exits. */
#ifndef GENPROBE_H
#define GENPROBE_H
#include "cs.h"
#include "probekind.h"
#include <gsl/gsl_rng.h>

/* Probe k applied in place to the token features feat[n * T * NFEAT] of n
 * patches (patch.h layout); rng draws nnswap's partners and sizes'
 * permutations (unused by the others). none and self leave them. */
void genprobe_apply(probekind k, float *feat, int n, gsl_rng *rng);

/* The ideal lattice point (unit spacing, orientation theta) nearest (x, y),
 * the lattice through the origin. */
void genprobe_snap(double x, double y, double theta, double *sx, double *sy);

typedef struct {
    const char *weights;  /* frozen weights (NULL with perfect) */
    const char *trained;  /* the unit's run table the weights were frozen with (provenance) */
    const char *arm;      /* "joint" or "indep": must be the weights' */
    const char *reading;  /* the weights' reading, checked (NULL: any) */
    const char *scale;    /* "full" or "smoke" */
    const char *out;      /* the probe table */
    const char *samples;  /* also the clearances behind every W1 (NULL: none) */
    unsigned seed;        /* the model seed of the weights (sampling seeds derive from it) */
    int perfect;          /* 1: the teacher's side of every probe that has one, no model */
    int argc;
    char **argv;
} genprobe_args;

/* One unit: every probe at every unseen spacing, the table (spacing, probe,
 * w1, n_gen, n_teacher) with provenance, atomically. */
cs_status genprobe_run(const genprobe_args *a);

#endif
