/* audit_evidence: the evidence behind the numbers, checked cheaply in tier 1
 * (design.md §9). See audit_evidence.h. */
#include "audit_evidence.h"
#include "audit_data.h"
#include "gate.h"
#include "paths.h"
#include "prov.h"
#include "sha256.h"
#include "tsv.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>


/* ---- files named by provenance, weights seals, W1 from samples ---- */

/* "NAME sha256 HEX ..." in a provenance value: 1 and the two parts. */
static int named_file(const char *v, char *name, size_t nn, char hex[65])
{
    char a[256], b[16], h[80];
    if (sscanf(v, "%255s %15s %79s", a, b, h) != 3 || strcmp(b, "sha256") || strlen(h) != 64) return 0;
    for (const char *p = h; *p; p++) if (!strchr("0123456789abcdef", *p)) return 0;
    snprintf(name, nn, "%s", a);
    memcpy(hex, h, 65);
    return 1;
}

static size_t check_named_files(const claims *c, const char *p, checklist *cl, size_t *checked)
{
    /* provenance is "# key: value" lines at the top; scan them as text (tsv
     * keeps only the first of a repeated key) */
    FILE *f = fopen(p, "r");
    if (!f) return 0;
    char line[4096], dir[1024];
    snprintf(dir, sizeof dir, "%.*s", (int)(strrchr(p, '/') ? strrchr(p, '/') - p : 0), p);
    size_t bad = 0;
    int lineno = 0;
    while (fgets(line, sizeof line, f) && line[0] == '#') {
        lineno++;
        char *colon = strstr(line, ": "), name[256], hex[65], cur[65], named[1300], file[1400], affected[600];
        if (!colon || !named_file(colon + 2, name, sizeof name, hex)) continue;
        /* a record names a file by the place it was frozen at (paths.h) */
        snprintf(named, sizeof named, "%s/%s", dir, name);
        paths_recorded(named, file, sizeof file);
        (*checked)++;
        struct stat sb;
        int missing = lstat(file, &sb) != 0 || !S_ISREG(sb.st_mode);
        if (!missing && !prov_sha256_file(file, cur) && !strcmp(cur, hex)) continue;
        audit_feeds(c, p, affected, sizeof affected);
        checklist_add(cl, VERDICT_FAIL, "provenance files",
                      "%s:%d names %s (sha256 %.16s…), which is %s; claims affected: %s", p, lineno, file, hex,
                      missing ? "missing" : "different (its sha256 differs)", affected);
        bad++;
    }
    fclose(f);
    return bad;
}

/* The seal of a weights file (format 1, src/model/train.h): magic "CSHYWGTS",
 * version 1, and the 64-bit FNV-1a checksum of everything before it in its
 * last 8 bytes. Read here byte for byte, so the claims need not reach the model. */
static int weights_sealed(const char *path, char *why, size_t wn)
{
    FILE *f = fopen(path, "rb");
    if (!f) { snprintf(why, wn, "cannot open"); return 0; }
    unsigned char buf[1 << 16], tail[8], head[12];
    uint64_t h = 14695981039346656037ull;
    size_t n, total = 0, have = 0;
    /* hash every byte but the last 8, which are kept back until the end */
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) {
        for (size_t i = 0; i < n; i++, total++) {
            if (total < 12) head[total] = buf[i];
            if (have == 8) { h ^= tail[0]; h *= 1099511628211ull; memmove(tail, tail + 1, 7); have = 7; }
            tail[have++] = buf[i];
        }
    }
    fclose(f);
    uint32_t ver = 0;
    if (total >= 12) memcpy(&ver, head + 8, 4);
    if (total < 20 || memcmp(head, "CSHYWGTS", 8)) { snprintf(why, wn, "not a weights file (magic)"); return 0; }
    if (ver != 1) { snprintf(why, wn, "weights format version %u, expected 1", ver); return 0; }
    uint64_t sum = 0;
    for (int i = 7; i >= 0; i--) sum = (sum << 8) | tail[i]; /* little-endian */
    if (sum != h) { snprintf(why, wn, "checksum seal broken (corrupt or tampered)"); return 0; }
    return 1;
}

void audit_evidence(const claims *c, checklist *cl)
{
    paths_list l = {0};
    paths_list_files(PATHS_FROZEN_DIR, "", 1, &l);
    size_t bad = 0, named = 0, seals = 0;
    for (size_t i = 0; i < l.n; i++) {
        size_t n = strlen(l.p[i]);
        if (n > 4 && !strcmp(l.p[i] + n - 4, ".tsv")) bad += check_named_files(c, l.p[i], cl, &named);
        if (n > 5 && !strcmp(l.p[i] + n - 5, ".ckpt")) {
            char why[128];
            if (!weights_sealed(l.p[i], why, sizeof why)) {
                char affected[600];
                audit_feeds(c, l.p[i], affected, sizeof affected);
                checklist_add(cl, VERDICT_FAIL, "weights seals", "%s: %s; claims affected: %s", l.p[i], why, affected);
                bad++;
            } else seals++;
        }
    }
    paths_list_free(&l);
    double seeds = 0;
    char msg[2048];
    int nw1 = 0;
    cs_status st = gate_read_value(PATHS_GATE("main"), "seeds", 0, &seeds);
    if (!st) st = claim_main_samples_check(PATHS_PAIR_16_STANDS_DIR, (int)seeds, msg, sizeof msg, &nw1);
    else snprintf(msg, sizeof msg, "%s", cs_errmsg());
    if (st) {
        char affected[600], table[1024];
        snprintf(table, sizeof table, "%.*s", (int)strcspn(msg, ":"), msg);
        audit_feeds(c, table, affected, sizeof affected);
        checklist_add(cl, VERDICT_FAIL, "W1 from samples", "%s; claims affected: %s", msg, affected);
        bad++;
    }
    if (!bad)
        checklist_add(cl, VERDICT_PASS, "evidence",
                      "%zu files named by provenance exist with their hashes; %zu weights files sealed; %d W1 "
                      "recomputed from their samples, bit for bit",
                      named, seals, nw1);
}

/* ---- git: the preregistration commit and the past versions of a file ---- */

static int have_git(void)
{
    struct stat sb;
    return stat(".git", &sb) == 0 && system("git rev-parse --git-dir >/dev/null 2>&1") == 0;
}




/* sha256 of `git show REV:PATH`, or of its TEACHER_VERSION string (version = 1). */
static int git_blob_value(const char *rev, const char *path, int version, char *out, size_t n)
{
    char cmd[700];
    snprintf(cmd, sizeof cmd, "git show '%s:%s' 2>/dev/null", rev, path);
    FILE *p = popen(cmd, "r");
    if (!p) return 1;
    size_t len = 0, cap = 1 << 16;
    char *buf = malloc(cap);
    for (size_t k; buf && (k = fread(buf + len, 1, cap - len - 1, p)) > 0;) {
        len += k;
        if (len + 1 == cap) { char *nb = realloc(buf, cap *= 2); if (!nb) { free(buf); buf = NULL; } else buf = nb; }
    }
    int rc = pclose(p);
    if (!buf || rc != 0) { free(buf); return 1; }
    buf[len] = '\0';
    if (!version) {
        char hex[65];
        sha256_hex(buf, len, hex);
        snprintf(out, n, "%s", hex);
    } else {
        char *d = strstr(buf, "#define TEACHER_VERSION \"");
        if (d) snprintf(out, n, "%.*s", (int)strcspn(d + 25, "\""), d + 25);
        else out[0] = '\0';
    }
    free(buf);
    return !out[0];
}

/* Is value a past value of path in one listing of its history? */
static int git_past_value_in(const char *how, const char *path, int version, const char *value, char *commit, size_t cn)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "git log %s --format='C %%H' --name-only -- '%s' 2>/dev/null", how, path);
    FILE *p = popen(cmd, "r");
    if (!p) return 0;
    char line[600], rev[64] = "", v[80];
    int found = 0;
    while (!found && fgets(line, sizeof line, p)) {
        line[strcspn(line, "\n")] = '\0';
        if (!strncmp(line, "C ", 2)) {
            snprintf(rev, sizeof rev, "%.63s", line + 2);
            /* without --follow the path is the same at every commit, merges included
             * (git prints no name for a merge) */
            if (strcmp(how, "--follow") && !git_blob_value(rev, path, version, v, sizeof v) && !strcmp(v, value)) {
                found = 1;
                snprintf(commit, cn, "%.12s", rev);
            }
            continue;
        }
        if (strcmp(how, "--follow")) continue;
        if (!line[0] || !rev[0]) continue;
        if (!git_blob_value(rev, line, version, v, sizeof v) && !strcmp(v, value)) {
            found = 1;
            snprintf(commit, cn, "%.12s", rev);
        }
    }
    while (fgets(line, sizeof line, p)) {}
    pclose(p);
    return found;
}

/* Is value a past value of path: any committed version, merges included
 * (--full-history), and under earlier names (--follow, which skips merges)? */
static int git_past_value(const char *path, int version, const char *value, char *commit, size_t cn)
{
    return git_past_value_in("--full-history", path, version, value, commit, cn) ||
           git_past_value_in("--follow", path, version, value, commit, cn);
}

/* ---- the gates against their preregistered content ---- */

/* The pinned copy: hex of every gate file; n entries. */
static size_t prereg_copy(char (*path)[128], char (*hex)[65], size_t cap, int *ok)
{
    FILE *f = fopen(PATHS_GATES_PREREG, "r");
    size_t n = 0;
    *ok = f != NULL;
    char line[512];
    while (f && n < cap && fgets(line, sizeof line, f)) {
        if (line[0] == '#') continue;
        if (sscanf(line, "%64s  %127s", hex[n], path[n]) == 2 && strlen(hex[n]) == 64) n++;
        else *ok = 0;
    }
    if (f) fclose(f);
    return n;
}

void audit_gates_prereg(const claims *c, checklist *cl)
{
    static char ppath[64][128], phex[64][65];
    int ok;
    size_t np = prereg_copy(ppath, phex, 64, &ok), bad = 0;
    if (!ok || !np) {
        checklist_add(
            cl, VERDICT_FAIL, "gates preregistered",
            "%s: missing or malformed (the pinned copy of the preregistered gates' hashes); every gated claim affected",
            PATHS_GATES_PREREG);
        return;
    }
    char base[64] = "";
    const int state = audit_prereg_state(base, sizeof base);
    int git = state == PREREG_ANCESTOR;
    if (state == PREREG_NOT_ANCESTOR) {
        checklist_add(cl, VERDICT_FAIL, "gates preregistered",
                      "the preregistration commit %s pinned in %s is not an ancestor of HEAD (a rewritten or grafted "
                      "history); every gated claim affected",
                      base, PATHS_GATES_PREREG);
        bad++;
    }
    paths_list g = {0};
    paths_list_every(PATHS_GATES_DIR, 1, &g);
    for (size_t i = 0; i < g.n; i++) {
        char cur[65] = "", then[80] = "", affected[600];
        const char *b = strrchr(g.p[i], '/') ? strrchr(g.p[i], '/') + 1 : g.p[i];
        size_t k = 0;
        while (k < np && strcmp(ppath[k], g.p[i])) k++;
        struct stat sb;
        int reg = lstat(g.p[i], &sb) == 0 && S_ISREG(sb.st_mode);
        if (reg) prov_sha256_file(g.p[i], cur);
        int in_git = git && !git_blob_value(base, g.p[i], 0, then, sizeof then);
        const char *why = !reg                   ? "is not a regular file"
                          : k == np              ? "is not among the preregistered gates"
                          : strcmp(cur, phex[k]) ? "differs from its pinned preregistered hash"
                                                 : NULL;
        if (!why && git && !in_git) why = "was not added at the preregistration commit";
        if (!why && in_git && strcmp(cur, then)) why = "differs from its content at the preregistration commit";
        if (!why && in_git && strcmp(then, phex[k]))
            why = "is pinned in " PATHS_GATES_PREREG " with a hash its preregistered content does not have";
        if (!why) continue;
        snprintf(affected, sizeof affected, "(no claim)");
        size_t off = 0, cnt = 0;
        for (size_t r = 0; r < c->n && off < sizeof affected - 80; r++)
            if (!strncmp(c->rows[r].gate, b, strlen(b)) && c->rows[r].gate[strlen(b)] == ':')
                off += (size_t)snprintf(affected + off, sizeof affected - off, "%s%s", cnt++ ? ", " : "",
                                        c->rows[r].macro);
        checklist_add(cl, VERDICT_FAIL, "gates preregistered",
                      "%s %s (%s%s%s): a preregistered threshold is never changed; claims affected: %s", g.p[i], why,
                      git ? "preregistration commit " : "no .git: checked against ", git ? base : PATHS_GATES_PREREG,
                      git ? ", " PATHS_GATES_PREREG : "", affected);
        bad++;
    }
    for (size_t k = 0; k < np; k++) {
        int found = 0;
        for (size_t i = 0; i < g.n && !found; i++) found = !strcmp(g.p[i], ppath[k]);
        if (!found) {
            checklist_add(cl, VERDICT_FAIL, "gates preregistered", "%s is missing (preregistered, %s)", ppath[k],
                          PATHS_GATES_PREREG);
            bad++;
        }
    }
    paths_list_free(&g);
    if (!bad)
        checklist_add(cl, VERDICT_PASS, "gates preregistered", "%zu gate files byte-identical to %s%s", np,
                      git ? "their content at the preregistration commit "
                          : "their pinned preregistered hashes (no .git) in ",
                      git ? base : PATHS_GATES_PREREG);
}

/* Does this history hold the preregistration commit recorded in the pinned
 * copy of the gates' hashes? A fresh or shallow history does not: its past
 * versions cannot show what the package's history would. */
static int history_has_prereg(void)
{
    char c[64];
    return audit_prereg_state(c, sizeof c) == PREREG_ANCESTOR;
}

/* ---- superseded pins: real past values ---- */

void audit_superseded_real(checklist *cl)
{
    tsv *t;
    if (tsv_read(PATHS_PINS_SUPERSEDED, &t)) {
        checklist_add(cl, VERDICT_FAIL, "superseded pins", "%s", cs_errmsg());
        return;
    }
    int git = have_git(), full = git && history_has_prereg();
    size_t bad = 0, n = tsv_nrows(t);
    for (size_t r = 0; r < n; r++) {
        const char *k = tsv_str(t, r, "key"), *v = tsv_str(t, r, "value"), *p = tsv_str(t, r, "path");
        if (!k || !v || !p) {
            checklist_add(cl, VERDICT_FAIL, "superseded pins", "%s:%d: fields 'key', 'value', 'path' required",
                          PATHS_PINS_SUPERSEDED, tsv_line(t, r));
            bad++;
            continue;
        }
        int version = !strcmp(k, "teacher_version");
        if (!version && strcmp(k, "teacher_sha256") && strcmp(k, "estimator_sha256")) {
            checklist_add(
                cl, VERDICT_FAIL, "superseded pins",
                "%s:%d: field 'key': '%s' is not a reading's pin (teacher_version, teacher_sha256, estimator_sha256)",
                PATHS_PINS_SUPERSEDED, tsv_line(t, r), k);
            bad++;
            continue;
        }
        char commit[16];
        if (full && !git_past_value(p, version, v, commit, sizeof commit)) {
            checklist_add(cl, VERDICT_FAIL, "superseded pins",
                          "%s:%d: %s %.16s… is no past version of %s in the history (made up?); tables naming it are "
                          "not traceable",
                          PATHS_PINS_SUPERSEDED, tsv_line(t, r), k, v, p);
            bad++;
        }
    }
    tsv_free(t);
    if (!bad)
        checklist_add(cl, VERDICT_PASS, "superseded pins", "%zu superseded pins%s", n,
                      full  ? ", each a real past version of its file in the history"
                      : git ? " (this history lacks the preregistration commit of " PATHS_GATES_PREREG
                              ": each rests on the pin of " PATHS_PINS_SUPERSEDED " in " PATHS_PINS ")"
                            : " (no .git: each rests on the pin of " PATHS_PINS_SUPERSEDED " in " PATHS_PINS ")");
}

/* The first value of "# key: value" at the top of path into out; 1 if found. */
static int header_value(FILE *f, const char *key, char *out, size_t n)
{
    rewind(f);
    char line[2048];
    size_t kl = strlen(key);
    while (fgets(line, sizeof line, f) && line[0] == '#')
        if (!strncmp(line + 2, key, kl) && line[2 + kl] == ':') {
            snprintf(out, n, "%.*s", (int)strcspn(line + 4 + kl, "\n"), line + 4 + kl);
            return 1;
        }
    return 0;
}

int audit_table_superseded(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    tsv *pins = NULL, *sup = NULL;
    int hit = 0;
    if (!tsv_read(PATHS_PINS, &pins) && !tsv_read(PATHS_PINS_SUPERSEDED, &sup)) {
        const char *keys[] = {"teacher_version", "teacher_sha256", "estimator_sha256"};
        for (int k = 0; k < 3 && !hit; k++) {
            char v[128];
            if (!header_value(f, keys[k], v, sizeof v)) continue;
            long cur = tsv_find(pins, "key", keys[k]);
            if (cur >= 0 && !strcmp(tsv_str(pins, (size_t)cur, "value"), v)) continue;
            for (size_t r = 0; r < tsv_nrows(sup) && !hit; r++)
                hit = !strcmp(tsv_str(sup, r, "key"), keys[k]) && !strcmp(tsv_str(sup, r, "value"), v);
        }
    }
    if (pins) tsv_free(pins);
    if (sup) tsv_free(sup);
    fclose(f);
    return hit;
}

/* ---- the preregistration anchored outside the repository ---- */

/* The gates' hash CITATION.cff publishes ("value: sha256:HEX" of the
 * identifier described as the preregistered gates); 0 when found. */
static int citation_gates_hash(char hex[65])
{
    FILE *f = fopen(PATHS_CITATION, "r");
    char line[512];
    int found = 0;
    while (f && !found && fgets(line, sizeof line, f)) {
        const char *v = strstr(line, "sha256:");
        if (v && strstr(line, "value:") && sscanf(v + 7, "%64[0-9a-f]", hex) == 1 && strlen(hex) == 64) found = 1;
    }
    if (f) fclose(f);
    return !found;
}

void audit_prereg_anchor(checklist *cl, const char *brought, char *line, size_t n)
{
    char now[65], pub[65], base[64];
    if (prov_gates_sha256(PATHS_GATES_DIR, now)) {
        checklist_add(cl, VERDICT_FAIL, "preregistration", "%s: %s", PATHS_GATES_DIR, cs_errmsg());
        snprintf(line, n, "preregistration: gates unreadable");
        return;
    }
    if (citation_gates_hash(pub))
        checklist_add(cl, VERDICT_FAIL, "preregistration",
                      "%s publishes no sha256 of the preregistered gates (an identifier 'value: sha256:<hex>'); every "
                      "gated claim affected",
                      PATHS_CITATION);
    else if (strcmp(pub, now))
        checklist_add(cl, VERDICT_FAIL, "preregistration",
                      "%s publishes the gates' sha256 %.16s..., but %s hashes to %.16s...; every gated claim affected",
                      PATHS_CITATION, pub, PATHS_GATES_DIR, now);
    else
        checklist_add(cl, VERDICT_PASS, "preregistration", "%s publishes the sha256 of %s (%.16s...)", PATHS_CITATION,
                      PATHS_GATES_DIR, now);
    if (brought && brought[0]) {
        if (strcmp(brought, now)) {
            checklist_add(cl, VERDICT_FAIL, "preregistration",
                          "%s hashes to %s, not to the preregistration hash you brought (PREREG=%s): a preregistered "
                          "threshold changed; every gated claim affected",
                          PATHS_GATES_DIR, now, brought);
            snprintf(line, n, "preregistration: %s DIFFER from the hash you brought (PREREG=%.16s...)", PATHS_GATES_DIR,
                     brought);
        } else {
            checklist_add(cl, VERDICT_PASS, "preregistration",
                          "%s equals the preregistration hash you brought (PREREG=%.16s...)", PATHS_GATES_DIR, brought);
            snprintf(line, n,
                     "preregistration: checked against the hash you brought (PREREG=%.16s...): the gates are the "
                     "preregistered ones",
                     brought);
        }
        return;
    }
    const int state = audit_prereg_state(base, sizeof base);
    snprintf(
        line, n,
        "preregistration: self-attested (%s; an author who rewrites the gates, their pinned hashes and the history "
        "passes this): bring the gates' sha256 from a copy you trust (CITATION.cff, the write-up's first page) as make "
        "verify PREREG=<sha256>",
        state == PREREG_ANCESTOR
            ? "the gates equal their content at the pinned preregistration commit, an ancestor of HEAD"
        : state == PREREG_NO_GIT
            ? "no .git: the gates equal their pinned hashes"
            : "the gates equal their pinned hashes; this history lacks the pinned preregistration commit");
}
