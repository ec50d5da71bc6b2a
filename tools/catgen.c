/*
 * catgen: builds libsky's star catalogue, textures/stars.dat, from
 *   - the npm package d3-celestial (BSD-3): data/stars.8.json, Hipparcos
 *     stars with J2000 positions, V magnitude and B-V (GeoJSON points,
 *     longitude = right ascension in degrees, -180..180);
 *   - Debian's stellarium-data: stars/default/hip_pm.dat, Hipparcos number,
 *     pmRA*cos(dec) and pmDE in mas/yr.
 *
 *   catgen --stars stars.8.json --pm hip_pm.dat --max-mag 6.5 --out stars.dat
 *          [--map starmap.png --mw mw.json]
 *
 * With --map it also writes Mueller's star map (sec. 4.4): a 512x256
 * equirectangular all-sky image in J2000 equatorial coordinates (u = right
 * ascension from 0 at the left, v = declination from +90 at the top) of
 * the light of every catalogue star fainter than --max-mag (the brighter
 * ones are drawn one by one; leaving them out avoids doubling them) plus
 * the Milky Way from d3-celestial's data/mw.json (five nested brightness
 * levels), smoothed. Stored as 8-bit sRGB-encoded surface brightness,
 * 1.0 = the brightest texel; libsky scales it to luminance.
 *
 * Output (little-endian): "SKYSTAR1", uint32 count, then per star, sorted
 * by magnitude: uint32 hip, float32 ra, float32 dec (radians, J2000),
 * float32 pm_ra_cosdec, float32 pm_dec (mas/yr), int16 vmag*100,
 * int16 bv*1000 (24 bytes). A star without B-V gets 0.65 (solar).
 */
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-prototypes"
#pragma GCC diagnostic ignored "-Wsign-compare"
#endif
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
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

/* ---- the star map --------------------------------------------------------- */

#define MAP_W 512
#define MAP_H 256

typedef struct ring {
    double *pt; /* lon, lat pairs, degrees */
    int n, cap;
} ring;

/* Reads the rings of one MultiPolygon feature ("id":"olN") of mw.json:
 * every innermost array of [lon, lat] points is a ring. */
static int read_rings(const char *json, const char *id, ring **out)
{
    char key[32];
    snprintf(key, sizeof key, "\"id\":\"%s\"", id);
    const char *p = strstr(json, key);
    if (!p || !(p = strstr(p, "\"coordinates\":"))) return -1;
    p += strlen("\"coordinates\":");
    int depth = 0, count = 0, cap = 0;
    ring *rings = NULL;
    ring *cur = NULL;
    for (; *p; p++) {
        if (*p == '[') {
            const char *q = p + 1;
            while (*q == ' ') q++;
            if (*q == '-' || (*q >= '0' && *q <= '9')) { /* a point */
                char *e;
                double lon = strtod(q, &e);
                if (*e != ',') return -1;
                double lat = strtod(e + 1, &e);
                if (!cur) {
                    if (count == cap) rings = realloc(rings, sizeof *rings * (size_t)(cap = cap ? 2 * cap : 64));
                    cur = &rings[count++];
                    memset(cur, 0, sizeof *cur);
                }
                if (cur->n == cur->cap) cur->pt = realloc(cur->pt, sizeof(double) * 2 * (size_t)(cur->cap = cur->cap ? 2 * cur->cap : 64));
                cur->pt[2 * cur->n] = lon;
                cur->pt[2 * cur->n + 1] = lat;
                cur->n++;
                p = e; /* at the point's ']' */
                continue;
            }
            depth++;
        } else if (*p == ']') {
            cur = NULL; /* a ring (or something above it) has ended */
            if (--depth <= 0) break;
        }
    }
    *out = rings;
    return count;
}

/* Fills the rings into the map, adding `value` inside. Inside is decided
 * per column by the parity of boundary crossings met going north from a
 * texel to the pole along its meridian: this works for ordinary closed
 * rings and for the two rings that each run once around the sky and
 * between them bound the Milky Way's band (a row-wise even-odd fill gets
 * those wrong). No ring may enclose the north pole. */
static void fill_rings(float *map, const ring *rings, int count, float value)
{
    static double ys[8192];
    for (int x = 0; x < MAP_W; x++) {
        double ra = (x + 0.5) * 360.0 / MAP_W, lon = ra > 180.0 ? ra - 360.0 : ra;
        int ny = 0;
        for (int r = 0; r < count; r++)
            for (int i = 0; i < rings[r].n; i++) {
                const double *a = &rings[r].pt[2 * i], *b = &rings[r].pt[2 * ((i + 1) % rings[r].n)];
                double dl = b[0] - a[0];
                if (dl > 180.0) dl -= 360.0;
                if (dl < -180.0) dl += 360.0;
                if (dl == 0.0) continue;
                /* where along the edge is this meridian? (wrapped) */
                double t = (lon - a[0]) / dl;
                double off = lon - a[0];
                if (dl > 0) {
                    while (off < 0) off += 360.0;
                    while (off >= 360.0) off -= 360.0;
                } else {
                    while (off > 0) off -= 360.0;
                    while (off <= -360.0) off += 360.0;
                }
                t = off / dl;
                if (t < 0.0 || t >= 1.0 || ny == 8192) continue;
                ys[ny++] = a[1] + t * (b[1] - a[1]);
            }
        /* sort north to south */
        for (int i = 1; i < ny; i++)
            for (int j = i; j > 0 && ys[j] > ys[j - 1]; j--) {
                double tmp = ys[j];
                ys[j] = ys[j - 1], ys[j - 1] = tmp;
            }
        int k = 0, inside = 0;
        for (int y = 0; y < MAP_H; y++) {
            double dec = 90.0 - (y + 0.5) * 180.0 / MAP_H;
            while (k < ny && ys[k] > dec) inside ^= 1, k++;
            if (inside) map[y * MAP_W + x] += value;
        }
    }
}

static void blur(float *map, int radius)
{
    float *tmp = malloc(sizeof(float) * MAP_W * MAP_H);
    for (int pass = 0; pass < 2; pass++) {
        for (int y = 0; y < MAP_H; y++)
            for (int x = 0; x < MAP_W; x++) {
                double s = 0;
                int n = 0;
                for (int k = -radius; k <= radius; k++) {
                    if (pass == 0)
                        s += map[y * MAP_W + (x + k + MAP_W) % MAP_W], n++; /* RA wraps */
                    else if (y + k >= 0 && y + k < MAP_H)
                        s += map[(y + k) * MAP_W + x], n++;
                }
                tmp[y * MAP_W + x] = (float)(s / n);
            }
        memcpy(map, tmp, sizeof(float) * MAP_W * MAP_H);
    }
    free(tmp);
}

static int write_map(const char *path, const char *mw_path, const star *faint, size_t n_faint)
{
    float *map = calloc(MAP_W * MAP_H, sizeof(float));
    size_t size = 0;
    char *mw = read_file(mw_path, &size);
    if (!map || !mw) {
        fprintf(stderr, "catgen: cannot read %s\n", mw_path);
        return -1;
    }
    /* the Milky Way: each nested level adds to the glow */
    static const char *levels[5] = {"ol1", "ol2", "ol3", "ol4", "ol5"};
    for (int l = 0; l < 5; l++) {
        ring *rings = NULL;
        int count = read_rings(mw, levels[l], &rings);
        if (count <= 0) {
            fprintf(stderr, "catgen: no Milky Way level %s in %s\n", levels[l], mw_path);
            return -1;
        }
        fill_rings(map, rings, count, 1.0f);
        for (int r = 0; r < count; r++) free(rings[r].pt);
        free(rings);
    }
    blur(map, 3);
    /* the faint stars, as surface brightness: flux over the texel's solid
     * angle (which shrinks with cos(dec)); a V = 8 star adds 0.02 of the
     * brightest Milky Way level's glow to a texel at the equator */
    for (size_t i = 0; i < n_faint; i++) {
        int x = (int)(faint[i].ra / (2 * M_PI) * MAP_W) % MAP_W;
        int y = (int)((M_PI / 2 - faint[i].dec) / M_PI * MAP_H);
        if (y < 0) y = 0;
        if (y >= MAP_H) y = MAP_H - 1;
        double c = cos(faint[i].dec);
        map[y * MAP_W + x] += (float)(0.1 * pow(10.0, -0.4 * (faint[i].vmag - 8.0)) / (c > 0.05 ? c : 0.05));
    }
    blur(map, 1);
    float mx = 0;
    for (int i = 0; i < MAP_W * MAP_H; i++) mx = map[i] > mx ? map[i] : mx;
    unsigned char *img = malloc(MAP_W * MAP_H * 4);
    for (int i = 0; i < MAP_W * MAP_H; i++) {
        double v = map[i] / mx;
        unsigned char b = (unsigned char)lround(255.0 * pow(v, 1.0 / 2.2)); /* 8 bits spent where the eye is */
        /* the Milky Way's light is old stars': slightly warm */
        img[4 * i + 0] = b;
        img[4 * i + 1] = (unsigned char)lround(b * 0.94);
        img[4 * i + 2] = (unsigned char)lround(b * 0.85);
        img[4 * i + 3] = 255;
    }
    int ok = stbi_write_png(path, MAP_W, MAP_H, 4, img, MAP_W * 4);
    free(img);
    free(map);
    free(mw);
    if (!ok) fprintf(stderr, "catgen: cannot write %s\n", path);
    else printf("catgen: wrote %s (%dx%d, %zu faint stars and 5 Milky Way levels)\n", path, MAP_W, MAP_H, n_faint);
    return ok ? 0 : -1;
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
    const char *stars_path = NULL, *pm_path = NULL, *out_path = NULL, *map_path = NULL, *mw_path = NULL;
    double max_mag = 6.5;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--stars"))
            stars_path = argv[i + 1];
        else if (!strcmp(argv[i], "--pm"))
            pm_path = argv[i + 1];
        else if (!strcmp(argv[i], "--out"))
            out_path = argv[i + 1];
        else if (!strcmp(argv[i], "--map"))
            map_path = argv[i + 1];
        else if (!strcmp(argv[i], "--mw"))
            mw_path = argv[i + 1];
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
            if (comma && comma < end && field(comma, end, ",", &dec) && id > 0 && id < MAX_HIP) {
                if (!field(p, end, "\"bv\":", &bv)) {
                    bv = 0.65;
                    missing_bv += mag <= max_mag;
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
                missing_pm += !has_pm[s->hip] && mag <= max_mag;
            }
        }
        p = end;
    }
    qsort(stars, count, sizeof *stars, by_mag);
    size_t bright = 0;
    while (bright < count && stars[bright].vmag <= max_mag) bright++;
    if (map_path && (!mw_path || write_map(map_path, mw_path, stars + bright, count - bright))) return 1;
    count = bright;
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
