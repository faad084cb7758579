/* claim_params: the registry's params column (see claims.h): a fixed set of
 * keys parsed into the typed fields of a row, so that one computing function
 * serving several claims is told what to compute by the row, never by the
 * spelling of its macro. */
#include "claims.h"
#include "design.h"
#include "mainruns.h"
#include "paths.h"
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const ARM_NAMES[] = {"",          "joint",   "indep",        "teacher",     "coupled",
                                        "uncoupled", "both_on", "coupling_off", "abrasion_off"};
static const char *const PROBE_NAMES[] = {"", "shuffled", "rotated"};
static const char *const BOUND_NAMES[] = {"", "lo", "hi"};
static const char *const STAT_NAMES[] = {"", "median", "range", "ratio"};
static const char *const STAND_NAMES[] = {"", "shown", "other_a", "other_b"};
#define NNAMES(a) (sizeof a / sizeof *a)
/* an enum field is written as the int of its name's index */
_Static_assert(sizeof(param_arm) == sizeof(int) && sizeof(param_probe) == sizeof(int) &&
                   sizeof(param_bound) == sizeof(int) && sizeof(param_stat) == sizeof(int) &&
                   sizeof(param_stand) == sizeof(int),
               "param enums are ints");

const char *param_arm_name(param_arm a) { return (size_t)a < NNAMES(ARM_NAMES) ? ARM_NAMES[a] : ""; }
const char *param_probe_name(param_probe p) { return (size_t)p < NNAMES(PROBE_NAMES) ? PROBE_NAMES[p] : ""; }

/* The keys in the order of the PARAM_* bits, each with the field it fills. */
typedef enum { K_ENUM, K_NAME, K_MACRO, K_NUMBER } key_type;
#define F(f) offsetof(claim_params, f), sizeof ((claim_params *)0)->f
static const struct { const char *key; key_type type; const char *const *names; size_t nnames, off, size; } KEYS[] = {
    {"arm", K_ENUM, ARM_NAMES, NNAMES(ARM_NAMES), F(arm)},
    {"probe", K_ENUM, PROBE_NAMES, NNAMES(PROBE_NAMES), F(probe)},
    {"bound", K_ENUM, BOUND_NAMES, NNAMES(BOUND_NAMES), F(bound)},
    {"stat", K_ENUM, STAT_NAMES, NNAMES(STAT_NAMES), F(stat)},
    {"column", K_NAME, NULL, 0, F(column)},
    {"quantity", K_NAME, NULL, 0, F(quantity)},
    {"stand", K_ENUM, STAND_NAMES, NNAMES(STAND_NAMES), F(stand)},
    {"of", K_MACRO, NULL, 0, F(of)},
    {"choice", K_NAME, NULL, 0, F(choice)},
    {"x", K_NUMBER, NULL, 0, F(x)},
    {"scale", K_NUMBER, NULL, 0, F(scale)},
    {"spacing", K_NUMBER, NULL, 0, F(spacing)},
    {"seeds", K_NUMBER, NULL, 0, F(seeds)},
};
#undef F
#define NKEYS (sizeof KEYS / sizeof *KEYS)
_Static_assert(NKEYS == 13 && PARAM_SEEDS == 1u << 12, "one PARAM_* bit per key, in KEYS order");

/* The order the registry prints the keys in (indexes of KEYS). */
static const unsigned char PRINT_ORDER[] = {0, 1, 3, 4, 6, 5, 7, 8, 9, 2, 10, 11, 12};
_Static_assert(sizeof PRINT_ORDER == NKEYS, "every key printed once");

void claim_params_format(const claim_params *p, char *buf, size_t n)
{
    snprintf(buf, n, "-");
    size_t o = 0;
    for (size_t i = 0; i < NKEYS && n; i++) {
        const size_t k = PRINT_ORDER[i];
        if (!(p->set & (1u << k))) continue;
        const char *field = (const char *)p + KEYS[k].off;
        char v[80];
        if (KEYS[k].type == K_ENUM) {
            int e;
            memcpy(&e, field, sizeof e);
            snprintf(v, sizeof v, "%s", e > 0 && (size_t)e < KEYS[k].nnames ? KEYS[k].names[e] : "?");
        } else if (KEYS[k].type == K_NUMBER) {
            double d;
            memcpy(&d, field, sizeof d);
            snprintf(v, sizeof v, "%g", d);
        } else
            snprintf(v, sizeof v, "%s", field);
        int w = snprintf(buf + o, n - o, "%s%s=%s", o ? ";" : "", KEYS[k].key, v);
        if (w < 0 || (size_t)w >= n - o) break;
        o += (size_t)w;
    }
}

static const char *key_names(unsigned keys, char *buf, size_t n)
{
    buf[0] = '\0';
    for (size_t k = 0; k < NKEYS; k++)
        if (keys & (1u << k)) snprintf(buf + strlen(buf), n - strlen(buf), "%s%s", buf[0] ? ", " : "", KEYS[k].key);
    return buf;
}

static int word_ok(const char *v, int macro)
{
    if (!*v) return 0;
    for (const char *c = v; *c; c++) {
        int letter = (*c >= 'A' && *c <= 'Z') || (*c >= 'a' && *c <= 'z');
        if (!letter && (macro || !((*c >= '0' && *c <= '9') || *c == '_'))) return 0;
    }
    return 1;
}

/* One "key=value" pair into p. */
static cs_status parse_pair(char *pair, const char *path, int line, claim_params *p)
{
    char *eq = strchr(pair, '=');
    if (!eq) return cs_err(CS_EINPUT, "%s:%d: field 'params': '%s' is not key=value", path, line, pair);
    *eq = '\0';
    const char *key = pair, *v = eq + 1;
    size_t k = 0;
    while (k < NKEYS && strcmp(KEYS[k].key, key)) k++;
    char list[160];
    if (k == NKEYS)
        return cs_err(CS_EINPUT, "%s:%d: field 'params': unknown key '%s' (%s)", path, line, key,
                      key_names((1u << NKEYS) - 1, list, sizeof list));
    if (p->set & (1u << k)) return cs_err(CS_EINPUT, "%s:%d: field 'params': key '%s' given twice", path, line, key);
    p->set |= 1u << k;
    char *field = (char *)p + KEYS[k].off;
    if (KEYS[k].type == K_ENUM) {
        for (size_t i = 1; i < KEYS[k].nnames; i++)
            if (!strcmp(KEYS[k].names[i], v)) {
                /* every param_* enum counts its names from 0, as the tables here */
                int e = (int)i;
                memcpy(field, &e, sizeof e);
                return CS_OK;
            }
        list[0] = '\0';
        for (size_t i = 1; i < KEYS[k].nnames; i++)
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i > 1 ? ", " : "", KEYS[k].names[i]);
        return cs_err(CS_EINPUT, "%s:%d: field 'params': %s='%s' is not one of %s", path, line, key, v, list);
    }
    if (KEYS[k].type == K_NUMBER) {
        char *end;
        double d = strtod(v, &end);
        memcpy(field, &d, sizeof d);
        if (end == v || *end || !isfinite(d))
            return cs_err(CS_EINPUT, "%s:%d: field 'params': %s='%s' is not one finite number", path, line, key, v);
        return CS_OK;
    }
    if (!word_ok(v, KEYS[k].type == K_MACRO) || strlen(v) >= KEYS[k].size)
        return cs_err(CS_EINPUT, "%s:%d: field 'params': %s='%s' is not %s", path, line, key, v,
                      KEYS[k].type == K_MACRO ? "a macro name (letters only)" : "a name (letters, digits, '_'; short)");
    strcpy(field, v);
    return CS_OK;
}

cs_status claim_params_parse(const char *text, const char *path, int line, claim_params *p)
{
    memset(p, 0, sizeof *p);
    if (!strcmp(text, "-")) return CS_OK;
    char buf[512];
    if (strlen(text) >= sizeof buf) return cs_err(CS_EINPUT, "%s:%d: field 'params': too long", path, line);
    strcpy(buf, text);
    cs_status st = CS_OK;
    char *save = NULL;
    /* an empty pair (";;", a leading or trailing ';') is malformed too */
    if (buf[0] == ';' || buf[strlen(buf) - 1] == ';' || strstr(buf, ";;"))
        return cs_err(CS_EINPUT, "%s:%d: field 'params': '%s' has an empty pair", path, line, text);
    for (char *pair = strtok_r(buf, ";", &save); pair && !st; pair = strtok_r(NULL, ";", &save))
        st = parse_pair(pair, path, line, p);
    return st;
}

cs_status claim_param_need(const claim_row *row, unsigned keys)
{
    unsigned miss = keys & ~row->param.set;
    if (!miss) return CS_OK;
    char list[160];
    return cs_err(CS_EINPUT, "%s:%d: field 'params': %s (%s) needs %s", PATHS_CLAIMS, row->line, row->macro,
                  row->function, key_names(miss, list, sizeof list));
}

cs_status claim_param_bad(const claim_row *row, const char *key, const char *allowed)
{
    return cs_err(CS_EINPUT, "%s:%d: field 'params': %s (%s) computes %s=%s only", PATHS_CLAIMS, row->line, row->macro,
                  row->function, key, allowed);
}

cs_status claim_param_seed_column(const claim_row *row, int *k)
{
    cs_status st = claim_param_need(row, PARAM_ARM);
    if (st) return st;
    if (row->param.arm != ARM_JOINT && row->param.arm != ARM_INDEP)
        return claim_param_bad(row, "arm", "joint or indep");
    *k = 2 * (int)row->param.probe + (row->param.arm == ARM_INDEP);
    return CS_OK;
}

cs_status claim_param_stand_spacing(const claim_row *row, double *d)
{
    cs_status st = claim_param_need(row, PARAM_STAND);
    if (st) return st;
    const param_stand s = row->param.stand;
    *d = s == STAND_OTHER_A   ? DESIGN_PC_OTHER_A_SPACING_M
         : s == STAND_OTHER_B ? DESIGN_PC_OTHER_B_SPACING_M
                              : DESIGN_PC_SPACING_M;
    return CS_OK;
}

cs_status claim_param_seeds(const claim_row *row, int *want)
{
    if (!(row->param.set & PARAM_SEEDS)) return mainruns_gate_seeds(want);
    const double s = row->param.seeds;
    if (strcmp(row->gate, "-"))
        return cs_err(CS_EINPUT, "%s:%d: field 'params': %s is gated: its seeds are the gate's, not seeds=%g",
                      PATHS_CLAIMS, row->line, row->macro, s);
    if (!(s >= 1 && s <= MAINRUNS_MAXSEED && s == (int)s))
        return claim_param_bad(row, "seeds", "a whole number of seeds, 1..64");
    *want = (int)s;
    return CS_OK;
}
