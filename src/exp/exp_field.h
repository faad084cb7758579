/* exp_field: CLI commands of E5 (field validation) and E6 (anisotropy
 * attribution), SPEC §7; reference paper §5.3, §5.4. Each returns a process
 * exit code (SPEC §11); the table in src/cli.c lists them. */
#ifndef EXP_FIELD_H
#define EXP_FIELD_H

int cmd_field_summary(int argc, char **argv);
int cmd_field_calibrate(int argc, char **argv);
int cmd_field_beta(int argc, char **argv);
int cmd_field_heldout(int argc, char **argv);
int cmd_aniso_lattice(int argc, char **argv);
int cmd_aniso_hardcore(int argc, char **argv);
int cmd_aniso_jitter(int argc, char **argv);
int cmd_aniso_jitter_calibrate(int argc, char **argv);
int cmd_aniso_heldout(int argc, char **argv);
int cmd_field_diagnose(int argc, char **argv);

#endif
