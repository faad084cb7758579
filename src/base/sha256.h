/* sha256: FIPS 180-4 SHA-256, used to pin the estimator source, the teacher
 * source, the gates and the frozen files (design.md §9). Streaming interface. */
#ifndef SHA256_H
#define SHA256_H
#include <stddef.h>
#include <stdint.h>

typedef struct { uint32_t h[8]; uint64_t len; uint8_t buf[64]; size_t nbuf; } sha256_ctx;

void sha256_init(sha256_ctx *c);
void sha256_update(sha256_ctx *c, const void *data, size_t n);
void sha256_final(sha256_ctx *c, uint8_t out[32]);
/* Digest of a buffer as 64 lowercase hex chars + NUL. */
void sha256_hex(const void *data, size_t n, char hex[65]);
void sha256_tohex(const uint8_t d[32], char hex[65]);

#endif
