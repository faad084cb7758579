/* exp_comp: E7, the generated-stand comparison (reference paper Fig. teaser
 * b-d and Limitations; design.md §7 E7). One 24-tree patch at 5.0 m (unseen in
 * training): teacher crowns, the joint model's and the independent arm's
 * (seed 1 of E3, the matched-capacity "attention ablated" twin), each with
 * the median nearest-neighbour clearance over the patch trees and the count
 * of crowns running into a neighbour. The dart probe: the joint model on
 * hard-core stems against the teacher on the same stands. */
#ifndef EXP_COMP_H
#define EXP_COMP_H

int exp_comp_cmd_run(int argc, char **argv);

#endif
