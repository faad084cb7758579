/* audit: traceability checks (design.md §9). Messages always name the
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
#include "audit_data.h"
#include "audit_paper.h"
#include "audit_render.h"
#include "audit_evidence.h"
#include "audit_grids.h"
#include "audit_pin.h"
#include "audit_units.h"

static int file_exists(const char *p) { struct stat sb; return stat(p, &sb) == 0; }

/* Claims whose source is `path` or whose gate names `gatefile`, comma-joined. */
static void claims_of(const claims *c, const char *path, const char *gatefile, char *buf, size_t n)
{
    size_t off = 0, cnt = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < c->n && off < n; i++) {
        int hit = path && !strcmp(c->rows[i].source, path);
        if (gatefile && !strncmp(c->rows[i].gate, gatefile, strlen(gatefile)) &&
            c->rows[i].gate[strlen(gatefile)] == ':')
            hit = 1;
        if (!hit) continue;
        off += (size_t)snprintf(buf + off, n - off, "%s%s", cnt++ ? ", " : "", c->rows[i].macro);
    }
    if (!cnt && path) audit_feeds(c, path, buf, n);
    else if (!cnt) snprintf(buf, n, "(no claim)");
}

/* ---- pins ---- */

/* Claims computed by a function defined in the claim-code file `path`. */
static void claims_of_code(const claims *c, const char *path, char *buf, size_t n)
{
    FILE *f = fopen(path, "r");
    char *text = NULL;
    size_t len = 0;
    if (f) {
        fseek(f, 0, SEEK_END);
        long sz = ftell(f);
        rewind(f);
        if (sz > 0 && (text = malloc((size_t)sz + 1))) { len = fread(text, 1, (size_t)sz, f); text[len] = '\0'; }
        fclose(f);
    }
    size_t off = 0, cnt = 0;
    buf[0] = '\0';
    for (size_t i = 0; text && i < c->n && off < n; i++) {
        char def[96];
        snprintf(def, sizeof def, "cs_status %s(", c->rows[i].function);
        if (!strstr(text, def)) continue;
        off += (size_t)snprintf(buf + off, n - off, "%s%s", cnt++ ? ", " : "", c->rows[i].macro);
    }
    free(text);
    if (!cnt) snprintf(buf, n, "every claim (shared claim code)");
}

/* The claims a changed pin (key, path) affects, into buf: the claims of a
 * gate or a claim-code file, else what the pinned file decides for all. */
static void pin_affected(const claims *c, const char *key, const char *path, char *buf, size_t n)
{
    if (!strcmp(key, "gate_sha256")) {
        const char *base = strrchr(path, '/');
        claims_of(c, NULL, base ? base + 1 : path, buf, n);
    } else if (!strcmp(key, "claim_code_sha256")) {
        claims_of_code(c, path, buf, n);
    } else if (!strcmp(key, "audit_code_sha256")) {
        snprintf(buf, n, "every claim (the code that judges them: %s)", path);
    } else if (!strcmp(key, "claim_row_sha256")) {
        snprintf(buf, n, "%s", strchr(path, ':') ? strchr(path, ':') + 1 : path);
    } else if (!strcmp(key, "gate_map_sha256")) {
        /* the claims whose judging gate moved (map vs registry), else every mapped one */
        size_t off = 0, cnt = 0;
        buf[0] = '\0';
        for (int pass = 0; pass < 2 && !cnt; pass++)
            for (size_t i = 0; i < c->n && off < n - 40; i++)
                if (pass ? c->rows[i].gate_map_line != 0 : strcmp(c->rows[i].gate, c->rows[i].gate_reg) != 0)
                    off += (size_t)snprintf(buf + off, n - off, "%s%s", cnt++ ? ", " : "", c->rows[i].macro);
        if (!cnt) snprintf(buf, n, "every gated claim");
    } else if (!strcmp(key, "intervals_sha256")) {
        snprintf(buf, n, "the interval of every measured claim (%s)", path);
    } else if (!strcmp(key, "registry_sha256") || !strcmp(key, "aggregates_sha256")) {
        snprintf(buf, n, "every claim (%s)", path);
    } else if (!strcmp(key, "estimator_sha256") || !strcmp(key, "teacher_sha256") || !strcmp(key, "teacher_version")) {
        size_t off = 0, cnt = 0;
        buf[0] = '\0';
        for (size_t i = 0; i < c->n && off < n - 40; i++)
            if (!strcmp(c->rows[i].kind, "measured") || !strcmp(c->rows[i].kind, "probe") ||
                claims_is_beside(&c->rows[i]))
                off += (size_t)snprintf(buf + off, n - off, "%s%s", cnt++ ? ", " : "", c->rows[i].macro);
        if (!cnt) snprintf(buf, n, "every measured claim");
    } else if (!strcmp(key, "design_sha256") || !strcmp(key, "design_numbers_sha256")) {
        snprintf(buf, n, "every claim resting on the design constants (%s)", path);
    } else if (!strcmp(key, "claim_test_sha256")) {
        snprintf(buf, n, "every claim whose test is in %s", path);
    } else if (!strcmp(key, "superseded_sha256")) {
        snprintf(buf, n, "every claim of a table made by a superseded reading (%s)", path);
    } else if (!strcmp(key, "grids_sha256")) {
        snprintf(buf, n, "every claim of a table with a design grid (%s)", path);
    } else if (!strcmp(key, "figure_script_sha256") || !strcmp(key, "figure_data_sha256")) {
        snprintf(buf, n, "the figures %s draws or pins (what they show, not a number)", path);
    } else if (!strcmp(key, "gates_prereg_sha256")) {
        snprintf(buf, n, "every gated claim (%s)", path);
    } else
        snprintf(buf, n, "(gates as a whole)");
}

static void check_pins(const claims *c, checklist *cl, const pinset *ps)
{
    tsv *t;
    if (tsv_read(PATHS_PINS, &t)) {
        checklist_add(cl, VERDICT_FAIL, "pins", "%s", cs_errmsg());
        return;
    }
    const pin *cur = ps->p;
    size_t n = ps->n;
    for (size_t r = 0; r < tsv_nrows(t); r++) {
        const char *key = tsv_str(t, r, "key"), *val = tsv_str(t, r, "value"), *path = tsv_str(t, r, "path");
        if (!key || !val || !path) {
            checklist_add(cl, VERDICT_FAIL, "pins", "%s:%d: missing key/value/path", PATHS_PINS, tsv_line(t, r));
            continue;
        }
        const pin *m = NULL;
        for (size_t i = 0; i < n; i++) if (!strcmp(cur[i].key, key) && !strcmp(cur[i].path, path)) m = &cur[i];
        char name[96];
        snprintf(name, sizeof name, "pin %s", path);
        if (!m) {
            checklist_add(cl, VERDICT_FAIL, name, "%s:%d: pinned %s for %s, which no longer exists", PATHS_PINS,
                          tsv_line(t, r), key, path);
            continue;
        }
        if (strcmp(m->value, val)) {
            char affected[600];
            pin_affected(c, key, path, affected, sizeof affected);
            checklist_add(cl, VERDICT_FAIL, name,
                          "%s changed: %s is %.16s…, pinned %.16s… (%s:%d); claims affected: %s", path, key, m->value,
                          val, PATHS_PINS, tsv_line(t, r), affected);
        } else
            checklist_add(cl, VERDICT_PASS, name, "%s %s matches the pin", key,
                          strcmp(key, "teacher_version") ? "sha256" : val);
    }
    for (size_t i = 0; i < n; i++) {
        if (tsv_find(t, "path", cur[i].path) < 0 && strcmp(cur[i].value, "absent")) {
            char name[96];
            snprintf(name, sizeof name, "pin %s", cur[i].path);
            checklist_add(cl, VERDICT_FAIL, name, "%s is not pinned in %s (run crownshy pin deliberately)", cur[i].path,
                          PATHS_PINS);
        }
    }
    tsv_free(t);
}

cs_status audit_hash_frozen(void)
{
    paths_list l;
    cs_status st = paths_list_every(PATHS_FROZEN_DIR, 1, &l);
    if (st) return st;
    /* a temporary or hidden file is never sealed as a result */
    for (size_t i = 0; i < l.n; i++) {
        struct stat sb;
        if (paths_is_hidden_or_tmp(l.p[i]) || lstat(l.p[i], &sb) != 0 || !S_ISREG(sb.st_mode)) {
            st = cs_err(CS_EINPUT,
                        "%s: a hidden, temporary or non-regular file (a symlink, a folder link, a device) in %s/ is "
                        "not a frozen result: remove it before sealing",
                        l.p[i], PATHS_FROZEN_DIR);
            paths_list_free(&l);
            return st;
        }
    }
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
        if (frozen_files->n)
            checklist_add(cl, VERDICT_FAIL, "frozen hashes", "%s missing but frozen/ has %zu files (run make freeze)",
                          PATHS_FROZEN_HASHES, frozen_files->n);
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
        if (!file_exists(path)) {
            checklist_add(cl, VERDICT_FAIL, name, "%s is listed in %s:%d but missing; claims affected: %s", path,
                          PATHS_FROZEN_HASHES, lineno, affected);
            bad++;
            continue;
        }
        if (prov_sha256_file(path, cur) || strcmp(cur, hex)) {
            checklist_add(cl, VERDICT_FAIL, name,
                          "%s was modified after freezing (sha256 differs from %s:%d); claims affected: %s", path,
                          PATHS_FROZEN_HASHES, lineno, affected);
            bad++;
            continue;
        }
        ok++;
    }
    fclose(f);
    for (size_t i = 0; i < frozen_files->n; i++) {
        int found = 0;
        for (size_t j = 0; j < listed.n && !found; j++) found = !strcmp(listed.p[j], frozen_files->p[i]);
        if (!found) {
            checklist_add(cl, VERDICT_FAIL, "frozen hashes", "%s is not listed in %s (frozen by hand? run make freeze)",
                          frozen_files->p[i], PATHS_FROZEN_HASHES);
            bad++;
        }
    }
    /* nothing in frozen/ is invisible: dotfiles, "*.tmp*" names, other entries */
    paths_list every = {0};
    paths_list_every(PATHS_FROZEN_DIR, 1, &every);
    for (size_t i = 0; i < every.n; i++) {
        struct stat sb;
        int reg = lstat(every.p[i], &sb) == 0 && S_ISREG(sb.st_mode); /* a symlink is not a result */
        if (!paths_is_hidden_or_tmp(every.p[i]) && reg) continue;
        int sealed = 0;
        for (size_t j = 0; j < listed.n && !sealed; j++) sealed = !strcmp(listed.p[j], every.p[i]);
        /* the table it shadows: "x.tsv.tmp.1.2" and ".x.tsv" name x.tsv's claims */
        char shadow[1024], affected[600];
        const char *b = strrchr(every.p[i], '/');
        b = b ? b + 1 : every.p[i];
        snprintf(shadow, sizeof shadow, "%.*s%s", (int)(b - every.p[i]), every.p[i], b + (b[0] == '.'));
        char *tmp = strstr(shadow + (b - every.p[i]), ".tmp");
        if (tmp) *tmp = '\0';
        claims_of(c, shadow, NULL, affected, sizeof affected);
        checklist_add(cl, VERDICT_FAIL, "frozen hashes",
                      "%s: a %s file in %s/%s is not a frozen result (a half-written or hand-placed file): remove it; "
                      "it shadows %s; claims affected: %s",
                      every.p[i], reg ? "hidden or temporary" : "non-regular (symlink or other)", PATHS_FROZEN_DIR,
                      sealed ? " (sealed in " PATHS_FROZEN_HASHES " by hand)" : "", shadow, affected);
        bad++;
    }
    paths_list_free(&every);
    paths_list_free(&listed);
    if (!bad) checklist_add(cl, VERDICT_PASS, "frozen hashes", "%zu frozen files match %s", ok, PATHS_FROZEN_HASHES);
}

/* Tables made by one superseded reading, one line per frozen folder. */
enum { SUP_GROUPS = 32 };
typedef struct { char dir[256], old[256], claims[700]; int line; size_t files; } sup_group;

/* The four pinned keys of table p (tsv t) against the pins: a mismatch the
 * readings expect passes; one a superseded reading of pins_superseded.tsv
 * excuses is named in old (first_line: its line); any other is a finding.
 * Returns the mismatches; *excused counts the excused ones. */
static int provenance_keys(const char *p, const tsv *t, const pinset *ps, const tsv *sup, checklist *cl, char *old,
                           size_t on, int *first_line, int *excused, size_t *bad)
{
    static const char *const keys[] = {"teacher_version", "teacher_sha256", "estimator_sha256", "gates_sha256"};
    size_t off = 0;
    int mismatch = 0;
    for (int k = 0; k < 4; k++) {
        const char *v = tsv_meta(t, keys[k]);
        const char *want = NULL;
        for (size_t j = 0; j < ps->n; j++) if (!strcmp(ps->p[j].key, keys[k])) want = ps->p[j].value;
        if (v && want && !strcmp(v, want)) continue;
        /* The readings (design.md §7 E0) and the sensitivity's dieback units run
         * the pinned teacher under its other die-back readings too: under their
         * folders those versions (teacher_version(): the pinned or the one-sided
         * one, optionally "-arc" or "-target") are expected, not a mismatch. */
        char one[32] = "";
        if (k == 0 && prov_teacher_version_one_sided(one, sizeof one)) one[0] = '\0';
        if (k == 0 && v &&
            (!strncmp(p, PATHS_FROZEN_DIR "/readings/", strlen(PATHS_FROZEN_DIR) + 10) ||
             !strncmp(p, PATHS_SENS_DIR "/", strlen(PATHS_SENS_DIR) + 1)) &&
            ((one[0] && prov_reading_version(v, one)) || (want && prov_reading_version(v, want)) ||
             !strcmp(v, "per run")))
            continue;
        mismatch++;
        int line = v && prov_reading_key(keys[k]) ? audit_pin_superseded_line(sup, keys[k], v) : 0;
        if (line) {
            (*excused)++;
            if (!*first_line) *first_line = line;
            off += (size_t)snprintf(old + off, off < on ? on - off : 0, "%s%s %.12s", off ? ", " : "",
                                    keys[k] + (strncmp(keys[k], "teacher_v", 9) ? 0 : 8), v);
            continue;
        }
        checklist_add(
            cl, VERDICT_FAIL, "provenance",
            "%s: provenance %s = %.16s does not match the current pin %.16s (frozen with other code: regenerate)", p,
            keys[k], v ? v : "(missing)", want ? want : "(none)");
        (*bad)++;
    }
    return mismatch;
}

/* Table p, made wholly by the superseded reading old, into its folder's group. */
static void group_superseded(const claims *c, const char *p, const char *old, int first_line, sup_group *sups,
                             size_t *nsup, checklist *cl, size_t *bad)
{
    char dir[256];
    snprintf(dir, sizeof dir, "%.*s", (int)(strrchr(p, '/') - p), p);
    size_t k = 0;
    while (k < *nsup && (strcmp(sups[k].dir, dir) || strcmp(sups[k].old, old))) k++;
    if (k == *nsup && *nsup < SUP_GROUPS) {
        snprintf(sups[k].dir, sizeof sups[k].dir, "%s", dir);
        snprintf(sups[k].old, sizeof sups[k].old, "%s", old);
        sups[k].line = first_line, sups[k].files = 0, sups[k].claims[0] = '\0';
        (*nsup)++;
    }
    if (k == *nsup) {
        checklist_add(cl, VERDICT_FAIL, "provenance",
                      "%s: more than %d folder/reading pairs made by superseded readings: re-run them", p, SUP_GROUPS);
        (*bad)++;
        return;
    }
    char affected[600];
    claims_of(c, p, NULL, affected, sizeof affected);
    size_t l = strlen(sups[k].claims);
    if (strcmp(affected, "(no claim)"))
        snprintf(sups[k].claims + l, sizeof sups[k].claims - l, "%s%s", l ? ", " : "", affected);
    sups[k].files++;
}

static void check_provenance(const claims *c, checklist *cl, const paths_list *frozen_files, const pinset *ps)
{
    tsv *sup = NULL;
    tsv_read(PATHS_PINS_SUPERSEDED, &sup); /* absent: no superseded reading */
    sup_group sups[SUP_GROUPS];
    size_t nsup = 0;
    size_t checked = 0, bad = 0;
    for (size_t i = 0; i < frozen_files->n; i++) {
        const char *p = frozen_files->p[i];
        size_t len = strlen(p);
        if (len < 4 || strcmp(p + len - 4, ".tsv")) continue;
        tsv *t;
        if (tsv_read(p, &t)) { checklist_add(cl, VERDICT_FAIL, "provenance", "%s", cs_errmsg()); bad++; continue; }
        const char *status = tsv_meta(t, "status");
        if (!(tsv_meta(t, "experiment") && tsv_meta(t, "teacher_version"))) {
            /* provenance is required: only a table of published figures (not
             * measured here, with its citation) may lack the run's provenance */
            if (!(status && !strncmp(status, "PUBLISHED FIGURES", 17) && tsv_meta(t, "citation"))) {
                char affected[600];
                claims_of(c, p, NULL, affected, sizeof affected);
                checklist_add(cl, VERDICT_FAIL, "provenance",
                              "%s: no provenance ('# experiment:' and '# teacher_version:' lines; or '# status: "
                              "PUBLISHED FIGURES' with '# citation:'): stripped or made by hand; claims affected: %s",
                              p, affected);
                bad++;
            }
        } else {
            checked++;
            char old[512] = "";
            int excused = 0, first_line = 0; /* one line per frozen folder and reading, not per file: */
            const int mismatch = provenance_keys(p, t, ps, sup, cl, old, sizeof old, &first_line, &excused, &bad);
            if (mismatch && excused == mismatch) group_superseded(c, p, old, first_line, sups, &nsup, cl, &bad);
        }
        tsv_free(t);
    }
    if (sup) tsv_free(sup);
    for (size_t k = 0; k < nsup; k++)
        checklist_add(cl, VERDICT_PENDING, "provenance",
                      "%s/: %zu tables made by a superseded reading (%s; %s:%d), their numbers that reading's until "
                      "re-run; claims: %s",
                      sups[k].dir, sups[k].files, sups[k].old, PATHS_PINS_SUPERSEDED, sups[k].line,
                      sups[k].claims[0] ? sups[k].claims : "(no claim)");
    if (!bad)
        checklist_add(cl, VERDICT_PASS, "provenance",
                      "%zu frozen tables carry provenance matching the pins or a superseded reading listed in %s",
                      checked, PATHS_PINS_SUPERSEDED);
}

static void check_registry(const claims *c, checklist *cl)
{
    size_t bad = 0;
    const char *const *fns = claims_fn_names();
    for (size_t i = 0; fns[i]; i++) {
        int used = 0;
        for (size_t r = 0; r < c->n && !used; r++) used = !strcmp(c->rows[r].function, fns[i]);
        if (!used) {
            checklist_add(cl, VERDICT_FAIL, "registry", "orphan computing function %s: no row of %s names it", fns[i],
                          PATHS_CLAIMS);
            bad++;
        }
    }
    /* each row's test is derived from its macro (claims_registry): tests/test_claims.c runs it */
    /* which claims each gate judges is fixed by the pinned map, not the registry */
    for (size_t r = 0; r < c->n; r++)
        if (strcmp(c->rows[r].gate_reg, c->rows[r].gate)) {
            checklist_add(cl, VERDICT_FAIL, "registry gate column",
                          "%s:%d: the gate column of %s says '%s' but the pinned %s%s%.0d says '%s' (the map decides "
                          "which claim a gate judges); claim: %s",
                          PATHS_CLAIMS, c->rows[r].line, c->rows[r].macro, c->rows[r].gate_reg,
                          claims_is_beside(&c->rows[r]) ? PATHS_GATE_MAP_EXT : PATHS_GATE_MAP,
                          c->rows[r].gate_map_line ? ":" : "", c->rows[r].gate_map_line, c->rows[r].gate,
                          c->rows[r].macro);
            bad++;
        }
    if (!file_exists("tests/test_claims.c")) {
        checklist_add(cl, VERDICT_FAIL, "registry", "tests/test_claims.c missing: claims have no tests");
        bad++;
    }
    /* the registry file is the print of the claim tables: a hand edit shows */
    if (claims_registry_check(PATHS_CLAIMS)) {
        checklist_add(cl, VERDICT_FAIL, "registry", "%s", cs_errmsg());
        bad++;
    }
    if (!bad)
        checklist_add(cl, VERDICT_PASS, "registry",
                      "%zu claims, each with a computing function name and a test; no orphan function; %s the print "
                      "of the claim tables",
                      c->n, PATHS_CLAIMS);
}

cs_status audit_run(const claims *c, const claim_result *res, checklist *out)
{
    paths_list frozen_files = {0};
    /* the instrument as it is now, hashed once for both checks that read it */
    pinset pins = {0};
    int have_pins = audit_pin_current(&pins) == CS_OK;
    if (have_pins) check_pins(c, out, &pins);
    else checklist_add(out, VERDICT_FAIL, "pins", "%s", cs_errmsg());
    check_frozen(c, out, &frozen_files);
    if (have_pins) check_provenance(c, out, &frozen_files, &pins);
    audit_pin_free(&pins);
    paths_list_free(&frozen_files);
    audit_aggregates(c, out);
    audit_evidence(c, out);
    audit_grids(c, out);
    audit_identities(c, out);
    audit_gates_prereg(c, out);
    audit_superseded_real(out);
    check_registry(c, out);
    audit_generated(c, res, out, 0);
    audit_paper_text(c, res, out);
    audit_render(c, res, out);
    return CS_OK;
}
