/* evalvol: the evaluation volumes of the E3/E4 units (design.md §8,
 * "Evaluation volumes"), named by their teacher stands per evaluation spacing
 * at full scale, shared by the experiment that evaluates at them
 * (src/exp/mainrun.h, where each is described) and the audit that reads the
 * volume of a frozen run table back from its evaluation line. */
#ifndef EVALVOL_H
#define EVALVOL_H
#include "cs.h"

/* The small volume: the pair runs of frozen/extension-pair-16-stands/main/
 * (16 teacher stands and 256 generated patches per spacing). */
#define EVALVOL_SMALL "16-stands"
#define EVALVOL_SMALL_EVAL_STANDS 16
#define EVALVOL_SMALL_GEN_PATCHES 256
/* The large volume, every generator reading's: chosen from the split-half
 * noise floor and its cost, measured (README "Budgets"). */
#define EVALVOL_LARGE "96-stands"
#define EVALVOL_LARGE_EVAL_STANDS 96
#define EVALVOL_LARGE_GEN_PATCHES 1536

/* The volume a run table was evaluated at, read from its "# eval:" line by
 * the teacher stands per spacing the line states (full scale): its name into
 * *name; CS_EINPUT when the line states neither volume's count. */
cs_status evalvol_of_eval(const char *eval, const char **name);

#endif
