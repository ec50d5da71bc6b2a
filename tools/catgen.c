/*
 * catgen: builds libsky's star catalogue, textures/stars.dat, from
 *   - the npm package d3-celestial (BSD-3): data/stars.8.json, Hipparcos
 *     stars with J2000 positions, V magnitude and B-V (GeoJSON points,
 *     longitude = right ascension in degrees, -180..180);
 *   - Debian's stellarium-data: stars/default/hip_pm.dat, Hipparcos number,
 *     pmRA*cos(dec) and pmDE in mas/yr.
 *
 *   catgen --stars stars.8.json --pm hip_pm.dat --max-mag 6.5 --out stars.dat
 *
 * Output (little-endian): "SKYSTAR1", uint32 count, then per star, sorted
 * by magnitude: uint32 hip, float32 ra, float32 dec (radians, J2000),
 * float32 pm_ra_cosdec, float32 pm_dec (mas/yr), int16 vmag*100,
 * int16 bv*1000 (24 bytes). A star without B-V gets 0.65 (solar).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct star {
    uint32_t hip;
    double ra, dec, pm_ra, pm_dec, vmag, bv;
} star;

static char *read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (buf && fread(buf, 1, (size_t)n, f) != (size_t)n) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    if (buf) buf[n] = '\0';
    *size = (size_t)n;
    return buf;
}

/* The value after "key": within [p, end), as a number (quotes allowed). */
static int field(const char *p, const char *end, const char *key, double *out)
{
    const char *k = strstr(p, key);
    if (!k || k >= end) return 0;
    k += strlen(key);
    while (*k == ' ' || *k == '"' || *k == '[') k++;
    char *e = NULL;
    double v = strtod(k, &e);
    if (e == k || !isfinite(v)) return 0;
    *out = v;
    return 1;
}

static int by_mag(const void *a, const void *b)
{
    const star *x = a, *y = b;
    return (x->vmag > y->vmag) - (x->vmag < y->vmag);
}

static void put_u32(FILE *f, uint32_t v)
{
    unsigned char b[4] = {(unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16), (unsigned char)(v >> 24)};
    fwrite(b, 1, 4, f);
}
static void put_f32(FILE *f, float v)
{
    uint32_t u;
    memcpy(&u, &v, 4);
    put_u32(f, u);
}
static void put_i16(FILE *f, int v)
{
    unsigned char b[2] = {(unsigned char)(v & 0xff), (unsigned char)((v >> 8) & 0xff)};
    fwrite(b, 1, 2, f);
}

int main(int argc, char **argv)
{
    const char *stars_path = NULL, *pm_path = NULL, *out_path = NULL;
    double max_mag = 6.5;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--stars"))
            stars_path = argv[i + 1];
        else if (!strcmp(argv[i], "--pm"))
            pm_path = argv[i + 1];
        else if (!strcmp(argv[i], "--out"))
            out_path = argv[i + 1];
        else if (!strcmp(argv[i], "--max-mag"))
            max_mag = atof(argv[i + 1]);
    }
    if (!stars_path || !pm_path || !out_path) {
        fprintf(stderr, "usage: catgen --stars stars.8.json --pm hip_pm.dat [--max-mag 6.5] --out stars.dat\n");
        return 2;
    }
    size_t n = 0;
    char *json = read_file(stars_path, &n);
    if (!json) {
        fprintf(stderr, "catgen: cannot read %s\n", stars_path);
        return 1;
    }
    /* proper motions by Hipparcos number */
    enum { MAX_HIP = 120500 };
    float *pm = calloc(2u * MAX_HIP, sizeof(float));
    unsigned char *has_pm = calloc(MAX_HIP, 1);
    FILE *f = fopen(pm_path, "r");
    if (!f || !pm || !has_pm) {
        fprintf(stderr, "catgen: cannot read %s\n", pm_path);
        return 1;
    }
    char line[256];
    int pm_count = 0;
    while (fgets(line, sizeof line, f)) {
        unsigned hip;
        float a, b;
        if (line[0] == '#' || sscanf(line, "%u %f %f", &hip, &a, &b) != 3 || hip >= MAX_HIP) continue;
        pm[2 * hip] = a;
        pm[2 * hip + 1] = b;
        has_pm[hip] = 1;
        pm_count++;
    }
    fclose(f);

    size_t cap = 16384, count = 0, missing_pm = 0, missing_bv = 0;
    star *stars = malloc(cap * sizeof *stars);
    const char *p = json;
    while ((p = strstr(p, "{\"type\":\"Feature\"")) != NULL) {
        const char *end = strstr(p + 1, "{\"type\":\"Feature\"");
        if (!end) end = json + n;
        double id, mag, bv, ra, dec;
        const char *coords = strstr(p, "\"coordinates\":");
        if (field(p, end, "\"id\":", &id) && field(p, end, "\"mag\":", &mag) && coords && coords < end &&
            field(coords, end, "\"coordinates\":", &ra)) {
            const char *comma = strchr(coords, ',');
            if (comma && comma < end && field(comma, end, ",", &dec) && mag <= max_mag && id > 0 && id < MAX_HIP) {
                if (!field(p, end, "\"bv\":", &bv)) {
                    bv = 0.65;
                    missing_bv++;
                }
                if (count == cap) stars = realloc(stars, (cap *= 2) * sizeof *stars);
                star *s = &stars[count++];
                s->hip = (uint32_t)id;
                s->ra = (ra < 0 ? ra + 360.0 : ra) * M_PI / 180.0;
                s->dec = dec * M_PI / 180.0;
                s->vmag = mag;
                s->bv = bv;
                s->pm_ra = has_pm[s->hip] ? pm[2 * s->hip] : 0.0;
                s->pm_dec = has_pm[s->hip] ? pm[2 * s->hip + 1] : 0.0;
                missing_pm += !has_pm[s->hip];
            }
        }
        p = end;
    }
    qsort(stars, count, sizeof *stars, by_mag);
    FILE *out = fopen(out_path, "wb");
    if (!out) {
        fprintf(stderr, "catgen: cannot write %s\n", out_path);
        return 1;
    }
    fwrite("SKYSTAR1", 1, 8, out);
    put_u32(out, (uint32_t)count);
    for (size_t i = 0; i < count; i++) {
        const star *s = &stars[i];
        put_u32(out, s->hip);
        put_f32(out, (float)s->ra);
        put_f32(out, (float)s->dec);
        put_f32(out, (float)s->pm_ra);
        put_f32(out, (float)s->pm_dec);
        put_i16(out, (int)lround(s->vmag * 100.0));
        put_i16(out, (int)lround(s->bv * 1000.0));
    }
    if (fclose(out) != 0) return 1;
    printf("catgen: %zu stars to V %.1f (%zu without proper motion, %zu without B-V; %d proper motions read)\n", count,
           max_mag, missing_pm, missing_bv, pm_count);
    free(stars);
    free(json);
    free(pm);
    free(has_pm);
    return 0;
}
