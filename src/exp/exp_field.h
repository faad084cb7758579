/* exp_field: CLI commands of E5 (field validation), design.md §7; reference
 * paper §5.3. Each returns a process exit code (design.md §11); the table in
 * src/cli/cli.c lists them. E6 (anisotropy) is exp_aniso.h. */
#ifndef EXP_FIELD_H
#define EXP_FIELD_H

int cmd_field_summary(int argc, char **argv);
int cmd_field_calibrate(int argc, char **argv);
int cmd_field_beta(int argc, char **argv);
int cmd_field_heldout(int argc, char **argv);
int cmd_field_diagnose(int argc, char **argv);

#endif
