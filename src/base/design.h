/* design: constants fixed by the design (SPEC §2, §7) that no gate file
 * carries. Gate-file values are always read from gates/, never repeated here. */
#ifndef DESIGN_H
#define DESIGN_H

#define DESIGN_FIGURE_L_M 36.0        /* figure footprint (SPEC §2) */
#define DESIGN_GENCOMP_SPACING_M 5.0  /* E7 patch spacing, unseen in training (SPEC §7 E7) */
#define DESIGN_PC_SPACING_M 3.0       /* E8 densest stand (SPEC §7 E8) */
#define DESIGN_PC_OTHER_A_SPACING_M 5.0
#define DESIGN_PC_OTHER_B_SPACING_M 4.0
#define DESIGN_FIELD_SPACING_M 5.0    /* E5 field stands (SPEC §7 E5) */

#endif
