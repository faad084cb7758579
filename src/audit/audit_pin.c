/* audit_pin: the instrument's pins, computed from the sources, and their
 * writing (design.md §9). A pin is a file's sha256 (or the teacher's version
 * string), so an edit anywhere a verdict rests on shows as a changed pin; a
 * file that is gone pins as "absent" rather than failing here, for the
 * check to name it. See audit_pin.h. */
#include "audit_pin.h"
#include "paths.h"
#include "prov.h"
#include "sha256.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int file_exists(const char *p) { struct stat sb; return stat(p, &sb) == 0; }

void audit_pin_free(pinset *s) { free(s->p); memset(s, 0, sizeof *s); }

static void add_pin(pinset *s, const char *key, const char *path, const char *value)
{
    if (s->n == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 512;
        pin *q = realloc(s->p, cap * sizeof *q);
        if (!q) { s->oom = 1; return; }
        s->p = q;
        s->cap = cap;
    }
    pin *e = &s->p[s->n++];
    snprintf(e->key, sizeof e->key, "%s", key);
    snprintf(e->path, sizeof e->path, "%s", path);
    snprintf(e->value, sizeof e->value, "%s", value);
}

static void add_file_pin(pinset *s, const char *key, const char *path)
{
    char hex[65];
    add_pin(s, key, path, file_exists(path) && !prov_sha256_file(path, hex) ? hex : "absent");
}

/* One pin per registry row (path "audit/claims.tsv:Macro"): an edited row names its claim. */
static void registry_row_pins(pinset *s)
{
    FILE *f = fopen(PATHS_CLAIMS, "r");
    char line[4096];
    int header = 0;
    while (f && fgets(line, sizeof line, f)) {
        if (line[0] == '#') continue;
        if (!header++) continue;
        char macro[64], path[160], hex[65];
        if (sscanf(line, "%63[^\t\n]", macro) != 1) continue;
        snprintf(path, sizeof path, "%s:%s", PATHS_CLAIMS, macro);
        sha256_hex(line, strlen(line), hex);
        add_pin(s, "claim_row_sha256", path, hex);
    }
    if (f) fclose(f);
}

/* The design constants no gate carries (design.md §2, §3, §7) and the claim
 * tests (the registry's test column names tests/test_claims.c). */
static const char *const design_files[] = {"src/base/design.h", "src/forest/crown.h", NULL};
static const char *const claim_tests[] = {"tests/test_claims.c", "tests/test_field_claims.c", "tests/test_interval.c",
                                          "tests/testutil.h",    "tests/tamper.sh",           NULL};

cs_status audit_pin_current(pinset *s)
{
    char v[80];
    if (prov_teacher_version(v, sizeof v)) snprintf(v, sizeof v, "absent");
    add_pin(s, "teacher_version", PATHS_TEACHER_HDR, v);
    add_file_pin(s, "teacher_sha256", PATHS_TEACHER_SRC);
    add_file_pin(s, "estimator_sha256", PATHS_ESTIMATOR_SRC);
    char hex[65];
    add_pin(s, "gates_sha256", PATHS_GATES_DIR, prov_gates_sha256(PATHS_GATES_DIR, hex) ? "absent" : hex);
    paths_list g = {0};
    paths_list_every(PATHS_GATES_DIR, 1, &g);
    for (size_t i = 0; i < g.n; i++) add_file_pin(s, "gate_sha256", g.p[i]);
    paths_list_free(&g);
    /* pinned with the gates: which claim each gate judges */
    add_file_pin(s, "gate_map_sha256", PATHS_GATE_MAP);
    add_file_pin(s, "gate_map_sha256", PATHS_GATE_MAP_EXT);
    /* the claim-computing code, the intervals and agreement it is judged by,
     * and the registry: an edit changes a verdict's inputs */
    const char *claim_dirs[] = {PATHS_CLAIMS_SRC_DIR, PATHS_AGREE_SRC_DIR};
    for (size_t d = 0; d < sizeof claim_dirs / sizeof *claim_dirs; d++) {
        paths_list cc = {0};
        paths_list_files(claim_dirs[d], ".c", 0, &cc);
        for (size_t i = 0; i < cc.n; i++) add_file_pin(s, "claim_code_sha256", cc.p[i]);
        paths_list_free(&cc);
    }
    /* the code that judges them: the audit, verify, the generated paper files */
    paths_list ac = {0};
    paths_list_files(PATHS_AUDIT_SRC_DIR, ".c", 0, &ac);
    for (size_t i = 0; i < ac.n; i++) add_file_pin(s, "audit_code_sha256", ac.p[i]);
    paths_list_free(&ac);
    add_file_pin(s, "registry_sha256", PATHS_CLAIMS);
    registry_row_pins(s);
    /* how every interval is computed (design.md §6.1) */
    add_file_pin(s, "intervals_sha256", PATHS_INTERVALS);
    add_file_pin(s, "aggregates_sha256", PATHS_AGGREGATES);
    /* what else a number rests on: the record of superseded readings, the
     * design grids and the preregistered gates' hashes, the design constants
     * no gate carries (and the list the paper may type), the claim tests */
    add_file_pin(s, "superseded_sha256", PATHS_PINS_SUPERSEDED);
    add_file_pin(s, "grids_sha256", PATHS_GRIDS);
    add_file_pin(s, "gates_prereg_sha256", PATHS_GATES_PREREG);
    add_file_pin(s, "design_numbers_sha256", PATHS_DESIGN_NUMBERS);
    for (size_t i = 0; design_files[i]; i++) add_file_pin(s, "design_sha256", design_files[i]);
    for (size_t i = 0; claim_tests[i]; i++) add_file_pin(s, "claim_test_sha256", claim_tests[i]);
    /* what draws each figure, and the data it must plot (figcheck.h) */
    static const char *const fig_ext[] = {".gp", ".gpi", NULL};
    for (size_t e = 0; fig_ext[e]; e++) {
        paths_list fl = {0};
        paths_list_files(PATHS_FIGURES_DIR, fig_ext[e], 0, &fl);
        for (size_t i = 0; i < fl.n; i++) add_file_pin(s, "figure_script_sha256", fl.p[i]);
        paths_list_free(&fl);
    }
    add_file_pin(s, "figure_data_sha256", PATHS_FIG_PLOTTED);
    return s->oom ? cs_err(CS_ENOMEM, "pins: out of memory after %zu pins", s->n) : CS_OK;
}

int audit_pin_superseded_line(const tsv *t, const char *key, const char *value)
{
    for (size_t r = 0; t && r < tsv_nrows(t); r++) {
        const char *k = tsv_str(t, r, "key"), *v = tsv_str(t, r, "value");
        if (k && v && !strcmp(k, key) && !strcmp(v, value)) return tsv_line(t, r);
    }
    return 0;
}

/* Keep every earlier pin of a reading that changes now, with the commit it
 * was superseded at: frozen results it made stay traceable until re-run.
 * Only the pins that name a reading: a gate is never superseded, it is
 * preregistered. */
static cs_status supersede(const pinset *ps)
{
    const pin *cur = ps->p;
    size_t n = ps->n;
    tsv *old = NULL, *sup = NULL;
    if (tsv_read(PATHS_PINS, &old)) return CS_OK; /* first pinning: nothing superseded */
    tsv_read(PATHS_PINS_SUPERSEDED, &sup);        /* absent: none yet */
    size_t add = 0;
    const char **newv = calloc(tsv_nrows(old) + 1, sizeof *newv);
    if (!newv) {
        tsv_free(old);
        if (sup) tsv_free(sup);
        return cs_err(CS_ENOMEM, "pin: out of memory");
    }
    for (size_t r = 0; r < tsv_nrows(old); r++) {
        const char *key = tsv_str(old, r, "key"), *val = tsv_str(old, r, "value");
        if (!key || !val || !prov_reading_key(key)) continue;
        for (size_t i = 0; i < n; i++)
            if (!strcmp(cur[i].key, key) && strcmp(cur[i].value, val) && !audit_pin_superseded_line(sup, key, val)) {
                newv[r] = val;
                add++;
            }
    }
    cs_status st = CS_OK;
    if (add) {
        char commit[64] = "unknown";
        FILE *g = popen("git rev-parse --short=12 HEAD 2>/dev/null", "r");
        if (g) { if (fgets(commit, sizeof commit, g)) commit[strcspn(commit, "\n")] = '\0'; pclose(g); }
        tsv_writer *w;
        if (!(st = tsv_writer_open(&w, PATHS_PINS_SUPERSEDED))) {
            tsv_writer_meta(w, "what",
                            "earlier pins of the teacher and estimator whose frozen results are not yet re-run");
            tsv_writer_meta(w, "written_by", "crownshy pin (appends a reading's pin when it changes)");
            tsv_writer_columns(w, "key\tvalue\tpath\tsuperseded_at");
            for (size_t r = 0; sup && r < tsv_nrows(sup); r++) {
                const char *c[4] = {tsv_str(sup, r, "key"), tsv_str(sup, r, "value"), tsv_str(sup, r, "path"),
                                    tsv_str(sup, r, "superseded_at")};
                for (int k = 0; k < 4; k++) tsv_writer_str(w, c[k] ? c[k] : "-");
                tsv_writer_endrow(w);
            }
            for (size_t r = 0; r < tsv_nrows(old); r++) {
                if (!newv[r]) continue;
                tsv_writer_str(w, tsv_str(old, r, "key")); tsv_writer_str(w, newv[r]);
                tsv_writer_str(w, tsv_str(old, r, "path")); tsv_writer_str(w, commit);
                tsv_writer_endrow(w);
            }
            st = tsv_writer_commit(w);
        }
    }
    free(newv);
    tsv_free(old);
    if (sup) tsv_free(sup);
    return st;
}

cs_status audit_pin(void)
{
    pinset ps = {0};
    cs_status st = audit_pin_current(&ps);
    if (!st) st = supersede(&ps);
    audit_pin_free(&ps);
    if (!st) st = audit_pin_current(&ps); /* the superseded record is pinned as supersede left it */
    tsv_writer *w = NULL;
    if (!st) st = tsv_writer_open(&w, PATHS_PINS);
    if (st) { audit_pin_free(&ps); return st; }
    const pin *p = ps.p;
    size_t n = ps.n;
    tsv_writer_meta(w, "what",
                    "pins of the instrument: teacher version and source hash, estimator source hash, gate hashes and "
                    "the claim-to-gate map; the claim code, the registry (whole and per row) and the aggregate map");
    tsv_writer_meta(w, "regenerate",
                    "crownshy pin (deliberate: afterwards frozen/ must be regenerated with make reproduce freeze)");
    tsv_writer_columns(w, "key\tvalue\tpath");
    for (size_t i = 0; i < n; i++) {
        tsv_writer_str(w, p[i].key); tsv_writer_str(w, p[i].value); tsv_writer_str(w, p[i].path);
        tsv_writer_endrow(w);
    }
    audit_pin_free(&ps);
    return tsv_writer_commit(w);
}
