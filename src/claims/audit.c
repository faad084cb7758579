/* audit: traceability checks (SPEC §9; issue 7). Messages always name the
 * file and the claims it feeds, so a tampered byte points at its culprit. */
#include "audit.h"
#include "afile.h"
#include "prov.h"
#include "tsv.h"
#include <dirent.h>
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include "paths.h"

void checklist_add(checklist *cl, verdict v, const char *name, const char *fmt, ...)
{
    if (cl->n == cl->cap) {
        size_t nc = cl->cap ? 2 * cl->cap : 64;
        check_item *ni = realloc(cl->items, nc * sizeof *ni);
        if (!ni) return;
        cl->items = ni;
        cl->cap = nc;
    }
    check_item *it = &cl->items[cl->n++];
    it->v = v;
    snprintf(it->name, sizeof it->name, "%s", name);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(it->msg, sizeof it->msg, fmt, ap);
    va_end(ap);
}

void checklist_free(checklist *cl)
{
    free(cl->items);
    memset(cl, 0, sizeof *cl);
}

void checklist_print(const checklist *cl, size_t count[3])
{
    for (size_t i = 0; i < cl->n; i++) {
        printf("  %-7s %-28s %s\n", verdict_name(cl->items[i].v), cl->items[i].name, cl->items[i].msg);
        count[cl->items[i].v]++;
    }
}

static int file_exists(const char *p) { struct stat sb; return stat(p, &sb) == 0; }

/* Claims whose source is `path` or whose gate names `gatefile`, comma-joined. */
static void claims_of(const claims *c, const char *path, const char *gatefile, char *buf, size_t n)
{
    size_t off = 0, cnt = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < c->n && off < n; i++) {
        int hit = path && !strcmp(c->rows[i].source, path);
        if (gatefile && !strncmp(c->rows[i].gate, gatefile, strlen(gatefile)) && c->rows[i].gate[strlen(gatefile)] == ':') hit = 1;
        if (!hit) continue;
        off += (size_t)snprintf(buf + off, n - off, "%s%s", cnt++ ? ", " : "", c->rows[i].macro);
    }
    if (!cnt) snprintf(buf, n, "(no claim)");
}

/* ---- pins ---- */
typedef struct { char key[64], value[80], path[256]; } pin;

static void current_pins(pin *p, size_t *n)
{
    size_t k = 0;
    snprintf(p[k].key, sizeof p[k].key, "teacher_version");
    if (prov_teacher_version(p[k].value, sizeof p[k].value)) snprintf(p[k].value, sizeof p[k].value, "absent");
    snprintf(p[k].path, sizeof p[k].path, "%s", PATHS_TEACHER_HDR);
    k++;
    const char *srcs[][2] = {{"teacher_sha256", PATHS_TEACHER_SRC}, {"estimator_sha256", PATHS_ESTIMATOR_SRC}};
    for (int i = 0; i < 2; i++, k++) {
        snprintf(p[k].key, sizeof p[k].key, "%s", srcs[i][0]);
        snprintf(p[k].path, sizeof p[k].path, "%s", srcs[i][1]);
        if (!file_exists(srcs[i][1]) || prov_sha256_file(srcs[i][1], p[k].value))
            snprintf(p[k].value, sizeof p[k].value, "absent");
    }
    snprintf(p[k].key, sizeof p[k].key, "gates_sha256");
    snprintf(p[k].path, sizeof p[k].path, PATHS_GATES_DIR);
    if (prov_gates_sha256(PATHS_GATES_DIR, p[k].value)) snprintf(p[k].value, sizeof p[k].value, "absent");
    k++;
    paths_list g = {0};
    paths_list_files(PATHS_GATES_DIR, "", 1, &g);
    for (size_t i = 0; i < g.n && k < 62; i++, k++) {
        snprintf(p[k].key, sizeof p[k].key, "gate_sha256");
        snprintf(p[k].path, sizeof p[k].path, "%s", g.p[i]);
        if (prov_sha256_file(g.p[i], p[k].value)) snprintf(p[k].value, sizeof p[k].value, "absent");
    }
    paths_list_free(&g);
    *n = k;
}

/* The instrument pins that name a reading (not the gates: a gate is never
 * superseded, it is preregistered). */
static int reading_key(const char *key)
{
    return !strcmp(key, "teacher_version") || !strcmp(key, "teacher_sha256") || !strcmp(key, "estimator_sha256");
}

/* Line of (key, value) in the superseded pins t (may be NULL), 0 if absent. */
static int superseded_line(const tsv *t, const char *key, const char *value)
{
    for (size_t r = 0; t && r < tsv_nrows(t); r++) {
        const char *k = tsv_str(t, r, "key"), *v = tsv_str(t, r, "value");
        if (k && v && !strcmp(k, key) && !strcmp(v, value)) return tsv_line(t, r);
    }
    return 0;
}

/* Keep every earlier pin of a reading that changes now, with the commit it
 * was superseded at: frozen results it made stay traceable until re-run. */
static cs_status supersede(const pin *cur, size_t n)
{
    tsv *old = NULL, *sup = NULL;
    if (tsv_read(PATHS_PINS, &old)) return CS_OK; /* first pinning: nothing superseded */
    tsv_read(PATHS_PINS_SUPERSEDED, &sup);        /* absent: none yet */
    size_t add = 0;
    const char *newv[64] = {0};
    for (size_t r = 0; r < tsv_nrows(old); r++) {
        const char *key = tsv_str(old, r, "key"), *val = tsv_str(old, r, "value");
        if (!key || !val || !reading_key(key)) continue;
        for (size_t i = 0; i < n; i++)
            if (!strcmp(cur[i].key, key) && strcmp(cur[i].value, val) && !superseded_line(sup, key, val)) { newv[r < 64 ? r : 63] = val; add++; }
    }
    cs_status st = CS_OK;
    if (add) {
        char commit[64] = "unknown";
        FILE *g = popen("git rev-parse --short=12 HEAD 2>/dev/null", "r");
        if (g) { if (fgets(commit, sizeof commit, g)) commit[strcspn(commit, "\n")] = '\0'; pclose(g); }
        tsv_writer *w;
        if (!(st = tsv_writer_open(&w, PATHS_PINS_SUPERSEDED))) {
            tsv_writer_meta(w, "what", "earlier pins of the teacher and estimator whose frozen results are not yet re-run");
            tsv_writer_meta(w, "written_by", "crownshy pin (appends a reading's pin when it changes)");
            tsv_writer_columns(w, "key\tvalue\tpath\tsuperseded_at");
            for (size_t r = 0; sup && r < tsv_nrows(sup); r++) {
                const char *c[4] = {tsv_str(sup, r, "key"), tsv_str(sup, r, "value"), tsv_str(sup, r, "path"), tsv_str(sup, r, "superseded_at")};
                for (int k = 0; k < 4; k++) tsv_writer_str(w, c[k] ? c[k] : "-");
                tsv_writer_endrow(w);
            }
            for (size_t r = 0; r < tsv_nrows(old) && r < 64; r++) {
                if (!newv[r]) continue;
                tsv_writer_str(w, tsv_str(old, r, "key")); tsv_writer_str(w, newv[r]);
                tsv_writer_str(w, tsv_str(old, r, "path")); tsv_writer_str(w, commit);
                tsv_writer_endrow(w);
            }
            st = tsv_writer_commit(w);
        }
    }
    tsv_free(old);
    if (sup) tsv_free(sup);
    return st;
}

cs_status audit_pin(void)
{
    pin p[64];
    size_t n;
    current_pins(p, &n);
    cs_status st = supersede(p, n);
    if (st) return st;
    tsv_writer *w;
    st = tsv_writer_open(&w, PATHS_PINS);
    if (st) return st;
    tsv_writer_meta(w, "what", "pins of the instrument: teacher version and source hash, estimator source hash, gate hashes");
    tsv_writer_meta(w, "regenerate", "crownshy pin (deliberate: afterwards frozen/ must be regenerated with make reproduce freeze)");
    tsv_writer_columns(w, "key\tvalue\tpath");
    for (size_t i = 0; i < n; i++) {
        tsv_writer_str(w, p[i].key); tsv_writer_str(w, p[i].value); tsv_writer_str(w, p[i].path);
        tsv_writer_endrow(w);
    }
    return tsv_writer_commit(w);
}

static void check_pins(const claims *c, checklist *cl)
{
    tsv *t;
    if (tsv_read(PATHS_PINS, &t)) {
        checklist_add(cl, VERDICT_FAIL, "pins", "%s", cs_errmsg());
        return;
    }
    pin cur[64];
    size_t n;
    current_pins(cur, &n);
    for (size_t r = 0; r < tsv_nrows(t); r++) {
        const char *key = tsv_str(t, r, "key"), *val = tsv_str(t, r, "value"), *path = tsv_str(t, r, "path");
        if (!key || !val || !path) { checklist_add(cl, VERDICT_FAIL, "pins", "%s:%d: missing key/value/path", PATHS_PINS, tsv_line(t, r)); continue; }
        const pin *m = NULL;
        for (size_t i = 0; i < n; i++) if (!strcmp(cur[i].key, key) && !strcmp(cur[i].path, path)) m = &cur[i];
        char name[96];
        snprintf(name, sizeof name, "pin %s", path);
        if (!m) { checklist_add(cl, VERDICT_FAIL, name, "%s:%d: pinned %s for %s, which no longer exists", PATHS_PINS, tsv_line(t, r), key, path); continue; }
        if (strcmp(m->value, val)) {
            char affected[600];
            if (!strcmp(key, "gate_sha256")) {
                const char *base = strrchr(path, '/');
                claims_of(c, NULL, base ? base + 1 : path, affected, sizeof affected);
            } else if (!strcmp(key, "estimator_sha256") || !strcmp(key, "teacher_sha256") || !strcmp(key, "teacher_version")) {
                size_t off = 0, cnt = 0;
                affected[0] = '\0';
                for (size_t i = 0; i < c->n && off < sizeof affected - 40; i++)
                    if (!strcmp(c->rows[i].kind, "measured") || !strcmp(c->rows[i].kind, "probe")) off += (size_t)snprintf(affected + off, sizeof affected - off, "%s%s", cnt++ ? ", " : "", c->rows[i].macro);
                if (!cnt) snprintf(affected, sizeof affected, "every measured claim");
            } else snprintf(affected, sizeof affected, "(gates as a whole)");
            checklist_add(cl, VERDICT_FAIL, name, "%s changed: %s is %.16s…, pinned %.16s… (%s:%d); claims affected: %s",
                          path, key, m->value, val, PATHS_PINS, tsv_line(t, r), affected);
        } else checklist_add(cl, VERDICT_PASS, name, "%s %s matches the pin", key, strcmp(key, "teacher_version") ? "sha256" : val);
    }
    for (size_t i = 0; i < n; i++) {
        if (tsv_find(t, "path", cur[i].path) < 0 && strcmp(cur[i].value, "absent")) {
            char name[96];
            snprintf(name, sizeof name, "pin %s", cur[i].path);
            checklist_add(cl, VERDICT_FAIL, name, "%s is not pinned in %s (run crownshy pin deliberately)", cur[i].path, PATHS_PINS);
        }
    }
    tsv_free(t);
}

cs_status audit_hash_frozen(void)
{
    paths_list l;
    cs_status st = paths_list_files(PATHS_FROZEN_DIR, "", 1, &l);
    if (st) return st;
    afile a;
    st = afile_open(&a, PATHS_FROZEN_HASHES);
    if (st) { paths_list_free(&l); return st; }
    for (size_t i = 0; i < l.n && !st; i++) {
        char hex[65];
        st = prov_sha256_file(l.p[i], hex);
        if (!st) fprintf(a.f, "%s  %s\n", hex, l.p[i]);
    }
    paths_list_free(&l);
    if (st) { afile_abort(&a); return st; }
    return afile_commit(&a);
}

static void check_frozen(const claims *c, checklist *cl, paths_list *frozen_files)
{
    FILE *f = fopen(PATHS_FROZEN_HASHES, "r");
    paths_list_files(PATHS_FROZEN_DIR, "", 1, frozen_files);
    if (!f) {
        if (frozen_files->n) checklist_add(cl, VERDICT_FAIL, "frozen hashes", "%s missing but frozen/ has %zu files (run make freeze)", PATHS_FROZEN_HASHES, frozen_files->n);
        else checklist_add(cl, VERDICT_PASS, "frozen hashes", "frozen/ is empty (no experiment frozen yet)");
        return;
    }
    char line[2048];
    int lineno = 0;
    paths_list listed = {0};
    size_t ok = 0, bad = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        char hex[65], path[1024];
        if (sscanf(line, "%64s  %1023[^\n]", hex, path) != 2 || strlen(hex) != 64) {
            checklist_add(cl, VERDICT_FAIL, "frozen hashes", "%s:%d: malformed line", PATHS_FROZEN_HASHES, lineno);
            bad++;
            continue;
        }
        paths_list_add(&listed, path);
        char cur[65], affected[600], name[96];
        snprintf(name, sizeof name, "frozen %.80s", path);
        claims_of(c, path, NULL, affected, sizeof affected);
        if (!file_exists(path)) { checklist_add(cl, VERDICT_FAIL, name, "%s is listed in %s:%d but missing; claims affected: %s", path, PATHS_FROZEN_HASHES, lineno, affected); bad++; continue; }
        if (prov_sha256_file(path, cur) || strcmp(cur, hex)) {
            checklist_add(cl, VERDICT_FAIL, name, "%s was modified after freezing (sha256 differs from %s:%d); claims affected: %s", path, PATHS_FROZEN_HASHES, lineno, affected);
            bad++;
            continue;
        }
        ok++;
    }
    fclose(f);
    for (size_t i = 0; i < frozen_files->n; i++) {
        int found = 0;
        for (size_t j = 0; j < listed.n && !found; j++) found = !strcmp(listed.p[j], frozen_files->p[i]);
        if (!found) { checklist_add(cl, VERDICT_FAIL, "frozen hashes", "%s is not listed in %s (frozen by hand? run make freeze)", frozen_files->p[i], PATHS_FROZEN_HASHES); bad++; }
    }
    paths_list_free(&listed);
    if (!bad) checklist_add(cl, VERDICT_PASS, "frozen hashes", "%zu frozen files match %s", ok, PATHS_FROZEN_HASHES);
}

static void check_provenance(const claims *c, checklist *cl, const paths_list *frozen_files)
{
    pin cur[64];
    size_t n;
    current_pins(cur, &n);
    tsv *sup = NULL;
    tsv_read(PATHS_PINS_SUPERSEDED, &sup); /* absent: no superseded reading */
    struct { char dir[256], old[256], claims[700]; int line; size_t files; } sups[32];
    size_t nsup = 0;
    size_t checked = 0, bad = 0;
    for (size_t i = 0; i < frozen_files->n; i++) {
        const char *p = frozen_files->p[i];
        size_t len = strlen(p);
        if (len < 4 || strcmp(p + len - 4, ".tsv")) continue;
        tsv *t;
        if (tsv_read(p, &t)) { checklist_add(cl, VERDICT_FAIL, "provenance", "%s", cs_errmsg()); bad++; continue; }
        const char *keys[] = {"teacher_version", "teacher_sha256", "estimator_sha256", "gates_sha256"};
        if (tsv_meta(t, "experiment") && tsv_meta(t, "teacher_version")) {
            checked++;
            char old[512] = "";
            size_t off = 0;
            int mismatch = 0, excused = 0, first_line = 0;
            for (int k = 0; k < 4; k++) {
                const char *v = tsv_meta(t, keys[k]);
                const char *want = NULL;
                for (size_t j = 0; j < n; j++) if (!strcmp(cur[j].key, keys[k])) want = cur[j].value;
                if (v && want && !strcmp(v, want)) continue;
                /* The readings (SPEC §7 E0) run the pinned teacher under its
                 * revision-1 switch too: under frozen/readings/ the other
                 * reading's version string is expected, not a mismatch. */
                char one[32] = "";
                if (k == 0 && prov_teacher_version_one_sided(one, sizeof one)) one[0] = '\0';
                if (k == 0 && v && !strncmp(p, PATHS_FROZEN_DIR "/readings/", strlen(PATHS_FROZEN_DIR) + 10) &&
                    ((one[0] && !strcmp(v, one)) || !strcmp(v, "per run")))
                    continue;
                mismatch++;
                int line = v && reading_key(keys[k]) ? superseded_line(sup, keys[k], v) : 0;
                if (line) {
                    excused++;
                    if (!first_line) first_line = line;
                    off += (size_t)snprintf(old + off, off < sizeof old ? sizeof old - off : 0, "%s%s %.12s",
                                            off ? ", " : "", keys[k] + (strncmp(keys[k], "teacher_v", 9) ? 0 : 8), v);
                    continue;
                }
                checklist_add(cl, VERDICT_FAIL, "provenance", "%s: provenance %s = %.16s does not match the current pin %.16s (frozen with other code: regenerate)",
                              p, keys[k], v ? v : "(missing)", want ? want : "(none)");
                bad++;
            }
            if (mismatch && excused == mismatch) {
                /* one line per frozen folder and reading, not per file */
                char dir[256];
                snprintf(dir, sizeof dir, "%.*s", (int)(strrchr(p, '/') - p), p);
                size_t k = 0;
                while (k < nsup && (strcmp(sups[k].dir, dir) || strcmp(sups[k].old, old))) k++;
                if (k == nsup && nsup < 32) {
                    snprintf(sups[k].dir, sizeof sups[k].dir, "%s", dir);
                    snprintf(sups[k].old, sizeof sups[k].old, "%s", old);
                    sups[k].line = first_line;
                    sups[k].files = 0;
                    sups[k].claims[0] = '\0';
                    nsup++;
                }
                if (k < nsup) {
                    char affected[600];
                    claims_of(c, p, NULL, affected, sizeof affected);
                    size_t l = strlen(sups[k].claims);
                    if (strcmp(affected, "(no claim)"))
                        snprintf(sups[k].claims + l, sizeof sups[k].claims - l, "%s%s", l ? ", " : "", affected);
                    sups[k].files++;
                }
            }
        }
        tsv_free(t);
    }
    if (sup) tsv_free(sup);
    for (size_t k = 0; k < nsup; k++)
        checklist_add(cl, VERDICT_PENDING, "provenance", "%s/: %zu tables made by a superseded reading (%s; %s:%d), their numbers that reading's until re-run; claims: %s",
                      sups[k].dir, sups[k].files, sups[k].old, PATHS_PINS_SUPERSEDED, sups[k].line,
                      sups[k].claims[0] ? sups[k].claims : "(no claim)");
    if (!bad) checklist_add(cl, VERDICT_PASS, "provenance", "%zu frozen tables carry provenance matching the pins or a superseded reading listed in %s", checked, PATHS_PINS_SUPERSEDED);
}

static void check_registry(const claims *c, checklist *cl)
{
    size_t bad = 0;
    const char *const *fns = claims_fn_names();
    for (size_t i = 0; fns[i]; i++) {
        int used = 0;
        for (size_t r = 0; r < c->n && !used; r++) used = !strcmp(c->rows[r].function, fns[i]);
        if (!used) { checklist_add(cl, VERDICT_FAIL, "registry", "orphan computing function %s: no row of %s names it", fns[i], PATHS_CLAIMS); bad++; }
    }
    for (size_t r = 0; r < c->n; r++) {
        char want[128];
        snprintf(want, sizeof want, "tests/test_claims.c:claim_%s", c->rows[r].macro);
        if (strcmp(c->rows[r].test, want)) {
            checklist_add(cl, VERDICT_FAIL, "registry", "%s:%d: claim %s names test '%s'; its test is %s", PATHS_CLAIMS, c->rows[r].line, c->rows[r].macro, c->rows[r].test, want);
            bad++;
        }
    }
    if (!file_exists("tests/test_claims.c")) { checklist_add(cl, VERDICT_FAIL, "registry", "tests/test_claims.c missing: claims have no tests"); bad++; }
    if (!bad) checklist_add(cl, VERDICT_PASS, "registry", "%zu claims, each with a computing function name and a test; no orphan function", c->n);
}

/* Macros used in the paper text must be claims (or their Gate verdicts). */
static const char *latex_upper[] = {"LaTeX", "TeX", "Large", "LARGE", "Huge", "HUGE", "Roman", "Alph", "Ref", "S", "P", "L", "O", "AA", "AE", "OE", "Delta", "Gamma", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi", "Omega", "Bigl", "Bigr", "Big", "Biggl", "Biggr", "bibliographystyle", "IfFileExists", NULL};

static int is_latex_upper(const char *name)
{
    for (int i = 0; latex_upper[i]; i++) if (!strcmp(latex_upper[i], name)) return 1;
    return 0;
}

static void check_paper(const claims *c, const claim_result *res, checklist *cl)
{
    paths_list tex, all;
    paths_list_files(PATHS_PAPER_DIR, ".tex", 0, &all);
    memset(&tex, 0, sizeof tex);
    for (size_t i = 0; i < all.n; i++)
        if (strcmp(all.p[i], PATHS_NUMBERS)) paths_list_add(&tex, all.p[i]);
    paths_list_free(&all);
    size_t bad = 0, used = 0;
    for (size_t i = 0; i < tex.n; i++) {
        FILE *f = fopen(tex.p[i], "r");
        if (!f) continue;
        char line[4096];
        int lineno = 0, in_generated = 0;
        /* generated files (first line says GENERATED) are checked against a fresh generation instead */
        if (fgets(line, sizeof line, f) && strstr(line, "GENERATED")) { fclose(f); continue; }
        rewind(f);
        while (fgets(line, sizeof line, f)) {
            lineno++;
            if (strstr(line, "%%BEGIN-GENERATED")) in_generated = 1;
            if (strstr(line, "%%END-GENERATED")) { in_generated = 0; continue; }
            if (in_generated) continue;
            char *pct = line;
            while ((pct = strchr(pct, '%'))) {
                if (pct == line || pct[-1] != '\\') { *pct = '\0'; break; }
                pct++;
            }
            for (char *s = line; (s = strchr(s, '\\')); s++) {
                char name[80];
                int k = 0;
                while (k < 79 && ((s[1 + k] >= 'A' && s[1 + k] <= 'Z') || (s[1 + k] >= 'a' && s[1 + k] <= 'z'))) { name[k] = s[1 + k]; k++; }
                name[k] = '\0';
                if (!k || !(name[0] >= 'A' && name[0] <= 'Z') || is_latex_upper(name)) continue;
                char base[80];
                snprintf(base, sizeof base, "%s", name);
                size_t bl = strlen(base);
                if (bl > 4 && !strcmp(base + bl - 4, "Gate")) base[bl - 4] = '\0';
                if (!claims_find(c, base)) {
                    checklist_add(cl, VERDICT_FAIL, "paper macros", "%s:%d: \\%s has no row in %s", tex.p[i], lineno, name, PATHS_CLAIMS);
                    bad++;
                } else used++;
            }
            /* A measured value typed by hand: the literal text of a measured
             * claim (ours or the reference paper's) appearing in the prose. */
            for (size_t r = 0; r < c->n; r++) {
                if (strcmp(c->rows[r].kind, "measured") && strcmp(c->rows[r].kind, "needs-data") && strcmp(c->rows[r].kind, "probe")) continue;
                const char *cands[2] = {res[r].status == VERDICT_PASS ? res[r].text : NULL, c->rows[r].reference};
                for (int q = 0; q < 2; q++) {
                    const char *v = cands[q];
                    if (!v || strlen(v) < 4 || !strchr(v, '.')) continue; /* short integers are too common to police */
                    const char *hit = strstr(line, v[0] == '+' ? v + 1 : v);
                    if (hit) {
                        checklist_add(cl, VERDICT_FAIL, "hand-typed numbers", "%s:%d: '%s' typed by hand; use \\%s", tex.p[i], lineno, v, c->rows[r].macro);
                        bad++;
                    }
                }
            }
        }
        fclose(f);
    }
    if (!bad) checklist_add(cl, VERDICT_PASS, "paper macros", "%zu paper files: %zu claim-macro uses, all registered; no measured number typed by hand", tex.n, used);
    paths_list_free(&tex);
}

void audit_numbers(const claims *c, const claim_result *res, checklist *cl)
{
    const char *fresh = "build/numbers.fresh.tex";
    if (claims_write_numbers(fresh, c, res)) { checklist_add(cl, VERDICT_FAIL, "numbers.tex", "%s", cs_errmsg()); return; }
    FILE *a = fopen(fresh, "r"), *b = fopen(PATHS_NUMBERS, "r");
    if (!b) {
        checklist_add(cl, VERDICT_FAIL, "numbers.tex", "%s missing (generate it with crownshy numbers)", PATHS_NUMBERS);
        if (a) fclose(a);
        return;
    }
    char la[1024], lb[1024];
    int lineno = 0, diff = 0;
    for (;;) {
        char *ra = a ? fgets(la, sizeof la, a) : NULL, *rb = fgets(lb, sizeof lb, b);
        lineno++;
        if (!ra && !rb) break;
        if (!ra || !rb || strcmp(la, lb)) { diff = lineno; break; }
    }
    if (a) fclose(a);
    fclose(b);
    if (diff) {
        lb[strcspn(lb, "\n")] = '\0';
        checklist_add(cl, VERDICT_FAIL, "numbers.tex", "%s:%d differs from a fresh generation ('%s'): edited by hand or stale", PATHS_NUMBERS, diff, lb);
    } else checklist_add(cl, VERDICT_PASS, "numbers.tex", "%s equals a fresh generation from frozen/", PATHS_NUMBERS);
}

cs_status audit_run(const claims *c, const claim_result *res, checklist *out)
{
    paths_list frozen_files = {0};
    check_pins(c, out);
    check_frozen(c, out, &frozen_files);
    check_provenance(c, out, &frozen_files);
    paths_list_free(&frozen_files);
    check_registry(c, out);
    audit_numbers(c, res, out);
    check_paper(c, res, out);
    return CS_OK;
}
