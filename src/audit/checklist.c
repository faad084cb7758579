/* checklist: see checklist.h. */
#include "checklist.h"
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void checklist_add(checklist *cl, verdict v, const char *name, const char *fmt, ...)
{
    if (cl->n == cl->cap) {
        size_t nc = cl->cap ? 2 * cl->cap : 64;
        check_item *ni = realloc(cl->items, nc * sizeof *ni);
        if (!ni) return;
        cl->items = ni;
        cl->cap = nc;
    }
    check_item *it = &cl->items[cl->n++];
    it->v = v;
    snprintf(it->name, sizeof it->name, "%s", name);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(it->msg, sizeof it->msg, fmt, ap);
    va_end(ap);
}

void checklist_free(checklist *cl)
{
    free(cl->items);
    memset(cl, 0, sizeof *cl);
}

void checklist_print(const checklist *cl, size_t count[3])
{
    for (size_t i = 0; i < cl->n; i++) {
        printf("  %-7s %-28s %s\n", verdict_name(cl->items[i].v), cl->items[i].name, cl->items[i].msg);
        count[cl->items[i].v]++;
    }
}

