/* gate: parser and judge for the preregistered thresholds (design.md §7).
 * Strict on purpose: a gate file that does not parse completely is an input
 * error, never a silently partial threshold set. */
#include "gate.h"
#include "paths.h"
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct { char *key; double *v; size_t n; int line; } gate_entry;
struct gate { char *path; gate_entry *e; size_t n; };

void gate_free(gate *g)
{
    if (!g) return;
    for (size_t i = 0; i < g->n; i++) { free(g->e[i].key); free(g->e[i].v); }
    free(g->e); free(g->path); free(g);
}

static const gate_entry *find(const gate *g, const char *key)
{
    for (size_t i = 0; i < g->n; i++) if (!strcmp(g->e[i].key, key)) return &g->e[i];
    return NULL;
}

cs_status gate_load(const char *path, gate **out)
{
    *out = NULL;
    cs_status ist = paths_input_file(path);
    if (ist) return ist;
    FILE *f = fopen(path, "r");
    if (!f) return cs_err(CS_EINPUT, "%s: cannot open gate file: %s", path, strerror(errno));
    gate *g = calloc(1, sizeof *g);
    if (!g || !(g->path = strdup(path))) {
        fclose(f);
        gate_free(g);
        return cs_err(CS_ENOMEM, "%s: out of memory", path);
    }
    char line[4096];
    int lineno = 0;
    cs_status st = CS_OK;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        size_t len = strlen(line);
        if (len == 0 || line[len - 1] != '\n') {
            st = cs_err(CS_EINPUT, "%s:%d: truncated line (no newline or longer than %zu bytes)", path, lineno,
                        sizeof line - 2);
            break;
        }
        char *hash = strchr(line, '#');
        if (hash) *hash = '\0';
        char *save = NULL;
        char *key = strtok_r(line, " \t\r\n", &save);
        if (!key) continue;
        if (find(g, key)) { st = cs_err(CS_EINPUT, "%s:%d: field '%s': duplicate key", path, lineno, key); break; }
        gate_entry e = {0};
        e.line = lineno;
        e.key = strdup(key);
        e.v = malloc(64 * sizeof *e.v);
        if (!e.key || !e.v) { free(e.key); free(e.v); st = cs_err(CS_ENOMEM, "%s: out of memory", path); break; }
        char *tok;
        while ((tok = strtok_r(NULL, " \t\r\n", &save))) {
            char *end;
            errno = 0;
            double v = strtod(tok, &end);
            if (end == tok || *end || errno == ERANGE || !isfinite(v) || e.n >= 64) {
                st = cs_err(CS_EINPUT, "%s:%d: field '%s': value %zu not a number: '%s'", path, lineno, key, e.n + 1,
                            tok);
                break;
            }
            e.v[e.n++] = v;
        }
        if (!st && e.n == 0) st = cs_err(CS_EINPUT, "%s:%d: field '%s': no value", path, lineno, key);
        if (st) { free(e.key); free(e.v); break; }
        gate_entry *ne = realloc(g->e, (g->n + 1) * sizeof *ne);
        if (!ne) { free(e.key); free(e.v); st = cs_err(CS_ENOMEM, "%s: out of memory", path); break; }
        g->e = ne;
        g->e[g->n++] = e;
    }
    if (!st && ferror(f)) st = cs_err(CS_EINPUT, "%s: read error", path);
    fclose(f);
    if (!st && g->n == 0) st = cs_err(CS_EINPUT, "%s: no thresholds in gate file", path);
    if (st) { gate_free(g); return st; }
    *out = g;
    return CS_OK;
}

size_t gate_count(const gate *g, const char *key)
{
    const gate_entry *e = find(g, key);
    return e ? e->n : 0;
}

int gate_line(const gate *g, const char *key)
{
    const gate_entry *e = find(g, key);
    return e ? e->line : 0;
}

cs_status gate_value(const gate *g, const char *key, size_t idx, double *out)
{
    const gate_entry *e = find(g, key);
    if (!e) return cs_err(CS_EINPUT, "%s: field '%s': missing from gate file", g->path, key);
    if (idx >= e->n)
        return cs_err(CS_EINPUT, "%s:%d: field '%s': value %zu missing (has %zu)", g->path, e->line, key, idx + 1,
                      e->n);
    *out = e->v[idx];
    return CS_OK;
}

cs_status gate_values(const gate *g, const char *key, const double **vals, size_t *n)
{
    const gate_entry *e = find(g, key);
    if (!e) return cs_err(CS_EINPUT, "%s: field '%s': missing from gate file", g->path, key);
    *vals = e->v;
    *n = e->n;
    return CS_OK;
}

cs_status gate_read_value(const char *path, const char *key, size_t idx, double *out)
{
    gate *g;
    cs_status st = gate_load(path, &g);
    if (st) return st;
    st = gate_value(g, key, idx, out);
    gate_free(g);
    return st;
}

cs_status gate_read_values(const char *path, const char *key, double *v, size_t cap, size_t *n)
{
    gate *g;
    cs_status st = gate_load(path, &g);
    if (st) return st;
    const double *vals = NULL;
    st = gate_values(g, key, &vals, n);
    if (!st && *n > cap) st = cs_err(CS_EINPUT, "%s: field '%s': more than %zu values", path, key, cap);
    if (!st) memcpy(v, vals, *n * sizeof *v);
    gate_free(g);
    return st;
}

const char *verdict_name(verdict v)
{
    return v == VERDICT_PASS ? "PASS" : v == VERDICT_FAIL ? "FAIL" : "PENDING";
}

verdict gate_judge(gate_op op, double x, double lo, double hi)
{
    if (!isfinite(x)) return VERDICT_FAIL;
    int ok = 0;
    switch (op) {
    case GATE_GE: ok = x >= lo; break;
    case GATE_GT: ok = x > lo; break;
    case GATE_LE: ok = x <= lo; break;
    case GATE_LT: ok = x < lo; break;
    case GATE_IN: ok = x >= lo && x <= hi; break;
    case GATE_OUT: ok = x < lo || x > hi; break;
    case GATE_TRUE: ok = x != 0.0; break;
    }
    return ok ? VERDICT_PASS : VERDICT_FAIL;
}

const char *gate_op_text(gate_op op)
{
    switch (op) {
    case GATE_GE: return ">=";
    case GATE_GT: return ">";
    case GATE_LE: return "<=";
    case GATE_LT: return "<";
    case GATE_IN: return "in";
    case GATE_OUT: return "outside";
    case GATE_TRUE: return "holds";
    }
    return "?";
}
