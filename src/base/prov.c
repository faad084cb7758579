/* prov: the provenance block of every frozen TSV (design.md §9). Source hashes are
 * computed from the files at run time (paths relative to the repository root,
 * the working directory of every make target). */
#include "prov.h"
#include "sha256.h"
#include "paths.h"
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

double prov_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void prov_begin(prov *p, const char *experiment, int argc, char **argv)
{
    memset(p, 0, sizeof *p);
    snprintf(p->experiment, sizeof p->experiment, "%s", experiment);
    size_t off = 0;
    off += (size_t)snprintf(p->command, sizeof p->command, "crownshy");
    /* argv[0] is the subcommand name (the CLI passes argv + 1) */
    for (int i = 0; i < argc && off < sizeof p->command; i++)
        off += (size_t)snprintf(p->command + off, sizeof p->command - off, " %s", argv[i]);
    p->worst_overlap_m = -1.0;
    if (prov_teacher_version(p->teacher_version, sizeof p->teacher_version))
        snprintf(p->teacher_version, sizeof p->teacher_version, "absent");
    p->t0 = prov_now();
}

static cs_status header_define(const char *name, char *out, size_t n);
cs_status prov_teacher_version(char *out, size_t n) { return header_define("TEACHER_VERSION", out, n); }
cs_status prov_teacher_version_one_sided(char *out, size_t n)
{
    return header_define("TEACHER_VERSION_ONE_SIDED", out, n);
}

static cs_status header_define(const char *name, char *out, size_t n)
{
    FILE *f = fopen(PATHS_TEACHER_HDR, "r");
    if (!f) return cs_err(CS_EINPUT, "%s: cannot open: %s", PATHS_TEACHER_HDR, strerror(errno));
    char line[512];
    int lineno = 0;
    cs_status st = cs_err(CS_EINPUT, "%s: no '#define %s \"...\"' line", PATHS_TEACHER_HDR, name);
    size_t nl = strlen(name);
    while (fgets(line, sizeof line, f)) {
        lineno++;
        const char *q = line;
        if (strncmp(q, "#define ", 8) || strncmp(q + 8, name, nl) || !isspace((unsigned char)q[8 + nl])) continue;
        q += 8 + nl;
        while (isspace((unsigned char)*q)) q++;
        const char *e = *q == '"' ? strchr(q + 1, '"') : NULL;
        if (!e || e - q - 1 <= 0 || (size_t)(e - q - 1) >= n) {
            st = cs_err(CS_EINPUT, "%s:%d: field '%s': not a quoted version string", PATHS_TEACHER_HDR, lineno, name);
            break;
        }
        snprintf(out, n, "%.*s", (int)(e - q - 1), q + 1);
        st = CS_OK;
        break;
    }
    fclose(f);
    return st;
}

static cs_status hash_into(sha256_ctx *c, const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return cs_err(CS_EINPUT, "%s: cannot open for hashing: %s", path, strerror(errno));
    char buf[65536];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) sha256_update(c, buf, n);
    int bad = ferror(f);
    fclose(f);
    return bad ? cs_err(CS_EINPUT, "%s: read error while hashing", path) : CS_OK;
}

cs_status prov_sha256_file(const char *path, char hex[65])
{
    sha256_ctx c;
    uint8_t d[32];
    sha256_init(&c);
    cs_status st = hash_into(&c, path);
    if (st) return st;
    sha256_final(&c, d);
    sha256_tohex(d, hex);
    return CS_OK;
}

cs_status prov_gates_sha256(const char *dir, char hex[65])
{
    paths_list l;
    cs_status st = paths_list_files(dir, ".gate", 0, &l);
    if (st) return st;
    size_t n = l.n;
    sha256_ctx c;
    sha256_init(&c);
    for (size_t i = 0; i < n && !st; i++) {
        /* the name is part of the hash: renaming a gate is a change */
        const char *name = l.p[i] + strlen(dir) + 1;
        sha256_update(&c, name, strlen(name) + 1);
        st = hash_into(&c, l.p[i]);
    }
    paths_list_free(&l);
    if (st) return st;
    if (n == 0) return cs_err(CS_EINPUT, "%s: no .gate files", dir);
    uint8_t dg[32];
    sha256_final(&c, dg);
    sha256_tohex(dg, hex);
    return CS_OK;
}

static void git_commit(char *out, size_t n)
{
    snprintf(out, n, "unknown");
    FILE *p = popen("git rev-parse HEAD 2>/dev/null", "r");
    if (!p) return;
    char buf[128] = {0};
    if (fgets(buf, sizeof buf, p)) {
        buf[strcspn(buf, "\n")] = '\0';
        if (buf[0]) snprintf(out, n, "%s", buf);
    }
    pclose(p);
    /* uncommitted source changes make the commit an incomplete description */
    p = popen("git status --porcelain -- src gates Makefile 2>/dev/null", "r");
    if (!p) return;
    if (fgets(buf, sizeof buf, p) && buf[0]) {
        size_t l = strlen(out);
        snprintf(out + l, n - l, "-dirty");
    }
    pclose(p);
}

cs_status prov_write(tsv_writer *w, prov *p)
{
    char th[65] = "absent", eh[65] = "absent", gh[65];
    cs_status st;
    FILE *f;
    if ((f = fopen(PATHS_TEACHER_SRC, "rb"))) {
        fclose(f);
        if ((st = prov_sha256_file(PATHS_TEACHER_SRC, th))) return st;
    }
    if ((f = fopen(PATHS_ESTIMATOR_SRC, "rb"))) {
        fclose(f);
        if ((st = prov_sha256_file(PATHS_ESTIMATOR_SRC, eh))) return st;
    }
    if ((st = prov_gates_sha256(PATHS_GATES_DIR, gh))) return st;
    char commit[160];
    git_commit(commit, sizeof commit);
    time_t now = time(NULL);
    struct tm tm;
    gmtime_r(&now, &tm);
    char date[32];
    strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &tm);
    p->wall_s = prov_now() - p->t0;
    tsv_writer_meta(w, "experiment", "%s", p->experiment);
    tsv_writer_meta(w, "command", "%s", p->command);
    tsv_writer_meta(w, "teacher_version", "%s", p->teacher_version);
    tsv_writer_meta(w, "teacher_sha256", "%s", th);
    tsv_writer_meta(w, "estimator_sha256", "%s", eh);
    tsv_writer_meta(w, "gates_sha256", "%s", gh);
    tsv_writer_meta(w, "git_commit", "%s", commit);
    tsv_writer_meta(w, "seeds", "%s", p->seeds[0] ? p->seeds : "-");
    tsv_writer_meta(w, "date", "%s", date);
    tsv_writer_meta(w, "wall_s", "%.3f", p->wall_s);
    if (p->worst_overlap_m >= 0) tsv_writer_meta(w, "worst_overlap_m", "%.17g", p->worst_overlap_m);
    else tsv_writer_meta(w, "worst_overlap_m", "n/a");
    return CS_OK;
}

int prov_reading_version(const char *v, const char *base)
{
    size_t l = strlen(base);
    if (strncmp(v, base, l)) return 0;
    return !v[l] || !strcmp(v + l, "-arc") || !strcmp(v + l, "-target");
}

int prov_reading_key(const char *key)
{
    return !strcmp(key, "teacher_version") || !strcmp(key, "teacher_sha256") || !strcmp(key, "estimator_sha256");
}
