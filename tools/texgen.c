/*
 * texgen: builds libsky's Roden-Parberry textures into a directory.
 *
 *   texgen --out DIR --photo FILE [--crop X,Y,SIZE]
 *
 *   clouds.png    512x512 RGBA: R cloud photo (made tileable), G tileable
 *                 noise, B tileable detail noise, A sunset gradient
 *                 (Roden & Parberry sec. 3: four monochrome textures packed
 *                 into one)
 *   flicker.png   256x256 RGBA: R mean star intensity, G flicker rate,
 *                 B relative variance, A phase (R-P sec. 4)
 *   galaxy.png    128x128 galaxy band, grey in all channels (R-P sec. 4)
 *   gradient.png  256x1 day-sky colour by sqrt(elevation) (R-P fig. 1)
 *   moon.png      256x128 lunar albedo, equirectangular, selenographic
 *                 longitude 0 at the centre, east to the right (with
 *                 --moon FILE: a global lunar map such as stellarium-data's
 *                 USGS/Clementine mosaic, box-filtered down)
 *
 * The photo may be any cloud photograph or a cloud map such as NASA's (as
 * shipped by Debian's stellarium-data); cloudiness is taken as the smallest
 * of R, G, B (white clouds are bright in all three, blue sea and brown land
 * are not). --crop picks a square region of it (x wraps around, as a global
 * map does); a quarter of SIZE more below and to the right is read for the
 * seamless cross-fade. Everything else is generated from a fixed seed, so the output
 * is reproducible.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_PERLIN_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <stb/stb_perlin.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#define CLOUD 512
#define FLICKER 256
#define GALAXY 128

/* ---- deterministic random numbers (splitmix64) --------------------------- */
static uint64_t rng_state = 0x5EED5EEDull;
static double rnd(void)
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) / 9007199254740992.0;
}

static double clamp01(double x) { return x < 0 ? 0 : x > 1 ? 1 : x; }
static unsigned char to_byte(double x) { return (unsigned char)lround(clamp01(x) * 255.0); }

/* Tileable fractal noise over [0,1)^2: octaves whose frequencies are powers
 * of two wrap exactly with stb_perlin's wrap arguments. */
static double fbm(double u, double v, int f0, int octaves, double gain, int seed)
{
    double sum = 0, amp = 1, norm = 0;
    int f = f0;
    for (int o = 0; o < octaves && f <= 256; o++, f *= 2) {
        sum += amp * stb_perlin_noise3((float)(u * f), (float)(v * f), (float)(seed * 7.31 + o * 1.7), f, f, 0);
        norm += amp;
        amp *= gain;
    }
    return sum / norm; /* about -1..1 */
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Stretches values so the given lower/upper percentiles map to 0 and 1. */
static void normalise(double *img, int n, double lo_pct, double hi_pct)
{
    double *sorted = malloc(sizeof(double) * (size_t)n);
    memcpy(sorted, img, sizeof(double) * (size_t)n);
    qsort(sorted, (size_t)n, sizeof(double), cmp);
    double lo = sorted[(int)(lo_pct * (n - 1))], hi = sorted[(int)(hi_pct * (n - 1))];
    free(sorted);
    for (int i = 0; i < n; i++) img[i] = clamp01((img[i] - lo) / (hi - lo > 1e-9 ? hi - lo : 1e-9));
}
/* ---- the photo channel ------------------------------------------------------ */

/* Bilinear sample of the cloudiness of the source photo; x wraps, y clamps. */
static double photo_sample(const unsigned char *rgb, int w, int h, double x, double y)
{
    int x0 = (int)floor(x), y0 = (int)floor(y);
    double fx = x - x0, fy = y - y0;
    double acc = 0;
    for (int dy = 0; dy < 2; dy++)
        for (int dx = 0; dx < 2; dx++) {
            int xi = ((x0 + dx) % w + w) % w;
            int yi = y0 + dy < 0 ? 0 : y0 + dy >= h ? h - 1 : y0 + dy;
            const unsigned char *p = rgb + 3 * ((size_t)yi * (size_t)w + (size_t)xi);
            int m = p[0] < p[1] ? p[0] : p[1];
            m = m < p[2] ? m : p[2];
            acc += (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (m / 255.0);
        }
    return acc;
}

/* Makes an image tile by cross-fading a margin: the source holds n + m
 * samples along each axis; the first m samples are blended with the m that
 * follow the tile (x + n), so the tile's last sample runs on into its first.
 * One axis at a time; the blend preserves variance so the faded band is
 * not washed out. src is (n+m)x(n+m), dst is nxn. */
static void make_tileable(const double *src, int n, int m, double *dst)
{
    int s = n + m;
    double *rows = malloc(sizeof(double) * (size_t)n * (size_t)s); /* x done, s rows */
    const double mean = 0.5;
    for (int pass = 0; pass < 2; pass++)
        for (int a = 0; a < (pass ? n : s); a++)     /* the other axis   */
            for (int t = 0; t < n; t++) {              /* the axis tiled   */
                double v0 = pass ? rows[t * n + a] : src[a * s + t];
                double v = v0;
                if (t < m) {
                    double v1 = pass ? rows[(t + n) * n + a] : src[a * s + t + n];
                    double w = (t + 0.5) / m;
                    w = w * w * (3 - 2 * w);
                    v = mean + ((v0 - mean) * w + (v1 - mean) * (1 - w)) / sqrt(w * w + (1 - w) * (1 - w));
                }
                if (pass)
                    dst[t * n + a] = v;
                else
                    rows[a * n + t] = v;
            }
    free(rows);
}

static int build_photo(const char *path, int cx, int cy, int cs, double *out)
{
    int w, h, comp;
    unsigned char *rgb = stbi_load(path, &w, &h, &comp, 3);
    if (!rgb) {
        fprintf(stderr, "texgen: cannot read photo %s: %s\n", path, stbi_failure_reason());
        return -1;
    }
    if (cs <= 0) { /* whole image: the largest square that leaves the margin */
        cs = (w < h ? w : h) * 4 / 5;
        cx = (w - cs) / 2;
        cy = (h - cs) / 2;
    }
    if (cy < 0 || cy + cs + cs / 4 > h || cs < 16) {
        fprintf(stderr, "texgen: crop %d,%d,%d does not fit the %dx%d photo\n", cx, cy, cs, w, h);
        stbi_image_free(rgb);
        return -1;
    }
    /* the tile plus a quarter-tile margin for the cross-fade */
    enum { MARGIN = CLOUD / 4, SRC = CLOUD + MARGIN };
    double *src = malloc(sizeof(double) * SRC * SRC);
    if (!src) {
        stbi_image_free(rgb);
        return -1;
    }
    for (int y = 0; y < SRC; y++)
        for (int x = 0; x < SRC; x++)
            src[y * SRC + x] = photo_sample(rgb, w, h, cx + (x + 0.5) * cs / CLOUD - 0.5, cy + (y + 0.5) * cs / CLOUD - 0.5);
    stbi_image_free(rgb);
    normalise(src, SRC * SRC, 0.02, 0.995);
    make_tileable(src, CLOUD, MARGIN, out);
    free(src);
    for (int i = 0; i < CLOUD * CLOUD; i++) out[i] = clamp01(out[i]);
    /* clouds cover part of the sky: push the lower half toward black */
    for (int i = 0; i < CLOUD * CLOUD; i++) out[i] = clamp01((out[i] - 0.25) / 0.75);
    return 0;
}

/* ---- writers ----------------------------------------------------------------- */

static int write_png(const char *dir, const char *name, int w, int h, const unsigned char *rgba)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (!stbi_write_png(path, w, h, 4, rgba, w * 4)) {
        fprintf(stderr, "texgen: cannot write %s\n", path);
        return -1;
    }
    printf("texgen: wrote %s (%dx%d)\n", path, w, h);
    return 0;
}

static int build_clouds(const char *dir, const char *photo, int cx, int cy, int cs)
{
    double *r = malloc(sizeof(double) * CLOUD * CLOUD);
    double *g = malloc(sizeof(double) * CLOUD * CLOUD);
    double *b = malloc(sizeof(double) * CLOUD * CLOUD);
    unsigned char *img = malloc(CLOUD * CLOUD * 4);
    int rc = -1;
    if (!r || !g || !b || !img || build_photo(photo, cx, cy, cs, r)) goto done;
    for (int y = 0; y < CLOUD; y++)
        for (int x = 0; x < CLOUD; x++) {
            double u = (double)x / CLOUD, v = (double)y / CLOUD;
            /* G: billowy shapes (first octave at 4 periods per tile) */
            g[y * CLOUD + x] = fbm(u, v, 4, 6, 0.55, 1);
            /* B: fine detail */
            b[y * CLOUD + x] = fbm(u, v, 16, 4, 0.6, 2);
        }
    /* the full range: at cover 1 (R-P line 15) almost every texel holds
     * some cloud, so the sky can be overcast */
    normalise(g, CLOUD * CLOUD, 0.02, 0.995);
    normalise(b, CLOUD * CLOUD, 0.01, 0.99);
    for (int y = 0; y < CLOUD; y++)
        for (int x = 0; x < CLOUD; x++) {
            int i = y * CLOUD + x;
            unsigned char *p = img + 4 * i;
            p[0] = to_byte(r[i]);
            p[1] = to_byte(g[i]);
            p[2] = to_byte(b[i] * 0.6); /* detail is a modulation, not a layer */
            /* A: sunset gradient, strongest at v = 0 (toward the sun) */
            p[3] = to_byte(pow(1.0 - (y + 0.5) / CLOUD, 1.6));
        }
    rc = write_png(dir, "clouds.png", CLOUD, CLOUD, img);
done:
    free(r);
    free(g);
    free(b);
    free(img);
    return rc;
}

static int build_flicker(const char *dir)
{
    unsigned char *img = calloc(FLICKER * FLICKER, 4);
    unsigned char *taken = calloc(FLICKER * FLICKER, 1);
    if (!img || !taken) return -1;
    int stars = 0;
    for (int attempt = 0; attempt < 20000 && stars < 260; attempt++) {
        int x = (int)(rnd() * FLICKER), y = (int)(rnd() * FLICKER);
        /* keep 3x3 neighbourhoods apart: each carries its star's G, B, A */
        int clear = 1;
        for (int dy = -2; dy <= 2 && clear; dy++)
            for (int dx = -2; dx <= 2; dx++)
                if (taken[((y + dy + FLICKER) % FLICKER) * FLICKER + (x + dx + FLICKER) % FLICKER]) clear = 0;
        if (!clear) continue;
        /* many faint stars, few bright ones */
        double intensity = 0.12 + 0.88 * pow(rnd(), 5.0);
        unsigned char rate = to_byte(0.15 + 0.85 * rnd());
        unsigned char variance = to_byte(0.15 + 0.5 * rnd());
        unsigned char phase = to_byte(rnd());
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int i = ((y + dy + FLICKER) % FLICKER) * FLICKER + (x + dx + FLICKER) % FLICKER;
                taken[i] = 1;
                img[4 * i + 0] = (dx == 0 && dy == 0) ? to_byte(intensity) : 0;
                img[4 * i + 1] = rate;
                img[4 * i + 2] = variance;
                img[4 * i + 3] = phase;
            }
        stars++;
    }
    int rc = write_png(dir, "flicker.png", FLICKER, FLICKER, img);
    printf("texgen: %d flicker stars per tile\n", stars);
    free(img);
    free(taken);
    return rc;
}

static int build_galaxy(const char *dir)
{
    unsigned char *img = malloc(GALAXY * GALAXY * 4);
    if (!img) return -1;
    for (int y = 0; y < GALAXY; y++)
        for (int x = 0; x < GALAXY; x++) {
            double u = (x + 0.5) / GALAXY * 2 - 1, v = (y + 0.5) / GALAXY * 2 - 1;
            /* a band crossing the dome, slightly curved, with dust lanes */
            double across = (u * 0.8 - v * 0.6) + 0.12 * (u * u - 0.5);
            double along = u * 0.6 + v * 0.8;
            double band = exp(-across * across / (2 * 0.17 * 0.17));
            double lanes = 0.55 + 0.45 * fbm((u + 1) / 2, (v + 1) / 2, 4, 4, 0.6, 3);
            double core = 1.0 + 0.8 * exp(-(along - 0.3) * (along - 0.3) / 0.08);
            double g = clamp01(band * lanes * core * 0.75);
            unsigned char c = to_byte(g);
            unsigned char *p = img + 4 * (y * GALAXY + x);
            p[0] = p[1] = p[2] = p[3] = c;
        }
    int rc = write_png(dir, "galaxy.png", GALAXY, GALAXY, img);
    free(img);
    return rc;
}

static int build_gradient(const char *dir)
{
    /* linear RGB: pale at the horizon, deep blue at the zenith */
    static const double horizon[3] = {0.72, 0.82, 0.97}, zenith[3] = {0.06, 0.18, 0.62};
    unsigned char img[256 * 4];
    for (int i = 0; i < 256; i++) {
        double s = i / 255.0; /* sqrt(elevation sine) */
        double t = pow(s, 0.9);
        for (int c = 0; c < 3; c++) img[4 * i + c] = to_byte(horizon[c] + (zenith[c] - horizon[c]) * t);
        img[4 * i + 3] = 255;
    }
    return write_png(dir, "gradient.png", 256, 1, img);
}

static int build_moon(const char *dir, const char *path)
{
    int w, h, comp;
    unsigned char *src = stbi_load(path, &w, &h, &comp, 3);
    if (!src) {
        fprintf(stderr, "texgen: cannot read moon map %s\n", path);
        return -1;
    }
    enum { MW = 256, MH = 128 };
    unsigned char *img = malloc(MW * MH * 4);
    for (int y = 0; y < MH; y++)
        for (int x = 0; x < MW; x++) {
            /* average the source texels that fall in this one (grey) */
            int x0 = x * w / MW, x1 = (x + 1) * w / MW, y0 = y * h / MH, y1 = (y + 1) * h / MH;
            double acc = 0;
            int n = 0;
            for (int yy = y0; yy < y1; yy++)
                for (int xx = x0; xx < x1; xx++) {
                    const unsigned char *p = src + 3 * ((size_t)yy * (size_t)w + (size_t)xx);
                    acc += (p[0] + p[1] + p[2]) / 3.0;
                    n++;
                }
            unsigned char v = (unsigned char)lround(n ? acc / n : 0);
            unsigned char *o = img + 4 * (y * MW + x);
            o[0] = o[1] = o[2] = v;
            o[3] = 255;
        }
    stbi_image_free(src);
    int rc = write_png(dir, "moon.png", MW, MH, img);
    free(img);
    return rc;
}

int main(int argc, char **argv)
{
    const char *out = NULL, *photo = NULL, *moon = NULL;
    int cx = 0, cy = 0, cs = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--out") && i + 1 < argc)
            out = argv[++i];
        else if (!strcmp(argv[i], "--photo") && i + 1 < argc)
            photo = argv[++i];
        else if (!strcmp(argv[i], "--moon") && i + 1 < argc)
            moon = argv[++i];
        else if (!strcmp(argv[i], "--crop") && i + 1 < argc) {
            if (sscanf(argv[++i], "%d,%d,%d", &cx, &cy, &cs) != 3) {
                fprintf(stderr, "texgen: --crop wants X,Y,SIZE\n");
                return 2;
            }
        } else {
            fprintf(stderr, "usage: texgen --out DIR --photo FILE [--crop X,Y,SIZE] [--moon FILE]\n");
            return 2;
        }
    }
    if (!out || !photo) {
        fprintf(stderr, "usage: texgen --out DIR --photo FILE [--crop X,Y,SIZE] [--moon FILE]\n");
        return 2;
    }
    if (build_clouds(out, photo, cx, cy, cs) || build_flicker(out) || build_galaxy(out) || build_gradient(out))
        return 1;
    if (moon && build_moon(out, moon)) return 1;
    return 0;
}
