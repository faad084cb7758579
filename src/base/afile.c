/* afile: atomic file writes (see afile.h). */
#include "afile.h"
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

cs_status afile_mkdir_parents(const char *path)
{
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", path);
    for (char *s = buf + 1; *s; s++) {
        if (*s != '/') continue;
        *s = '\0';
        if (mkdir(buf, 0777) != 0 && errno != EEXIST)
            return cs_err(CS_EIO, "%s: cannot create parent directory: %s", path, strerror(errno));
        *s = '/';
    }
    return CS_OK;
}

static void release(afile *a)
{
    free(a->path);
    free(a->tmp);
    a->path = a->tmp = NULL;
    a->f = NULL;
}

cs_status afile_open(afile *a, const char *path)
{
    memset(a, 0, sizeof *a);
    cs_status st = afile_mkdir_parents(path);
    if (st) return st;
    a->path = strdup(path);
    a->tmp = malloc(strlen(path) + 48);
    if (!a->path || !a->tmp) { release(a); return cs_err(CS_ENOMEM, "%s: out of memory", path); }
    /* unique per process and call: two concurrent writers of one path (two
     * audits, two verifies) never share a temp file; "x" refuses a leftover */
    static unsigned long serial;
    sprintf(a->tmp, "%s.tmp.%ld.%lu", path, (long)getpid(), ++serial);
    int fd = open(a->tmp, O_WRONLY | O_CREAT | O_EXCL, 0666);
    a->f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (fd >= 0 && !a->f) { close(fd); unlink(a->tmp); }
    if (!a->f) {
        st = cs_err(CS_EIO, "%s: cannot write: %s", a->tmp, strerror(errno));
        release(a);
    }
    return st;
}

cs_status afile_commit(afile *a)
{
    cs_status st = CS_OK;
    if (ferror(a->f) || fflush(a->f) != 0 || fsync(fileno(a->f)) != 0) a->err = 1;
    if (fclose(a->f) != 0) a->err = 1;
    if (a->err) {
        st = cs_err(CS_EIO, "%s: write failed", a->tmp);
        unlink(a->tmp);
    } else if (rename(a->tmp, a->path) != 0) {
        st = cs_err(CS_EIO, "%s: cannot rename to %s: %s", a->tmp, a->path, strerror(errno));
        unlink(a->tmp);
    }
    release(a);
    return st;
}

void afile_abort(afile *a)
{
    fclose(a->f);
    unlink(a->tmp);
    release(a);
}

char *afile_read(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 4096, len = 0;
    char *s = malloc(cap);
    size_t k;
    while (s && (k = fread(s + len, 1, cap - len - 1, f)) > 0) {
        len += k;
        if (cap - len < 2) { char *t = realloc(s, cap *= 2); if (!t) { free(s); s = NULL; } else s = t; }
    }
    fclose(f);
    if (s) s[len] = '\0';
    return s;
}
