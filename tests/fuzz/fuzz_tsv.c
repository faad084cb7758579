/* libFuzzer harness: frozen-table reader (src/base/tsv.c). Any input must give
 * CS_OK or a clean error, never a crash; every cell of an accepted table is read. */
#include "fuzz_common.h"
#include "tsv.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    tsv *t;
    if (tsv_read(fuzz_file(data, size, ".tsv"), &t) != CS_OK) return 0;
    for (size_t r = 0; r < tsv_nrows(t); r++)
        for (size_t c = 0; c < tsv_ncols(t); c++) {
            double v;
            long l;
            (void)tsv_double(t, r, tsv_colname(t, c), &v);
            (void)tsv_long(t, r, tsv_colname(t, c), &l);
        }
    (void)tsv_meta(t, "experiment");
    tsv_free(t);
    return 0;
}
