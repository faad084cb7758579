/* afile: atomic file writes (see afile.h). */
#include "afile.h"
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
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

/* the temp files open now, read by the signal handler: a slot holds the
 * afile's own tmp string from open until after its rename or unlink */
static char *volatile live[AFILE_LIVE];

static void watch(char *tmp)
{
    for (int i = 0; i < AFILE_LIVE; i++)
        if (!live[i]) { live[i] = tmp; return; }
}

static void unwatch(const char *tmp)
{
    for (int i = 0; i < AFILE_LIVE; i++)
        if (live[i] == tmp) live[i] = NULL;
}

/* unlink, sigaction and raise are async-signal-safe; the signal stays
 * blocked until the handler returns, then kills with the default action */
static void on_signal(int sig)
{
    int saved = errno;
    for (int i = 0; i < AFILE_LIVE; i++)
        if (live[i]) unlink(live[i]);
    struct sigaction dfl;
    memset(&dfl, 0, sizeof dfl);
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    sigaction(sig, &dfl, NULL);
    raise(sig);
    errno = saved;
}

void afile_remove_on_signal(void)
{
    static const int sigs[] = {SIGTERM, SIGINT, SIGHUP};
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
        struct sigaction old, sa;
        if (sigaction(sigs[i], NULL, &old) != 0 || old.sa_handler == SIG_IGN) continue;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_signal;
        sigemptyset(&sa.sa_mask);
        for (size_t j = 0; j < sizeof sigs / sizeof sigs[0]; j++) sigaddset(&sa.sa_mask, sigs[j]);
        sigaction(sigs[i], &sa, NULL);
    }
}

static void release(afile *a)
{
    if (a->tmp) unwatch(a->tmp);
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
    if (fd >= 0) watch(a->tmp);
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
