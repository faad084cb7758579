/* exp_aniso: CLI commands of E6 (anisotropy attribution), design.md §7; reference
 * paper §5.4. Each returns a process exit code (design.md §11); the table in
 * src/cli/cli.c lists them. They run at beta_field from E5's calibration. */
#ifndef EXP_ANISO_H
#define EXP_ANISO_H

int cmd_aniso_lattice(int argc, char **argv);
int cmd_aniso_hardcore(int argc, char **argv);
int cmd_aniso_jitter(int argc, char **argv);
int cmd_aniso_jitter_calibrate(int argc, char **argv);
int cmd_aniso_heldout(int argc, char **argv);

#endif
