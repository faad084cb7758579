/* claim_design: computing functions for the design constants of the paper.
 * Each value is read from the preregistered gate file (or the header that
 * fixes it), never typed here, so a changed gate shows up in the paper. */
#include "claims.h"
#include "paths.h"
#include "design.h"
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "crown.h"
#include "prov.h"

/* One load of gates/<file>: value idx of key (v may be NULL), its number of
 * values (count may be NULL), and res->where naming the file line. */
static cs_status gate_get(claim_result *res, const char *file, const char *key, size_t idx, double *v, size_t *count)
{
    gate *g;
    cs_status st = claim_gate_load(file, &g);
    if (st) return st;
    if (count) *count = gate_count(g, key);
    double tmp;
    st = gate_value(g, key, idx, v ? v : &tmp);
    if (!st) snprintf(res->where, sizeof res->where, PATHS_GATES_DIR "/%s:%d (%s)", file, gate_line(g, key), key);
    gate_free(g);
    return st;
}

/* A design claim that is one gate value times `scale`. */
static cs_status gate_claim(const claim_row *row, claim_result *res, const char *file, const char *key, double scale)
{
    double v;
    cs_status st = gate_get(res, file, key, 0, &v, NULL);
    if (!st) claim_set_value(row, res, scale * v);
    return st;
}

cs_status claim_design_mech_rows(const claim_row *row, claim_result *res)
{
    size_t nb, ns;
    cs_status st = gate_get(res, "mechanism.gate", "spacings_m", 0, NULL, &ns);
    if (!st) st = gate_get(res, "mechanism.gate", "dieback_sweep", 0, NULL, &nb);
    if (st) return st;
    claim_set_value(row, res, (double)(nb * ns));
    return CS_OK;
}

cs_status claim_design_irred_spacings(const claim_row *row, claim_result *res)
{
    size_t n;
    cs_status st = gate_get(res, "irreducibility.gate", "spacings_m", 0, NULL, &n);
    if (st) return st;
    claim_set_value(row, res, (double)n);
    return CS_OK;
}

cs_status claim_design_irred_refine_max(const claim_row *row, claim_result *res)
{
    double lo, hi;
    size_t n;
    cs_status st = gate_get(res, "irreducibility.gate", "refine_levels", 0, &lo, &n);
    if (!st) st = gate_get(res, "irreducibility.gate", "refine_levels", n - 1, &hi, NULL);
    if (st) return st;
    claim_set_value(row, res, hi / lo);
    return CS_OK;
}

cs_status claim_design_dieback_train(const claim_row *row, claim_result *res)
{
    double v;
    cs_status st = gate_get(res, "mechanism.gate", "dieback_train", 0, &v, NULL);
    if (st) return st;
    claim_set_value(row, res, v);
    /* Its gate (the row passes at every spacing) is judged from the frozen
     * sweep; until the mechanism experiment is frozen it stays pending. */
    FILE *f = fopen("frozen/mechanism/sweep.tsv", "r");
    if (!f) {
        res->gate = VERDICT_PENDING;
        snprintf(res->gate_detail, sizeof res->gate_detail, "needs frozen/mechanism/sweep.tsv");
        return CS_OK;
    }
    fclose(f);
    return claim_mech_train_row(row, res, v);
}

cs_status claim_design_main_seeds(const claim_row *row, claim_result *res)
{
    return gate_claim(row, res, "main.gate", "seeds", 1.0);
}

cs_status claim_design_main_epochs(const claim_row *row, claim_result *res)
{
    return gate_claim(row, res, "main.gate", "epochs", 1.0);
}

/* A list of spacings of gates/main.gate as text ("3.5, 4.5, ..."). */
static cs_status spacings_text(claim_result *res, const char *key)
{
    gate *g;
    cs_status st = claim_gate_load("main.gate", &g);
    if (st) return st;
    const double *v;
    size_t n;
    st = gate_values(g, key, &v, &n);
    if (!st) {
        size_t off = 0;
        res->text[0] = '\0';
        for (size_t i = 0; i < n; i++)
            off += (size_t)snprintf(res->text + off, sizeof res->text - off, "%s%.1f", i ? ", " : "", v[i]);
        res->value = v[0];
        snprintf(res->where, sizeof res->where, PATHS_GATE("main") ":%d (%s)", gate_line(g, key), key);
    }
    gate_free(g);
    return st;
}

cs_status claim_design_train_spacings(const claim_row *row, claim_result *res)
{
    (void)row;
    return spacings_text(res, "train_spacings_m");
}

/* The unseen spacings, a constant of the text given as its own macro. */
cs_status claim_design_unseen_spacings(const claim_row *row, claim_result *res)
{
    (void)row;
    return spacings_text(res, "unseen_spacings_m");
}

cs_status claim_design_calib_target(const claim_row *row, claim_result *res)
{
    return gate_claim(row, res, "field.gate", "calibration_target_m", 1.0);
}

cs_status claim_design_calib_seeds(const claim_row *row, claim_result *res)
{
    return gate_claim(row, res, "field.gate", "calibration_seeds", 1.0);
}

cs_status claim_design_jitter_canonical_pct(const claim_row *row, claim_result *res)
{
    return gate_claim(row, res, "anisotropy.gate", "canonical_jitter", 100.0);
}

cs_status claim_design_nsec(const claim_row *row, claim_result *res)
{
    snprintf(res->where, sizeof res->where, "src/forest/crown.h (CROWN_NSEC)");
    claim_set_value(row, res, (double)CROWN_NSEC);
    return CS_OK;
}

cs_status claim_design_patch_trees(const claim_row *row, claim_result *res)
{
    return gate_claim(row, res, "main.gate", "patch_trees", 1.0);
}

cs_status claim_design_gencomp_spacing(const claim_row *row, claim_result *res)
{
    snprintf(res->where, sizeof res->where, "src/base/design.h (DESIGN_GENCOMP_SPACING_M)");
    claim_set_value(row, res, DESIGN_GENCOMP_SPACING_M);
    return CS_OK;
}

/* The spacing of the row's point-cloud stand. */
cs_status claim_design_pc_spacing(const claim_row *row, claim_result *res)
{
    double v;
    cs_status st = claim_param_stand_spacing(row, &v);
    if (st) return st;
    snprintf(res->where, sizeof res->where, "src/base/design.h");
    claim_set_value(row, res, v);
    return CS_OK;
}

/* The extrapolation spacings (E4), each a constant of the text given as its own macro. */
cs_status claim_design_extrap_spacing_low(const claim_row *row, claim_result *res)
{
    double v;
    cs_status st = gate_get(res, "extrapolation.gate", "spacings_m", 0, &v, NULL);
    if (!st) claim_set_value(row, res, v);
    return st;
}

cs_status claim_design_extrap_spacing_high(const claim_row *row, claim_result *res)
{
    double v;
    cs_status st = gate_get(res, "extrapolation.gate", "spacings_m", 1, &v, NULL);
    if (!st) claim_set_value(row, res, v);
    return st;
}

/* The sha256 of the preregistered gates (gates/ as a whole, the pins'
 * gates_sha256): what the write-up's first page publishes, for a reviewer to
 * bring to make verify PREREG= from a copy they trust. */
cs_status claim_design_prereg_gates(const claim_row *row, claim_result *res)
{
    (void)row;
    char hex[65];
    cs_status st = prov_gates_sha256(PATHS_GATES_DIR, hex);
    if (st) return st;
    snprintf(res->text, sizeof res->text, "%s", hex);
    res->value = 0;
    snprintf(res->where, sizeof res->where,
             PATHS_GATES_DIR "/*.gate (sha256 of the set, as audit/pins.tsv gates_sha256)");
    return CS_OK;
}
