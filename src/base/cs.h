/* cs: status codes, the last-error message, and the GSL error handler.
 * Library code returns a cs_status and never exits; only the CLI maps a status
 * to a process exit code (design.md §11: 0 ok, 1 gate/claim failed, 2 usage, 3 bad input). */
#ifndef CS_H
#define CS_H
#include <stddef.h>

typedef enum {
    CS_OK = 0,
    CS_EFAIL = 1,    /* a gate or claim failed (not an error of the program) */
    CS_EUSAGE = 2,   /* bad command line */
    CS_EINPUT = 3,   /* bad, missing, truncated or tampered input file */
    CS_ENOMEM = 4,   /* allocation failed */
    CS_ENUMERIC = 5, /* numerical failure (GSL error, non-finite value) */
    CS_EIO = 6,      /* write or rename failed */
    CS_EINVARIANT = 7 /* a self-check failed (e.g. teacher overlap > 1e-9 m) */
} cs_status;

/* Record a message for the last error (printf-style); returns `st` so a caller
 * can write `return cs_err(CS_EINPUT, "%s:%d: field '%s': ...", ...)`. */
cs_status cs_err(cs_status st, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* The message recorded by the last cs_err (empty string if none). */
const char *cs_errmsg(void);
/* How many CS_ENOMEM errors cs_err has raised in this process. */
size_t cs_nomem_count(void);
void cs_errclear(void);
/* Process exit code for a status (design.md §11). */
int cs_exit_code(cs_status st);
/* Install a GSL error handler that records the error instead of aborting. */
void cs_gsl_install(void);
/* Status name for messages. */
const char *cs_status_name(cs_status st);

#endif
