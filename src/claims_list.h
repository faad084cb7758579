/* claims_list: every computing function the registry may name (X-macro).
 * A function listed here but named by no row of audit/claims.tsv is an orphan
 * and fails the audit; a row naming an unlisted function is PENDING. */
X(claim_design_mech_rows)
X(claim_design_irred_spacings)
X(claim_design_irred_refine_max)
X(claim_design_dieback_train)
X(claim_design_main_seeds)
X(claim_design_main_epochs)
X(claim_design_train_spacings)
X(claim_design_calib_target)
X(claim_design_calib_seeds)
X(claim_design_jitter_canonical_pct)
X(claim_design_nsec)
X(claim_design_patch_trees)
X(claim_design_gencomp_spacing)
X(claim_design_pc_spacing)
