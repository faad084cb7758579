/* gate: preregistered thresholds (design.md §7). A gate file holds lines
 * "key value [value…]" with "#" comments; every value must be a number.
 * The files in gates/ are byte-for-byte copies of ../shared/gates and are
 * never edited; their joint SHA-256 is pinned in audit/pins.tsv. */
#ifndef GATE_H
#define GATE_H
#include "cs.h"
#include <stddef.h>

typedef struct gate gate;

/* Parse; errors name file, line and field ("mechanism.gate:9: field 'cover_min': value 1 not a number: 'x'"). */
cs_status gate_load(const char *path, gate **out);
void gate_free(gate *g);
/* Number of values for key (0 if absent). */
size_t gate_count(const gate *g, const char *key);
/* Value idx of key; error naming file and key when absent or out of range. */
cs_status gate_value(const gate *g, const char *key, size_t idx, double *out);
/* All values of key (pointer into g), count in *n; error when absent. */
cs_status gate_values(const gate *g, const char *key, const double **vals, size_t *n);
/* Line number of key in the file (0 if absent), for traces. */
int gate_line(const gate *g, const char *key);
/* One-off lookups (load `path`, read, free): value idx of key, or every value
 * of key copied into v[cap] with its count in *n (more than cap is an error
 * naming file and key). */
cs_status gate_read_value(const char *path, const char *key, size_t idx, double *out);
cs_status gate_read_values(const char *path, const char *key, double *v, size_t cap, size_t *n);

/* Verdict of one preregistered check. */
typedef enum { VERDICT_PASS = 0, VERDICT_FAIL = 1, VERDICT_PENDING = 2 } verdict;
const char *verdict_name(verdict v);

typedef enum { GATE_GE, GATE_GT, GATE_LE, GATE_LT, GATE_IN, GATE_OUT, GATE_TRUE } gate_op;
/* Judge observed against threshold(s): GE/GT/LE/LT use lo; IN/OUT use [lo, hi]
 * (closed); TRUE passes when observed != 0. Non-finite observed fails. */
verdict gate_judge(gate_op op, double observed, double lo, double hi);
const char *gate_op_text(gate_op op);

#endif
