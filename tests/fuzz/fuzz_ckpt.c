/* libFuzzer harness: checkpoint reader (src/model/train.c train_load_model). A
 * truncated, tampered or foreign checkpoint must be rejected cleanly. */
#include "fuzz_common.h"
#include "train.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    model *m = NULL;
    double scale;
    if (train_load_model(fuzz_file(data, size, ".ckpt"), &m, 2, &scale) == CS_OK) model_free(m);
    return 0;
}
