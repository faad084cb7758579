/* seed: the one documented pure function from (experiment, spacing, stand,
 * stream) to an RNG seed (design.md §1). Everything random in the package is
 * seeded through it, never from the clock or the environment.
 *
 * Definition (frozen; changing it changes every result):
 *   key  = "crownshy|<experiment>|<spacing as %.3f>|<stand as %u>|<stream>"
 *   h    = FNV-1a 64 over the bytes of key (offset 0xcbf29ce484222325,
 *          prime 0x100000001b3)
 *   seed = splitmix64 finaliser of h (mixes so that nearby keys give
 *          unrelated seeds).
 * Twins: a coupled stand and its uncoupled twin pass the same key, so they
 * share stems ("stems") and crown draws ("crowns"). Train, eval, calibration
 * and held-out stands use different experiment strings (e.g. "main/train",
 * "main/eval"), so their keys, and hence their draws, are disjoint by
 * construction (up to a 64-bit hash collision). */
#ifndef SEED_H
#define SEED_H
#include <stdint.h>

uint64_t seed_derive(const char *experiment, double spacing, unsigned stand, const char *stream);
/* The seed GSL's mt19937 actually uses is 32 bits: fold the 64-bit seed
 * (xor of halves) so that all of its bits matter; never 0 (GSL maps 0 to 4357). */
unsigned long seed_mt(uint64_t seed);

#endif
