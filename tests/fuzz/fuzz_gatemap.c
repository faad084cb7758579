/* libFuzzer harness: the claim-to-gate map (audit/gate_map.tsv) parser,
 * src/claims/claims.c claims_apply_gate_map, on a small in-memory registry. */
#include "fuzz_common.h"
#include "claims.h"
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    claim_row rows[3];
    memset(rows, 0, sizeof rows);
    const char *names[3] = {"MainRel", "MainP", "Elong"};
    for (int i = 0; i < 3; i++) {
        strcpy(rows[i].macro, names[i]);
        strcpy(rows[i].gate, "-");
        strcpy(rows[i].gate_reg, "-");
    }
    claims c = {rows, 3};
    (void)claims_apply_gate_map(&c, fuzz_file(data, size, ".tsv"));
    for (int i = 0; i < 3; i++)
        if (strlen(rows[i].gate) >= sizeof rows[i].gate) abort();
    return 0;
}
