/* libFuzzer harness: paper/numbers.tex reader (src/claims/claims.c numbers_read). */
#include "fuzz_common.h"
#include "claims.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    numbers_tex nt;
    if (numbers_read(fuzz_file(data, size, ".tex"), &nt) != CS_OK) return 0;
    (void)numbers_get(&nt, "MainRel", NULL);
    numbers_free(&nt);
    return 0;
}
