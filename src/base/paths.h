/* paths: the one place that knows where the package's files live (design.md §1,
 * §9): the preregistered gates, the audit's pins and registry, the generated
 * paper files, and the pinned instrument sources. Every path is relative to
 * the repository root, the directory every command runs from. Also the one
 * sorted directory listing the audit, verify and the CLI share. */
#ifndef PATHS_H
#define PATHS_H
#include "cs.h"
#include <stddef.h>

#define PATHS_GATES_DIR "gates"
/* PATHS_GATE("mechanism") is "gates/mechanism.gate" (string literals only). */
#define PATHS_GATE(name) PATHS_GATES_DIR "/" name ".gate"

#define PATHS_PINS "audit/pins.tsv"
/* Earlier pins of the teacher and estimator that still made frozen results
 * (a re-run is pending): `crownshy pin` appends a pin here when it changes. */
#define PATHS_PINS_SUPERSEDED "audit/pins_superseded.tsv"
#define PATHS_FROZEN_HASHES "audit/frozen.sha256"
#define PATHS_CLAIMS "audit/claims.tsv"
/* Which claim each preregistered gate key judges (macro, gate): pinned with
 * the gates (audit/pins.tsv), so dropping a verdict changes a pinned file;
 * the registry's gate column must agree with it. */
#define PATHS_GATE_MAP "audit/gate_map.tsv"
/* The same for the extension claims (kind extension: a generator reading
 * added after the first verdict, judged by the same thresholds beside the
 * reference paper's method, design.md §8): pinned like the map above. */
#define PATHS_GATE_MAP_EXT "audit/gate_map_extension.tsv"
/* Aggregate frozen tables and the per-run tables they are computed from. */
#define PATHS_AGGREGATES "audit/aggregates.tsv"
/* The design grid of every frozen table (its rows, block by block). */
#define PATHS_GRIDS "audit/grids.tsv"
/* The preregistered gates' hashes, written once at preregistration and never
 * by `crownshy pin`: the gates' anchor where no .git is present. */
#define PATHS_GATES_PREREG "audit/gates_prereg.sha256"
/* The numbers the paper text may type: constants of the design, each with
 * the file that fixes it. */
#define PATHS_DESIGN_NUMBERS "audit/design_numbers.tsv"
/* The claim-computing code, and the code that gives each claim its interval
 * and its agreement with the paper: pinned file by file. */
#define PATHS_CLAIMS_SRC_DIR "src/claims"
#define PATHS_AGREE_SRC_DIR "src/agree"
#define PATHS_AUDIT_SRC_DIR "src/audit"
/* How each measured claim's interval is computed (design.md §6.1; pinned). */
#define PATHS_INTERVALS "audit/intervals.tsv"
#define PATHS_NUMBERS "paper/numbers.tex"
/* Every measured claim's interval, %.17g (generated; the claim tests' reference). */
#define PATHS_INTERVALS_OUT "paper/intervals.tsv"
/* The one-page reproduction summary that opens the write-up (generated). */
#define PATHS_SUMMARY_TEX "paper/summary.tex"
#define PATHS_COMPARISON "paper/comparison.tex"
#define PATHS_READINGS_TEX "paper/readings.tex"
#define PATHS_READINGS_DIR "frozen/readings"
#define PATHS_READINGS_SUMMARY "frozen/readings/summary.tsv"
#define PATHS_SENS_TEX "paper/sensitivity.tex"
#define PATHS_SENS_DIR "frozen/sensitivity"
#define PATHS_SENS_SUMMARY "frozen/sensitivity/summary.tsv"
#define PATHS_MODEL_READINGS_SUMMARY "frozen/model-readings/summary.tsv"
#define PATHS_PAPER_DIR "paper"
#define PATHS_MAIN_TEX "paper/main.tex"
#define PATHS_CONSTANTS_TEX "paper/constants.tex"
#define PATHS_RENDER_DIR "build/render/paper"
#define PATHS_FIGURES_DIR "figures"
#define PATHS_CITATION "CITATION.cff"
#define PATHS_FIG_PLOTTED "figures/plotted.sha256"
#define PATHS_FIG_RENDERER "figures/renderer.tsv"
#define PATHS_FROZEN_DIR "frozen"
/* The pair extension's runs at volume 16-stands: tier 1 recomputes every W1
 * of their run tables and baselines from the samples beside them. */
#define PATHS_PAIR_16_STANDS_DIR PATHS_FROZEN_DIR "/extension-pair-16-stands"
/* Folders of frozen/ that provenance lines of frozen tables (records, kept as
 * written) name by the place they were frozen at, each with the place they
 * lie at now: {named, now}. */
#define PATHS_FROZEN_RECORDED                                                       \
    {{PATHS_FROZEN_DIR "/main/", PATHS_PAIR_16_STANDS_DIR "/main/"},                \
     {PATHS_FROZEN_DIR "/extrapolation/", PATHS_PAIR_16_STANDS_DIR "/extrapolation/"}}
/* The documentation pages the audit reads for typed numbers (design.md §9):
 * README.md and every *.md under these folders; the changelog is history. */
#define PATHS_README "README.md"
#define PATHS_DOCS_DIRS {"audit", "frozen", "src", "tests", "paper", "figures", "gates", NULL}
#define PATHS_CHANGELOG "paper/CHANGELOG.md"
/* Design constants a documentation page may type although a measured value
 * rounds to them, each with the source that holds it (beside PATHS_DESIGN_NUMBERS). */
#define PATHS_DOC_NUMBERS "audit/doc_numbers.tsv"

/* The pinned instrument (design.md §4, §5): its sources are hashed into every
 * frozen file's provenance and into audit/pins.tsv; the teacher header holds
 * the version string (#define TEACHER_VERSION). */
#define PATHS_TEACHER_SRC "src/forest/teacher.c"
#define PATHS_TEACHER_HDR "src/forest/teacher.h"
#define PATHS_ESTIMATOR_SRC "src/forest/estimator.c"

/* A sorted list of file paths ("dir/name"). */
typedef struct { char **p; size_t n, cap; } paths_list;

/* Regular files under dir whose names end in suffix ("" for any), in strcmp
 * order of their paths; recursive descends into subdirectories. Names that
 * start with '.' or contain ".tmp" (atomic-write temporaries) are skipped.
 * A missing dir gives an empty list. CS_ENOMEM on allocation failure. */
cs_status paths_list_files(const char *dir, const char *suffix, int recursive, paths_list *out);
/* Every entry under dir (also dotfiles, "*.tmp*" names and non-regular
 * entries): what the frozen-hash audit compares with its list, so nothing in
 * frozen/ is invisible to it. */
cs_status paths_list_every(const char *dir, int recursive, paths_list *out);
/* 1 when the last component starts with '.' or contains ".tmp". */
int paths_is_hidden_or_tmp(const char *path);
void paths_list_free(paths_list *l);
/* An input file must exist and be a regular file: CS_EINPUT naming it
 * ("is a directory", "cannot open: ...") instead of a later odd error. */
cs_status paths_input_file(const char *path);
/* The file a frozen table's provenance names by path (its directory joined
 * with the name the record gives): 1 and its place now in out when, with "."
 * and ".." resolved by name (no link followed), it lies in a folder of
 * PATHS_FROZEN_RECORDED; else 0 and path unchanged in out. */
int paths_recorded(const char *path, char *out, size_t n);
/* Append a copy of s (unsorted). */
cs_status paths_list_add(paths_list *l, const char *s);

#endif
