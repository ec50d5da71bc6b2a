/*
 * The star catalogue (textures/stars.dat, built by tools/catgen.c):
 * parsing with every field checked, and look-up by Hipparcos number. The
 * stars layer draws it; sky_compute_astronomy places its stars.
 */
#ifndef SKY_CATALOG_H
#define SKY_CATALOG_H

#include "core.h"

typedef struct sky_catalog {
    sky_star *stars; /* sorted by magnitude, brightest first */
    int count;
} sky_catalog;
int sky_catalog_parse(sky_catalog *cat, const unsigned char *data, size_t size, char *err, size_t err_len);
int sky_catalog_load(sky_catalog *cat, char *err, size_t err_len); /* the embedded one */
const sky_star *sky_catalog_find(const sky_catalog *cat, int hip);
void sky_catalog_free(sky_catalog *cat);

#endif /* SKY_CATALOG_H */
