/* libFuzzer harness: the aggregate map (audit/aggregates.tsv) parser,
 * src/audit/audit_data.c aggr_load, and the lineage lookup built on it. */
#include "fuzz_common.h"
#include "audit_data.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    aggr_spec *a;
    size_t n;
    if (aggr_load(fuzz_file(data, size, ".tsv"), &a, &n) != CS_OK) return 0;
    free(a);
    return 0;
}
