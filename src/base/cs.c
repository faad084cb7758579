/* cs: status codes, the last-error message and a non-aborting GSL error handler.
 * The message buffer is per process (the library is single-threaded by design:
 * parallelism comes from make -j running one process per unit, design.md §1). */
#include "cs.h"
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <gsl/gsl_errno.h>

static char cs_msg[2048];

/* how many out-of-memory errors were raised: a run that met one cannot vouch for its checks */
static size_t cs_nomem;

cs_status cs_err(cs_status st, const char *fmt, ...)
{
    /* formatted apart first: a caller may wrap the previous message
     * (cs_err(st, "%s ...", cs_errmsg())), whose text lives in cs_msg */
    char buf[sizeof cs_msg];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    memcpy(cs_msg, buf, sizeof cs_msg);
    if (st == CS_ENOMEM) cs_nomem++;
    return st;
}

size_t cs_nomem_count(void) { return cs_nomem; }

const char *cs_errmsg(void) { return cs_msg; }
void cs_errclear(void) { cs_msg[0] = '\0'; }

int cs_exit_code(cs_status st)
{
    switch (st) {
    case CS_OK: return 0;
    case CS_EFAIL: return 1;
    case CS_EUSAGE: return 2;
    case CS_EINPUT: return 3;
    default: return 4;
    }
}

const char *cs_status_name(cs_status st)
{
    switch (st) {
    case CS_OK: return "ok";
    case CS_EFAIL: return "failed";
    case CS_EUSAGE: return "usage error";
    case CS_EINPUT: return "bad input";
    case CS_ENOMEM: return "out of memory";
    case CS_ENUMERIC: return "numerical error";
    case CS_EIO: return "i/o error";
    case CS_EINVARIANT: return "invariant violated";
    }
    return "unknown";
}

static void cs_gsl_handler(const char *reason, const char *file, int line, int gsl_errno)
{
    cs_err(CS_ENUMERIC, "GSL error %d (%s) at %s:%d: %s", gsl_errno,
           gsl_strerror(gsl_errno), file, line, reason);
}

void cs_gsl_install(void) { gsl_set_error_handler(cs_gsl_handler); }
