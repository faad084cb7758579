/* experiments: E1 mechanism and E2 irreducibility (SPEC §7; reference paper
 * §3.2, §3.3) and the teacher figure data (mechanism, hero, point cloud), one
 * CLI unit each, writing <out>/<experiment>/<unit>.tsv with the provenance
 * block. The command handlers return process exit codes (SPEC §11) and never
 * exit themselves. */
#ifndef EXPERIMENTS_H
#define EXPERIMENTS_H
#include "cs.h"

/* crownshy bench-teacher [reps] */
int exp_cmd_bench_teacher(int argc, char **argv);
/* crownshy run <unit> [--stands N] [--out DIR] [--beta B] [--tag T] */
int exp_cmd_run(int argc, char **argv);

/* Stand counts used when --stands is not given (recorded in provenance). */
#define EXP_STANDS_DEFAULT 8

#endif
