/* claim_design: computing functions for the design constants of the paper.
 * Each value is read from the preregistered gate file (or the header that
 * fixes it), never typed here, so a changed gate shows up in the paper. */
#include "claims.h"
#include "design.h"
#include <math.h>
#include <stdio.h>
#include <string.h>
cs_status claim_mech_train_row(const claim_row *row, claim_result *res, double beta);
#if __has_include("crown.h")
#include "crown.h"
#endif

static cs_status gate_get(const char *file, const char *key, size_t idx, double *v, size_t *count)
{
    gate *g;
    cs_status st = claim_gate_load(file, &g);
    if (st) return st;
    if (count) *count = gate_count(g, key);
    st = gate_value(g, key, idx, v);
    gate_free(g);
    return st;
}

static void where_gate(claim_result *res, const char *file, const char *key)
{
    gate *g;
    if (claim_gate_load(file, &g) == CS_OK) {
        snprintf(res->where, sizeof res->where, "gates/%s:%d (%s)", file, gate_line(g, key), key);
        gate_free(g);
    }
}

cs_status claim_design_mech_rows(const claim_row *row, claim_result *res)
{
    double v;
    size_t nb, ns;
    cs_status st = gate_get("mechanism.gate", "dieback_sweep", 0, &v, &nb);
    if (!st) st = gate_get("mechanism.gate", "spacings_m", 0, &v, &ns);
    if (st) return st;
    where_gate(res, "mechanism.gate", "dieback_sweep");
    claim_set_value(row, res, (double)(nb * ns));
    return CS_OK;
}

cs_status claim_design_irred_spacings(const claim_row *row, claim_result *res)
{
    double v;
    size_t n;
    cs_status st = gate_get("irreducibility.gate", "spacings_m", 0, &v, &n);
    if (st) return st;
    where_gate(res, "irreducibility.gate", "spacings_m");
    claim_set_value(row, res, (double)n);
    return CS_OK;
}

cs_status claim_design_irred_refine_max(const claim_row *row, claim_result *res)
{
    double lo, hi;
    size_t n;
    cs_status st = gate_get("irreducibility.gate", "refine_levels", 0, &lo, &n);
    if (!st) st = gate_get("irreducibility.gate", "refine_levels", n - 1, &hi, NULL);
    if (st) return st;
    where_gate(res, "irreducibility.gate", "refine_levels");
    claim_set_value(row, res, hi / lo);
    return CS_OK;
}

cs_status claim_design_dieback_train(const claim_row *row, claim_result *res)
{
    double v;
    cs_status st = gate_get("mechanism.gate", "dieback_train", 0, &v, NULL);
    if (st) return st;
    where_gate(res, "mechanism.gate", "dieback_train");
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
    double v;
    cs_status st = gate_get("main.gate", "seeds", 0, &v, NULL);
    if (st) return st;
    where_gate(res, "main.gate", "seeds");
    claim_set_value(row, res, v);
    return CS_OK;
}

cs_status claim_design_main_epochs(const claim_row *row, claim_result *res)
{
    double v;
    cs_status st = gate_get("main.gate", "epochs", 0, &v, NULL);
    if (st) return st;
    where_gate(res, "main.gate", "epochs");
    claim_set_value(row, res, v);
    return CS_OK;
}

cs_status claim_design_train_spacings(const claim_row *row, claim_result *res)
{
    gate *g;
    cs_status st = claim_gate_load("main.gate", &g);
    if (st) return st;
    const double *v;
    size_t n;
    st = gate_values(g, "train_spacings_m", &v, &n);
    if (!st) {
        size_t off = 0;
        res->text[0] = '\0';
        for (size_t i = 0; i < n; i++)
            off += (size_t)snprintf(res->text + off, sizeof res->text - off, "%s%.1f", i ? ", " : "", v[i]);
        res->value = v[0];
        snprintf(res->where, sizeof res->where, "gates/main.gate:%d (train_spacings_m)", gate_line(g, "train_spacings_m"));
    }
    gate_free(g);
    return st;
}

cs_status claim_design_calib_target(const claim_row *row, claim_result *res)
{
    double v;
    cs_status st = gate_get("field.gate", "calibration_target_m", 0, &v, NULL);
    if (st) return st;
    where_gate(res, "field.gate", "calibration_target_m");
    claim_set_value(row, res, v);
    return CS_OK;
}

cs_status claim_design_calib_seeds(const claim_row *row, claim_result *res)
{
    double v;
    cs_status st = gate_get("field.gate", "calibration_seeds", 0, &v, NULL);
    if (st) return st;
    where_gate(res, "field.gate", "calibration_seeds");
    claim_set_value(row, res, v);
    return CS_OK;
}

cs_status claim_design_jitter_canonical_pct(const claim_row *row, claim_result *res)
{
    double v;
    cs_status st = gate_get("anisotropy.gate", "canonical_jitter", 0, &v, NULL);
    if (st) return st;
    where_gate(res, "anisotropy.gate", "canonical_jitter");
    claim_set_value(row, res, 100.0 * v);
    return CS_OK;
}

cs_status claim_design_nsec(const claim_row *row, claim_result *res)
{
#ifdef CROWN_NSEC
    snprintf(res->where, sizeof res->where, "src/crown.h (CROWN_NSEC)");
    claim_set_value(row, res, (double)CROWN_NSEC);
#else
    claim_pending(res, "src/crown.h (CROWN_NSEC) not in this build yet");
#endif
    return CS_OK;
}

cs_status claim_design_patch_trees(const claim_row *row, claim_result *res)
{
    double v;
    cs_status st = gate_get("main.gate", "patch_trees", 0, &v, NULL);
    if (st) return st;
    where_gate(res, "main.gate", "patch_trees");
    claim_set_value(row, res, v);
    return CS_OK;
}

cs_status claim_design_gencomp_spacing(const claim_row *row, claim_result *res)
{
    snprintf(res->where, sizeof res->where, "src/design.h (DESIGN_GENCOMP_SPACING_M)");
    claim_set_value(row, res, DESIGN_GENCOMP_SPACING_M);
    return CS_OK;
}

cs_status claim_design_pc_spacing(const claim_row *row, claim_result *res)
{
    double v;
    if (!strcmp(row->macro, "PcSpacing")) v = DESIGN_PC_SPACING_M;
    else if (!strcmp(row->macro, "PcOtherASpacing")) v = DESIGN_PC_OTHER_A_SPACING_M;
    else if (!strcmp(row->macro, "PcOtherBSpacing")) v = DESIGN_PC_OTHER_B_SPACING_M;
    else return cs_err(CS_EINPUT, "claim_design_pc_spacing: no spacing for macro %s", row->macro);
    snprintf(res->where, sizeof res->where, "src/design.h");
    claim_set_value(row, res, v);
    return CS_OK;
}
