/* seed: FNV-1a + splitmix64 over a canonical key string (see seed.h, design.md §1). */
#include "seed.h"
#include <stdio.h>

static uint64_t seed_splitmix64(uint64_t z)
{
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

uint64_t seed_derive(const char *experiment, double spacing, unsigned stand, const char *stream)
{
    char key[512];
    /* %.3f: spacings are given to the millimetre; 3.5 and 3.5000001 are one key. */
    snprintf(key, sizeof key, "crownshy|%s|%.3f|%u|%s", experiment ? experiment : "",
             spacing, stand, stream ? stream : "");
    uint64_t h = 0xcbf29ce484222325ULL;
    for (const unsigned char *p = (const unsigned char *)key; *p; p++) {
        h ^= *p;
        h *= 0x100000001b3ULL;
    }
    return seed_splitmix64(h);
}

unsigned long seed_mt(uint64_t seed)
{
    unsigned long s = (unsigned long)((seed ^ (seed >> 32)) & 0xffffffffULL);
    return s ? s : 1UL;
}
