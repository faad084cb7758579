/* mainsum: the E3/E4 units that need no model: main-baselines (the baselines
 * of an evaluation volume) and main-summary (a reading's per-run tables into
 * its main/runs.tsv and extrapolation/runs.tsv); see mainsum.c. CLI entry
 * points (return process exit codes; design.md §11). */
#ifndef MAINSUM_H
#define MAINSUM_H

int mainsum_cmd_baselines(int argc, char **argv);
int mainsum_cmd_summary(int argc, char **argv);

#endif
