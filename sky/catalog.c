/*
 * The star catalogue (textures/stars.dat, built by tools/catgen.c from
 * d3-celestial and stellarium-data's proper motions, embedded in the
 * library). The reader treats the bytes as hostile: the header, the count
 * and every value are checked before anything is allocated or used.
 */
#include "catalog.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define RECORD_BYTES 24
#define MAX_STARS 200000

static uint32_t get_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}
static float get_f32(const unsigned char *p)
{
    uint32_t u = get_u32(p);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}
static int get_i16(const unsigned char *p) { return (int16_t)(uint16_t)(p[0] | p[1] << 8); }

int sky_catalog_parse(sky_catalog *cat, const unsigned char *data, size_t size, char *err, size_t err_len)
{
    memset(cat, 0, sizeof *cat);
    if (!data || size < 12 || memcmp(data, "SKYSTAR1", 8) != 0) {
        sky_format(err, err_len, "star catalogue: not a SKYSTAR1 file");
        return -1;
    }
    uint32_t count = get_u32(data + 8);
    if (count == 0 || count > MAX_STARS || (size - 12) / RECORD_BYTES < count) {
        sky_format(err, err_len, "star catalogue: %u stars claimed in %lu bytes", (unsigned)count,
                   (unsigned long)size); /* (%zu: not in every C runtime, MinGW's msvcrt) */
        return -1;
    }
    sky_star *stars = malloc(sizeof *stars * count);
    if (!stars) {
        sky_format(err, err_len, "star catalogue: out of memory");
        return -1;
    }
    for (uint32_t i = 0; i < count; i++) {
        const unsigned char *r = data + 12 + (size_t)i * RECORD_BYTES;
        sky_star *s = &stars[i];
        s->hip = (int)get_u32(r);
        s->ra = get_f32(r + 4);
        s->dec = get_f32(r + 8);
        s->pm_ra = get_f32(r + 12);
        s->pm_dec = get_f32(r + 16);
        s->vmag = (float)(get_i16(r + 20) / 100.0);
        s->bv = (float)(get_i16(r + 22) / 1000.0);
        if (s->hip <= 0 || !isfinite(s->ra) || !isfinite(s->dec) || s->ra < 0.0 || s->ra > 2.0 * SKY_PI + 1e-6 ||
            fabs(s->dec) > SKY_PI / 2 + 1e-6 || !isfinite(s->pm_ra) || !isfinite(s->pm_dec) ||
            fabs(s->pm_ra) > 20000.0 || fabs(s->pm_dec) > 20000.0) {
            sky_format(err, err_len, "star catalogue: record %u is out of range", (unsigned)i);
            free(stars);
            return -1;
        }
    }
    cat->stars = stars;
    cat->count = (int)count;
    return 0;
}

int sky_catalog_load(sky_catalog *cat, char *err, size_t err_len)
{
    const sky_blob *b = sky_find_blob("stars.dat");
    if (!b) {
        memset(cat, 0, sizeof *cat);
        sky_format(err, err_len, "the star catalogue is not embedded in this build");
        return -1;
    }
    return sky_catalog_parse(cat, b->data, b->size, err, err_len);
}

const sky_star *sky_catalog_find(const sky_catalog *cat, int hip)
{
    for (int i = 0; i < cat->count; i++)
        if (cat->stars[i].hip == hip) return &cat->stars[i];
    return NULL;
}

void sky_catalog_free(sky_catalog *cat)
{
    free(cat->stars);
    memset(cat, 0, sizeof *cat);
}
