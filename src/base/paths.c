/* paths: see paths.h. */
#include "paths.h"
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

void paths_list_free(paths_list *l)
{
    for (size_t i = 0; i < l->n; i++) free(l->p[i]);
    free(l->p);
    memset(l, 0, sizeof *l);
}

cs_status paths_list_add(paths_list *l, const char *s)
{
    if (l->n == l->cap) {
        size_t nc = l->cap ? 2 * l->cap : 64;
        char **np = realloc(l->p, nc * sizeof *np);
        if (!np) return cs_err(CS_ENOMEM, "paths: out of memory");
        l->p = np;
        l->cap = nc;
    }
    if (!(l->p[l->n] = strdup(s))) return cs_err(CS_ENOMEM, "paths: out of memory");
    l->n++;
    return CS_OK;
}

static int ends_with(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    return a >= b && !strcmp(s + a - b, suffix);
}

static cs_status walk(const char *dir, const char *suffix, int recursive, int all, paths_list *out)
{
    DIR *d = opendir(dir);
    if (!d) return CS_OK;
    cs_status st = CS_OK;
    struct dirent *e;
    while (!st && (e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
        if (!all && (e->d_name[0] == '.' || strstr(e->d_name, ".tmp"))) continue;
        char p[1024];
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        struct stat sb;
        if (lstat(p, &sb) != 0) continue; /* a symlink is listed (all) as itself, never followed */
        if (S_ISDIR(sb.st_mode)) { if (recursive) st = walk(p, suffix, recursive, all, out); }
        else if ((S_ISREG(sb.st_mode) || all) && ends_with(e->d_name, suffix)) st = paths_list_add(out, p);
    }
    closedir(d);
    return st;
}

static int cmp(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

static cs_status list(const char *dir, const char *suffix, int recursive, int all, paths_list *out)
{
    memset(out, 0, sizeof *out);
    cs_status st = walk(dir, suffix ? suffix : "", recursive, all, out);
    if (st) { paths_list_free(out); return st; }
    if (out->n) qsort(out->p, out->n, sizeof *out->p, cmp);
    return CS_OK;
}

cs_status paths_list_files(const char *dir, const char *suffix, int recursive, paths_list *out)
{
    return list(dir, suffix, recursive, 0, out);
}

cs_status paths_list_every(const char *dir, int recursive, paths_list *out)
{
    return list(dir, "", recursive, 1, out);
}

int paths_is_hidden_or_tmp(const char *path)
{
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    return b[0] == '.' || strstr(b, ".tmp") != NULL;
}

int paths_recorded(const char *path, char *out, size_t n)
{
    static const struct { const char *named, *now; } moved[] = PATHS_FROZEN_RECORDED;
    char norm[1024] = "";
    size_t len = 0;
    const char *p = path;
    while (*p) {
        size_t k = strcspn(p, "/");
        if (k == 2 && !strncmp(p, "..", 2) && len) {
            char *cut = strrchr(norm, '/');
            len = cut ? (size_t)(cut - norm) : 0;
            norm[len] = '\0';
        } else if (k && !(k == 1 && p[0] == '.') && len + k + 2 < sizeof norm) {
            len += (size_t)snprintf(norm + len, sizeof norm - len, "%s%.*s", len ? "/" : "", (int)k, p);
        }
        p += k + (p[k] == '/');
    }
    for (size_t i = 0; i < sizeof moved / sizeof *moved; i++) {
        size_t m = strlen(moved[i].named);
        if (!strncmp(norm, moved[i].named, m)) {
            snprintf(out, n, "%s%s", moved[i].now, norm + m);
            return 1;
        }
    }
    snprintf(out, n, "%s", path);
    return 0;
}

cs_status paths_input_file(const char *path)
{
    struct stat sb;
    if (stat(path, &sb) != 0) return cs_err(CS_EINPUT, "%s: cannot open: %s", path, strerror(errno));
    if (S_ISDIR(sb.st_mode)) return cs_err(CS_EINPUT, "%s: is a directory, not an input file", path);
    if (!S_ISREG(sb.st_mode)) return cs_err(CS_EINPUT, "%s: not a regular file", path);
    return CS_OK;
}
