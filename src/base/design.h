/* design: constants fixed by the design (design.md §2, §7) that no gate file
 * carries. Gate-file values are always read from gates/, never repeated here. */
#ifndef DESIGN_H
#define DESIGN_H

#define DESIGN_FIGURE_L_M 36.0        /* figure footprint (design.md §2) */
#define DESIGN_GENCOMP_SPACING_M 5.0  /* E7 patch spacing, unseen in training (design.md §7 E7) */
#define DESIGN_PC_SPACING_M 3.0       /* E8 densest stand (design.md §7 E8) */
#define DESIGN_PC_OTHER_A_SPACING_M 5.0
#define DESIGN_PC_OTHER_B_SPACING_M 4.0
/* E5/E6 field stands (design.md §7 E5, layout 4m-on-36m): lattice d = 4 m on the
 * figure footprint L = 36 m (9 x 9 stems, ~25 interior trees; the paper: 731
 * trees in 28 stands). Layout 5m-on-60m (a reading, design.md §7 E0): d = 5 m, L = 12 d = 60 m (64 interior trees per
 * stand). */
#define DESIGN_FIELD_SPACING_M 4.0
#define DESIGN_FIELD_L_M 36.0
#define DESIGN_FIELD_SPACING_WIDE_M 5.0
#define DESIGN_FIELD_L_WIDE_M 60.0

#endif
