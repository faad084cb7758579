/* spot: a derivation spot-checked in tier 1 (audit/README.md "What tier 1
 * guarantees"). Each verify picks one slice at random: one frozen generator
 * unit (a weights file with its samples and run table beside it), one
 * spacing and one probe of its run table, and draws that slice again from the
 * weights with `crownshy main-redraw --spacing --probe --patches` (the
 * teacher's evaluation stands of that spacing regrown, the probe's first 64
 * patches generated: a prefix of the whole, bit for bit),
 * in the background while the rest of verify runs; the rows must equal those
 * of the frozen samples bit for bit. The pick comes from a seed the reviewer
 * gives (SEED=) or from the clock, and is printed so it can be repeated.
 * Limits: one slice per verify; a fabricated unit is caught by one verify
 * with probability (its fabricated slices) / (all slices), printed with the
 * count. */
#ifndef SPOT_H
#define SPOT_H
#include "checklist.h"
#include "claims.h"

/* Pick the slice (seed: the reviewer's; 0: from the clock) and start its
 * redraw in the background. */
void spot_launch(unsigned long seed);
/* Wait for the redraw and compare it; one checklist line (c, may be NULL,
 * names the claims a failing slice feeds). */
void spot_check(checklist *cl, const claims *c);
#endif
