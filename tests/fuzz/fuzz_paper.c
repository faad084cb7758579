/* libFuzzer harness: the paper-text scanner (src/audit/audit_paper.c
 * paper_scan_file: claim macros, definitions, typed numbers, comments). */
#include "fuzz_common.h"
#include "audit_paper.h"
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    claim_row rows[2];
    memset(rows, 0, sizeof rows);
    strcpy(rows[0].macro, "MainRel");
    strcpy(rows[1].macro, "MechOn");
    claims c = {rows, 2};
    const double vals[3] = {12.345, -0.1828, 1e300};
    const char *const who[3] = {"MainRel", "MechOn", "MainRel"};
    checklist cl = {0};
    size_t used = 0;
    (void)paper_scan_file(fuzz_file(data, size, ".tex"), &c, vals, who, 3, &cl, &used);
    checklist_free(&cl);
    return 0;
}
