/* exp_irreducibility: E2 irreducibility units (design.md §7 E2; reference paper §3.3),
 * writing <out>/irreducibility/<unit>_<o->tag>.tsv at die-back beta. */
#ifndef EXP_IRREDUCIBILITY_H
#define EXP_IRREDUCIBILITY_H
#include "exp_common.h"

cs_status exp_irreducibility_perturb(const exp_opts *o, double beta);
cs_status exp_irreducibility_refine(const exp_opts *o, double beta);
cs_status exp_irreducibility_reduction(const exp_opts *o, double beta);

#endif
