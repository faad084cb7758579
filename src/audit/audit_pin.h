/* audit_pin: the pins of the instrument (design.md §9): every hash and
 * version a verdict rests on, as the sources are now, and `crownshy pin`,
 * which writes them to audit/pins.tsv with the record of superseded
 * readings. Nothing here judges: audit.c compares these pins with the
 * pinned ones and the frozen provenance. */
#ifndef AUDIT_PIN_H
#define AUDIT_PIN_H
#include "cs.h"
#include "tsv.h"
#include <stddef.h>

/* The instrument's pins grow with the registry (one per claim row): a set
 * that grows, never one that silently drops its tail. */
typedef struct { char key[64], value[80], path[256]; } pin;
typedef struct { pin *p; size_t n, cap; int oom; } pinset;

/* Every pin of the instrument as it is now, into an empty set *s (freed by
 * the caller with audit_pin_free, also on failure); CS_ENOMEM when a pin
 * could not be kept. */
cs_status audit_pin_current(pinset *s);
void audit_pin_free(pinset *s);
/* Line of (key, value) in the superseded pins t (may be NULL), 0 if absent. */
int audit_pin_superseded_line(const tsv *t, const char *key, const char *value);
/* Rewrite audit/pins.tsv from the current sources (a deliberate act: after it,
 * frozen/ must be regenerated, or the provenance check fails). */
cs_status audit_pin(void);

#endif
