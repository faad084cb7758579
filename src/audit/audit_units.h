/* audit_units: every unit table's identity (audit/README.md, "What `make
 * verify` prints"): the seed and arm a run, probes or samples table's name
 * carries against its command line and its rows, its volume against its
 * evaluation line. A consistent fabrication that also rewrites the command
 * line passes here; the spot check and tier 2 redraw it from its weights. */
#ifndef AUDIT_UNITS_H
#define AUDIT_UNITS_H
#include "checklist.h"
#include "claims.h"

/* Every unit table (run_, probes_, samples_sNN_ARM.tsv under frozen/): the
 * seed and arm its name carries equal its command line's (--seed, --arm, the
 * path it wrote) and its rows' seed and arm columns; its --volume its
 * evaluation line's. A swapped or copied unit fails, naming it. */
void audit_identities(const claims *c, checklist *cl);
#endif
