/* checklist: the items of the audit, verify and figures (a verdict, a name
 * and a message naming file and claim), printed in one layout. */
#ifndef CHECKLIST_H
#define CHECKLIST_H
#include "gate.h"
#include <stddef.h>

typedef struct { verdict v; char name[96]; char msg[1024]; } check_item;
typedef struct { check_item *items; size_t n, cap; } checklist;

void checklist_add(checklist *cl, verdict v, const char *name, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
void checklist_free(checklist *cl);
/* Print every item as "  VERDICT  name  message" (the layout of crownshy
 * verify, audit and figures) and add its verdict to count[v] (indexed by
 * verdict: PASS, FAIL, PENDING). */
void checklist_print(const checklist *cl, size_t count[3]);

#endif
