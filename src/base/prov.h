/* prov: the provenance block every frozen TSV starts with (design.md §9):
 * experiment, command, teacher version (the reading that made the result),
 * teacher/estimator/gates SHA-256,
 * git commit, seeds, date, wall time, worst overlap. Hashes are computed from
 * the source files at run time (the pinned sources named in paths.h, gates/
 * *.gate in name order), so the audit can compare them with audit/pins.tsv. The
 * teacher version is the one the pinned teacher header declares; a run of
 * another reading of the teacher overwrites p->teacher_version. */
#ifndef PROV_H
#define PROV_H
#include "cs.h"
#include "tsv.h"

typedef struct {
    char experiment[64];
    char command[512];   /* the command line that produced the file */
    char teacher_version[32]; /* the reading that made the result: prov_begin sets the
                                 pinned default (PATHS_TEACHER_HDR); a unit that runs
                                 another reading copies teacher_version(params) here */
    char seeds[256];     /* how seeds were derived, e.g. "seed_derive(mechanism,d,stand,stream) stands 0..7" */
    double wall_s;       /* wall time of the producing run, seconds */
    double worst_overlap_m; /* max teacher self-check overlap over the run; <0 if not applicable */
    double t0;           /* start time (internal) */
} prov;

/* Start: records experiment name, command line ("crownshy " + argv joined; argv[0]
 * is the subcommand as the CLI passes it) and start time. */
void prov_begin(prov *p, const char *experiment, int argc, char **argv);
/* Write all provenance lines (computes wall time now, hashes, git commit, date). */
cs_status prov_write(tsv_writer *w, prov *p);
/* The version string the pinned teacher header declares
 * (#define TEACHER_VERSION "..."); CS_EINPUT naming file and line if absent. */
cs_status prov_teacher_version(char *out, size_t n);
/* The one-sided reading's string (#define TEACHER_VERSION_ONE_SIDED "..."),
 * which the readings (design.md §7 E0) record under frozen/readings/. */
cs_status prov_teacher_version_one_sided(char *out, size_t n);
/* SHA-256 of a file as 64 lowercase hex chars (+NUL). */
cs_status prov_sha256_file(const char *path, char hex[65]);
/* SHA-256 of gates/ *.gate concatenated in name order. */
cs_status prov_gates_sha256(const char *gates_dir, char hex[65]);
/* Monotonic seconds. */
double prov_now(void);

/* v is the teacher version `base` under one of the teacher's readings: base
 * itself, or base with a die-back suffix (teacher.h teacher_version()). */
int prov_reading_version(const char *v, const char *base);
/* Whether a provenance key names the code a reading changes (the teacher's
 * version and sources, the estimator's): the keys a superseded reading excuses. */
int prov_reading_key(const char *key);

#endif
