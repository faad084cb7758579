/* libFuzzer harness: gate-file parser (src/base/gate.c). */
#include "fuzz_common.h"
#include "gate.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gate *g;
    if (gate_load(fuzz_file(data, size, ".gate"), &g) != CS_OK) return 0;
    double v;
    (void)gate_value(g, "seeds", 0, &v);
    (void)gate_value(g, "spread_ratio_band", 1, &v);
    gate_free(g);
    return 0;
}
