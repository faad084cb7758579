/* claim_probe: the claims of what a generator uses (claim_probe.c, design.md
 * §8.4) and the summary table of every reading's probe ratios. */
#ifndef CLAIM_PROBE_H
#define CLAIM_PROBE_H
#include "cs.h"

/* <root>/generator-probes/<reading>/probes_s*_<arm>.tsv of every reading,
 * arm, probe and seed 1..seeds gathered into the table `out` (reading, arm,
 * probe, ratio), with provenance, atomically; CS_EINPUT when a reading's
 * seeds are not all there. */
cs_status claim_probe_summary_write(const char *root, const char *out, int seeds, int argc, char **argv);

#endif
