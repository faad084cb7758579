/* field: loader and summary of the field reference (design.md §7; paper §5.3-5.4).
 * Limits: the raw table must already be in the documented three-column TSV
 * form (convert the Dryad file first); one measurement per tree and direction. */
#include "field.h"
#include "estimator.h"
#include "tsv.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

int field_direction(const char *s)
{
    static const char *shortn[4] = {"E", "N", "W", "S"};
    static const char *longn[4] = {"east", "north", "west", "south"};
    for (int c = 0; c < 4; c++)
        if (!strcasecmp(s, shortn[c]) || !strcasecmp(s, longn[c])) return c;
    return -1;
}

void field_table_free(field_table *ft)
{
    free(ft->id);
    free(ft->gap);
    ft->id = NULL;
    ft->gap = NULL;
    ft->n = 0;
}

const char *field_table_env(void)
{
    const char *p = getenv(FIELD_TABLE_ENV);
    return p && p[0] ? p : NULL;
}

/* qsort context (the loader is not reentrant across threads; the CLI is single-threaded) */
static const char **sort_ids;
static const size_t *sort_first;

static int by_id_then_row(const void *a, const void *b)
{
    size_t x = *(const size_t *)a, y = *(const size_t *)b;
    int c = strcmp(sort_ids[x], sort_ids[y]);
    return c ? c : (x > y) - (x < y);
}

static int by_first_row(const void *a, const void *b)
{
    size_t x = sort_first[*(const size_t *)a], y = sort_first[*(const size_t *)b];
    return (x > y) - (x < y);
}

/* Number the trees of the rows in order of first appearance (the file's
 * order) in O(n log n): sort the row indices by (id, row), give the first row
 * of each group a provisional index, then rank the groups by that row.
 * tree_of[r] receives row r's tree, out->id the ids, out->n the count. */
static cs_status group_trees(const char *path, const char **ids, size_t nr, size_t *ord, size_t *tree_of,
                             field_table *out)
{
    cs_status st = CS_OK;
    sort_ids = ids;
    qsort(ord, nr, sizeof *ord, by_id_then_row);
    /* first row of each group gets a provisional index; trees are then
     * numbered by the row of their first appearance (the file's order) */
    size_t *first = malloc(nr * sizeof *first), ng = 0;
    if (!first) st = cs_err(CS_ENOMEM, "%s: out of memory", path);
    for (size_t k = 0; !st && k < nr; k++) {
        if (k == 0 || strcmp(ids[ord[k]], ids[ord[k - 1]])) first[ng++] = ord[k];
        tree_of[ord[k]] = ng - 1;
    }
    if (!st) {
        /* rank groups by first row: first[] sorted ascending gives the order */
        size_t *rank = malloc(ng * sizeof *rank), *gorder = malloc(ng * sizeof *gorder);
        if (!rank || !gorder) st = cs_err(CS_ENOMEM, "%s: out of memory", path);
        for (size_t g = 0; !st && g < ng; g++) gorder[g] = g;
        if (!st) { sort_first = first; qsort(gorder, ng, sizeof *gorder, by_first_row); }
        for (size_t g = 0; !st && g < ng; g++) rank[gorder[g]] = g;
        for (size_t r = 0; !st && r < nr; r++) tree_of[r] = rank[tree_of[r]];
        for (size_t g = 0; !st && g < ng; g++) {
            strcpy(out->id[g], ids[first[gorder[g]]]);
            for (int q = 0; q < 4; q++) out->gap[g][q] = NAN;
        }
        if (!st) out->n = ng;
        free(rank); free(gorder);
    }
    free(first);
    return st;
}

/* Every tree has each of the four directions (seen[i][c]: the line of it, 0 = none). */
static cs_status check_complete(const char *path, const field_table *out, int (*seen)[4])
{
    static const char *names[4] = {"E", "N", "W", "S"};
    for (size_t i = 0; i < out->n; i++)
        for (int c = 0; c < 4; c++)
            if (!seen[i][c]) {
                int first = 0;
                for (int q = 0; q < 4; q++) if (seen[i][q] && (!first || seen[i][q] < first)) first = seen[i][q];
                return cs_err(CS_EINPUT,
                              "%s:%d: field 'direction': tree '%s' has no %s measurement (each tree needs E, N, W and "
                              "S exactly once)",
                              path, first, out->id[i], names[c]);
            }
    return CS_OK;
}

cs_status field_table_load(const char *path, field_table *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->path, sizeof out->path, "%s", path);
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    static const char *need[3] = {"tree", "direction", "clearance_m"};
    for (int k = 0; k < 3; k++)
        if (tsv_col(t, need[k]) < 0) {
            st = cs_err(CS_EINPUT, "%s: field '%s': no such column (need tree, direction, clearance_m)", path, need[k]);
            tsv_free(t);
            return st;
        }
    size_t nr = tsv_nrows(t);
    if (nr == 0) { tsv_free(t); return cs_err(CS_EINPUT, "%s: no measurements", path); }
    out->id = calloc(nr, sizeof *out->id);
    out->gap = malloc(nr * sizeof *out->gap);
    int (*seen)[4] = calloc(nr, sizeof *seen); /* line of each tree's direction, 0 = not yet */
    size_t *tree_of = malloc(nr * sizeof *tree_of), *ord = malloc(nr * sizeof *ord);
    const char **ids = malloc(nr * sizeof *ids);
    if (!out->id || !out->gap || !seen || !tree_of || !ord || !ids) {
        free(seen); free(tree_of); free(ord); free(ids); tsv_free(t); field_table_free(out);
        return cs_err(CS_ENOMEM, "%s: out of memory", path);
    }
    /* validate every row, then group rows by tree id in O(n log n): sort the
     * row indices by (id, row) and number the trees in order of first appearance */
    for (size_t r = 0; r < nr && !st; r++) {
        int line = tsv_line(t, r);
        const char *id = tsv_str(t, r, "tree");
        if (!id[0]) { st = cs_err(CS_EINPUT, "%s:%d: field 'tree': empty", path, line); break; }
        if (strlen(id) >= sizeof out->id[0]) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'tree': longer than 63 characters", path, line);
            break;
        }
        ord[r] = r;
        ids[r] = id;
    }
    if (!st) st = group_trees(path, ids, nr, ord, tree_of, out);
    for (size_t r = 0; r < nr && !st; r++) {
        int line = tsv_line(t, r);
        const char *id = tsv_str(t, r, "tree"), *dir = tsv_str(t, r, "direction");
        int c = field_direction(dir);
        if (c < 0) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'direction': '%s' is not E/N/W/S (or east/north/west/south)", path,
                        line, dir);
            break;
        }
        double g;
        if ((st = tsv_double(t, r, "clearance_m", &g))) break;
        if (fabs(g) > FIELD_CLEARANCE_MAX_M) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'clearance_m': %g m is out of range (|clearance| <= %g m)", path, line,
                        g, FIELD_CLEARANCE_MAX_M);
            break;
        }
        size_t i = tree_of[r];
        if (seen[i][c]) {
            st = cs_err(CS_EINPUT, "%s:%d: field 'direction': tree '%s' already has direction %s (line %d)", path, line,
                        id, dir, seen[i][c]);
            break;
        }
        seen[i][c] = line;
        out->gap[i][c] = g;
    }
    free(tree_of);
    free(ord);
    free(ids);
    if (!st) st = check_complete(path, out, seen);
    free(seen);
    tsv_free(t);
    if (st) field_table_free(out);
    return st;
}

cs_status field_summarize(const double (*gap)[4], size_t n, field_summary *out)
{
    memset(out, 0, sizeof *out);
    if (n == 0) return cs_err(CS_EINPUT, "field summary: no trees");
    double *tm = malloc(n * sizeof *tm), *all = malloc(4 * n * sizeof *all), *an = malloc(n * sizeof *an);
    if (!tm || !all || !an) { free(tm); free(all); free(an); return cs_err(CS_ENOMEM, "field summary: out of memory"); }
    size_t na = 0;
    for (size_t i = 0; i < n; i++) {
        tm[i] = est_tree_mean(gap[i]);
        for (int c = 0; c < 4; c++) all[4 * i + c] = gap[i][c];
        if (est_anisotropy(gap[i], &an[na])) na++;
    }
    out->trees = n;
    out->measurements = 4 * n;
    out->aniso_trees = na;
    out->aniso_excluded = n - na;
    out->aniso_median = NAN;
    cs_status st = est_median(tm, n, &out->tree_mean_median);
    if (!st) st = est_spread(all, 4 * n, &out->spread);
    if (!st && na) st = est_median(an, na, &out->aniso_median);
    free(tm); free(all); free(an);
    return st;
}

cs_status field_reference_get(const char *path, const char *quantity, double *v, int *line)
{
    tsv *t;
    cs_status st = tsv_read(path, &t);
    if (st) return st;
    if (tsv_col(t, "quantity") < 0 || tsv_col(t, "value") < 0) {
        st = cs_err(CS_EINPUT, "%s: field 'quantity'/'value': missing column", path);
    } else {
        long r = tsv_find(t, "quantity", quantity);
        if (r < 0) st = cs_err(CS_EINPUT, "%s: field 'quantity': no row '%s'", path, quantity);
        else {
            st = tsv_double(t, (size_t)r, "value", v);
            if (line) *line = tsv_line(t, (size_t)r);
        }
    }
    tsv_free(t);
    return st;
}
