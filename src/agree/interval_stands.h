/* interval_stands: the stand units of the pooled teacher tables (design.md
 * §6.1): the E1 sweep and the E2 tables pool the stands k = 0..7 of each
 * cell; their per-stand rows lie beside them (<table>_trees, _stands,
 * _sectors.tsv). The unit is the stand index k (its stands at every spacing
 * drawn together). The extractors (interval_stands.c: sweep, perturbation;
 * interval_irred.c: refinement, reduction) and the readers they share. */
#ifndef INTERVAL_STANDS_H
#define INTERVAL_STANDS_H
#include "interval.h"
#include "tsv.h"

#define IV_MAXD 16 /* spacings of an E2 table */

cs_status iv_sweep_stands(const claim_row *row, const claim_result *res, const interval_spec *spec, iv_data *d);
cs_status iv_perturb_stands(const claim_row *row, const claim_result *res, const interval_spec *spec, iv_data *d);
cs_status iv_refine_stands(const claim_row *row, const claim_result *res, const interval_spec *spec, iv_data *d);
cs_status iv_reduction_stands(const claim_row *row, const claim_result *res, const interval_spec *spec, iv_data *d);
/* interval_blind.c: the direction-blind level over the evaluation stands of baselines.tsv. */
cs_status iv_blind_stands(const claim_row *row, const claim_result *res, const interval_spec *spec, iv_data *d);

/* The start of every extractor: path = the per-stand rows <base><suffix>.tsv
 * beside row's pooled table, and *ctx a zeroed context of size bytes handed
 * to the bootstrap as the data of its statistic fn (freed by cleanup). */
cs_status iv_stands_begin(const claim_row *row, const char *suffix, char *path, size_t np, size_t size, boot_stat fn,
                          void (*cleanup)(void *), iv_data *d, void **ctx);
/* <dir>/<base><suffix>.tsv beside the pooled table <dir>/<base>.tsv. */
void iv_rows_path(const char *source, const char *suffix, char *out, size_t n);
/* Hand the bootstrap the units x[k] = k, k = 0..ns-1, read from rows. */
cs_status iv_stand_units(iv_data *d, size_t ns, const char *rows, const char *what);
/* Column col of row r of the pooled table must be want, bit for bit; else
 * CS_EINVARIANT naming the claim, the cell and the rows. */
cs_status iv_check_cell(const claim_row *row, const tsv *pooled, size_t r, const char *col, double want,
                        const char *rows);
/* Index of key v among keys[0..n-1] (exact text), or -1. */
long iv_key_index(char (*keys)[48], size_t n, const char *v);
/* The stand index of row r (0 <= k < maxk). */
cs_status iv_row_stand(const tsv *t, size_t r, size_t maxk, size_t *k);
/* The number of stands of t: its largest stand index + 1. */
cs_status iv_count_stands(const tsv *t, size_t *ns);

#endif
