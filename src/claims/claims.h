/* claims: the claim registry and its evaluation (design.md §9). Every macro
 * of the paper has one row of a claim table in C (claim_spec below; the
 * tables in src/claims/claim_*_table.c, their order the CLAIMS rows of
 * src/base/manifest.h) naming its kind, frozen source, computing function,
 * gate and paper section, with typed params; audit/claims.tsv is their print
 * (claims_registry_text), checked by the audit. A computing function
 * recomputes the value from frozen/ (or a gate file, for design constants)
 * with the same library code the pipeline used, formats it, and judges the
 * row's gate. paper/numbers.tex is generated from these results only. */
#ifndef CLAIMS_H
#define CLAIMS_H
#include "cs.h"
#include "gate.h"
#include <stddef.h>

/* The typed parameters of a row (printed as the registry's last column,
 * params: "key=value;..." or "-"): which arm, probe, bound, statistic, column or
 * quantity a computing function that serves several claims computes, and for
 * a row standing for another claim under a variant (`of`), which. The macro
 * is a name only: nothing is chosen by its spelling. `set` holds a PARAM_*
 * bit per key the row gives; a function missing a key it needs fails naming
 * the row's line (claim_param_need). */
typedef enum {
    ARM_NONE,
    ARM_JOINT,
    ARM_INDEP,
    ARM_TEACHER,
    ARM_COUPLED,
    ARM_UNCOUPLED,
    ARM_BOTH_ON,
    ARM_COUPLING_OFF,
    ARM_ABRASION_OFF
} param_arm;
typedef enum { PROBE_NONE, PROBE_SHUFFLED, PROBE_ROTATED } param_probe;
typedef enum { BOUND_NONE, BOUND_LO, BOUND_HI } param_bound;
typedef enum { STAT_NONE, STAT_MEDIAN, STAT_RANGE, STAT_RATIO } param_stat;
typedef enum { STAND_NONE, STAND_SHOWN, STAND_OTHER_A, STAND_OTHER_B } param_stand;
enum {
    PARAM_ARM = 1u << 0,   /* arm=joint|indep|teacher|coupled|uncoupled|both_on|coupling_off|abrasion_off: the arm (or
                              source) whose rows are read */
    PARAM_PROBE = 1u << 1, /* probe=shuffled|rotated: the probe applied to the arm */
    PARAM_BOUND = 1u << 2, /* bound=lo|hi: the lower or upper end (of a span, or of two spacings) */
    PARAM_STAT =
        1u << 3, /* stat=median|range|ratio: the median, its 5-95 % range, or the probe's median over the arm's own */
    PARAM_COLUMN = 1u << 4,   /* column=NAME: the table column read */
    PARAM_QUANTITY = 1u << 5, /* quantity=NAME: which of a function's named quantities */
    PARAM_STAND = 1u << 6,    /* stand=shown|other_a|other_b: the point-cloud stand (its spacing is the design's) */
    PARAM_OF = 1u << 7,       /* of=MACRO: the claim this row is a variant of (another row of the registry) */
    PARAM_CHOICE = 1u << 8,   /* choice=NAME: the unstated choice or reading whose units are read */
    PARAM_X = 1u << 9,        /* x=NUMBER: that choice's value */
    PARAM_SCALE = 1u << 10,   /* scale=NUMBER: the value is shown times this (100 for a percent) */
    PARAM_SPACING = 1u << 11, /* spacing=NUMBER: the stand spacing read, metres */
    PARAM_SEEDS =
        1u << 12, /* seeds=N: the seeds read of a unit set (1..N); absent: the preregistered seeds of gates/main.gate */
};
typedef struct {
    unsigned set;
    param_arm arm;
    param_probe probe;
    param_bound bound;
    param_stat stat;
    param_stand stand;
    char column[32], quantity[32], of[64], choice[32];
    double x, scale, spacing, seeds;
} claim_params;

typedef struct {
    char macro[64], kind[16], source[256], function[64], gate[128], test[160], section[16], format[16], reference[64];
    claim_params param;
    int line; /* line in audit/claims.tsv */
    const char *table; /* the claim table holding the row (claims_registry); NULL when read from a file */
    /* The registry's own gate column. `gate` is what audit/gate_map.tsv (pinned
     * with the gates) says when the registry is PATHS_CLAIMS; the audit fails
     * when the two differ. gate_map_line: line of the map row, 0 if none. */
    char gate_reg[128];
    int gate_map_line;
    int gate_map_ext; /* 1: the row's gate comes from PATHS_GATE_MAP_EXT */
} claim_row;

typedef struct {
    verdict status;      /* PASS: computed; PENDING: cannot be computed yet (why); FAIL: error (why) */
    double value;        /* in display units (e.g. percent for *Rel) */
    char text[128];      /* what numbers.tex shows */
    char why[512];       /* reason for PENDING/FAIL */
    char where[512];     /* frozen file (and line) the value came from */
    verdict gate;        /* verdict of the row's gate; PENDING when no gate or not judgeable */
    char gate_detail[256];
    double gate_observed; /* the quantity the gate judged, when has_observed */
    int has_observed;     /* 1 once a gate with a threshold judged gate_observed */
    cs_status err;       /* status FAIL from the computing function's error: its kind (CS_OK otherwise) */
} claim_result;

typedef cs_status (*claim_fn)(const claim_row *row, claim_result *res);

/* One row of a claim table (the C home of a claim): what audit/claims.tsv
 * prints of it. gate is the registry's gate column (the pinned maps decide,
 * claims_apply_gate_maps); the test is derived (tests/test_claims.c:claim_MACRO);
 * param.set holds a PARAM_* bit per field given, the others stay zero. */
typedef struct {
    const char *macro, *kind, *source, *function, *gate, *section, *format, *reference;
    claim_params param;
} claim_spec;
/* A table's row count beside it: CLAIM_TABLE_SIZE(claim_table_x); after the array. */
#define CLAIM_TABLE_SIZE(t) const size_t t##_n = sizeof t / sizeof *t

typedef struct { claim_row *rows; size_t n; } claims;

/* Load and validate the registry (unique macros, known kinds, gate refs
 * "file.gate:key", params as claim_params_parse, an `of` naming another row).
 * For PATHS_CLAIMS the gate of every row comes from PATHS_GATE_MAP and, for
 * the rows of kind extension, from PATHS_GATE_MAP_EXT (see claims_apply_gate_map). */
cs_status claims_load(const char *path, claims *out);
/* Validate rows[0..n) (each row's fields as a file's, unique macros, an `of`
 * naming another row; errors name path and the row's line) and hand them to
 * *out, which owns rows after (freed on error); maps: the gates from the
 * pinned maps (claims_apply_gate_maps). */
cs_status claims_adopt(claim_row *rows, size_t n, const char *path, int maps, claims *out);
/* The registry: every claim table, in the order of the CLAIMS rows of
 * src/base/manifest.h, validated as claims_load validates a file (each row's
 * line is the one it prints on in PATHS_CLAIMS), gates from the pinned maps. */
cs_status claims_registry(claims *out);
/* The registry's print (PATHS_CLAIMS): its header comments, the header line
 * and one row per claim; *text is malloc'd, NUL-terminated. */
cs_status claims_registry_text(char **text, size_t *len);
/* Where a row of the tables is written: the file of src/claims/ whose line
 * opens with the row ({"MACRO", ...) and that line; CS_EINPUT when none. */
cs_status claims_table_where(const claim_row *row, char *path, size_t pathsz, int *line);
/* Write the print to path (atomic). */
cs_status claims_registry_write(const char *path);
/* CS_EINVARIANT naming path's first line that differs from the print (or the
 * line where one of them ends) unless path holds exactly the print. */
cs_status claims_registry_check(const char *path);
/* Parse a params cell into *p (zeroed first): CS_EINPUT naming path, line and
 * field 'params' for an unknown or repeated key, a pair without '=', or a
 * value out of its key's set (numbers: one finite number; names: letters,
 * digits and '_'; of: a macro name). */
cs_status claim_params_parse(const char *text, const char *path, int line, claim_params *p);
/* The params as the registry spells them ("-" when none): its keys in the
 * registry's print order (arm probe stat column stand quantity of choice x
 * bound scale spacing seeds), numbers as %g. */
void claim_params_format(const claim_params *p, char *buf, size_t n);
/* CS_EINPUT naming the row's registry line unless the row gives every key of
 * `keys` (PARAM_* bits): a function never falls back to a default. */
cs_status claim_param_need(const claim_row *row, unsigned keys);
/* CS_EINPUT naming the row's line: its key `key` holds a value the row's
 * function does not compute (`allowed` lists what it does). */
cs_status claim_param_bad(const claim_row *row, const char *key, const char *allowed);
/* The seeds a row reads of its unit set: its seeds=N, or the preregistered
 * count of gates/main.gate when it gives none. A gated row gives none (its
 * gate's count rules it): CS_EINPUT naming the row otherwise. */
cs_status claim_param_seeds(const claim_row *row, int *want);
/* The registry spelling of an arm and a probe ("joint", "rotated", ...): the
 * same words name the arms and probes in the frozen tables. */
const char *param_arm_name(param_arm a);
const char *param_probe_name(param_probe p);
/* The per-seed error column of an E3 row: 2 probe + arm (arm 0 joint, 1
 * indep; probe 0 generated when the row names none, 1 shuffled, 2 rotated),
 * as claim_main.c and the seed bootstrap index the run tables; CS_EINPUT
 * naming the row's line without an arm of the two. */
cs_status claim_param_seed_column(const claim_row *row, int *k);
/* The spacing of the row's point-cloud stand (stand=shown|other_a|other_b),
 * metres: the design's (src/base/design.h), never restated. */
cs_status claim_param_stand_spacing(const claim_row *row, double *d);
/* Set every row's gate from a claim-to-gate map (TSV: macro, gate): a row the
 * map does not name has no gate. CS_EINPUT naming file, line and field for a
 * malformed map, an unknown or duplicate macro, or a gate not "file.gate:key". */
cs_status claims_apply_gate_map(claims *c, const char *map_path);
/* The two pinned maps: main_map may name no row of kind extension, ext_map
 * only such rows (CS_EINPUT naming the map's file and line otherwise). */
cs_status claims_apply_gate_maps(claims *c, const char *main_map, const char *ext_map);
/* Kinds extension and variant: a claim of a generator reading added after the
 * first verdict, gated by the same thresholds beside the reference paper's
 * claims, never one of them: the pair extension (extension), or the paper's
 * method under one unstated training choice, at the gate's seeds (variant). */
int claims_kind_beside(const char *kind);
int claims_is_beside(const claim_row *row);
/* A frozen source that is a reading's unit still being run: under one of the
 * readings' folders of design.md §8 (the generator probes', the paper reading's, the pair
 * reading's 96-stands main and extrapolation folders, the descriptive readings'; the
 * list is in claims.c) or a unit set "<dir>/run_s*_*.tsv"; such a source
 * missing is pending, never a failure. */
int claims_awaited_source(const char *source);
void claims_free(claims *c);
const claim_row *claims_find(const claims *c, const char *macro);
/* The first line of a .c file of src/claims/ that starts with prefix (after
 * leading spaces when indented): its file and line number. 0 found, 1 none,
 * -1 out of memory. */
int claims_src_line(const char *prefix, int indented, char *path, size_t pathsz, int *line);
/* Where a computing function is defined: the file of src/claims/ holding its
 * definition ("cs_status FN(" at the start of a line) and the line; CS_EINPUT
 * when no file defines it. */
cs_status claims_function_file(const char *function, char *path, size_t pathsz, int *line);
/* The computing function named in a row, or NULL. */
claim_fn claims_lookup_fn(const char *name);
/* Names of every registered computing function (NULL-terminated). */
const char *const *claims_fn_names(void);
/* Evaluate one row (never fails: errors become FAIL with the message in why). */
void claims_eval(const claim_row *row, claim_result *res);

/* Mean over the rows of split (and, d_only > 0, that spacing) of column col
 * of a reading's baselines: source is the table itself (…/baselines.tsv) or a
 * reading's main/ or extrapolation/ table, whose main/baselines.tsv is read
 * (claim_main.c). `where` (may be NULL) names the table and column. */
cs_status claim_main_baseline_mean(const char *source, const char *col, const char *split, double d_only, double *out,
                                   char *where, size_t wn);

/* Helpers for computing functions. */
void claim_set_value(const claim_row *row, claim_result *res, double v);
void claim_pending(claim_result *res, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Judge the row's gate key with op against the gate file's value(s);
 * for IN/OUT the key must hold two values. */
void claim_judge(const claim_row *row, claim_result *res, gate_op op, double observed);
/* The gate of CalibDiebackTrain: the sweep row at `beta` passes at every
 * spacing (src/claims/claim_teacher.c, from frozen/mechanism/sweep.tsv). */
cs_status claim_mech_train_row(const claim_row *row, claim_result *res, double beta);
/* Load gates/<file> named in the row's gate column (or `file` if given). */
cs_status claim_gate_load(const char *file, gate **g);
/* Every W1 of ROOT/main/run_s<NN>_<arm>.tsv (NN = 1..maxseed, where present)
 * and of ROOT/main/baselines.tsv (if present) recomputed with est_w1 from the
 * samples files beside them and compared bit for bit (src/claims/claim_samples.c).
 * *nchecked counts the W1 checked; on a difference CS_EINVARIANT and msg names
 * the table, line, spacing and probe. */
cs_status claim_main_samples_check(const char *root, int maxseed, char *msg, size_t mn, int *nchecked);

/* numbers.tex */
#define CLAIMS_PENDING_FMT "\\pending{%s}"
/* The word every generated value prints as in the audit's render. */
#define CLAIMS_HIDDEN_WORD "HIDDEN"
/* Write the generated file (atomic) from evaluated results; hide: the audit's
 * render, with the same macros, each printing CLAIMS_HIDDEN_WORD. */
cs_status claims_write_numbers(const char *path, const claims *c, const claim_result *res, int hide);
/* LaTeX-escape a short table cell (% & _ # $). */
void claims_tex_escape(const char *in, char *out, size_t n);
/* Distance to the reference paper: 1 and *ref, *rel = (value - ref) / |ref|
 * for a computed measured claim whose reference is a non-zero number; else 0. */
int claims_rel_diff(const claim_row *row, const claim_result *res, double *ref, double *rel);
/* Parse a numbers.tex: value text of \newcommand{\NAME}{...}; NULL if absent. */
typedef struct { size_t n; char (*name)[80]; char (*value)[192]; int *line; } numbers_tex;
cs_status numbers_read(const char *path, numbers_tex *out);
void numbers_free(numbers_tex *nt);
const char *numbers_get(const numbers_tex *nt, const char *name, int *line);
/* The text numbers.tex must hold for a result (value, or \pending{macro}). */
void claims_expected_text(const claim_row *row, const claim_result *res, char *buf, size_t n);

#endif
