/* claim_field: E5 claim functions shared with the E6 claims (the held-out
 * spread ratio is the same computation on another frozen table). */
#ifndef CLAIM_FIELD_H
#define CLAIM_FIELD_H
#include "claims.h"

/* Simulated coupled spread of row->source / field spread (FIELD_TABLE);
 * gate IN the row's band; PENDING with the reason without the table. */
cs_status claim_field_spread_ratio(const claim_row *row, claim_result *res);

#endif
