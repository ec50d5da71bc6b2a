/*
 * libsky's test runner: runs every test (or those whose name contains
 * the argument) and ends with the line "N passed, N failed" (followed by
 * ", N skipped" when a test could not run here). --fast (make check)
 * leaves out the tests defined with SLOW_TEST, which make test runs.
 */
#include "test.h"
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef _WIN32
#include <process.h>
#include <windows.h>
#else
#include <sys/wait.h>
#include <unistd.h>
#endif

/* The test program's own PNG reader (the library keeps its copy private). */
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

int test_failures;
int test_skipped;

/* TESTS(X): every TEST and SLOW_TEST of the runner's files, in their
 * order, found by tests/list.sh (no hand-kept list). Each runner (this
 * one, the browser's, the engine examples') has its own list. */
#include "test_list.h"

#define DECLARE(name, slow) void test_##name(void);
TESTS(DECLARE)
#undef DECLARE

/* ---- fixtures ------------------------------------------------------------- */

scene scene_default(void)
{
    scene sc;
    memset(&sc, 0, sizeof sc);
    sc.params = sky_default_params();
    sc.yaw = 180.0;
    sc.pitch = 20.0;
    sc.fov = 60.0;
    sc.w = 320;
    sc.h = 180;
    return sc;
}

void scene_camera(const scene *sc, float view[16], float proj[16])
{
    sky_cli_camera_at(sc->yaw, sc->pitch, sc->fov, sc->w, sc->h, view, proj);
}

int scene_project(const scene *sc, double alt_deg, double az_deg, double *px, double *py)
{
    const double deg = 3.14159265358979323846 / 180.0;
    float view[16], proj[16];
    scene_camera(sc, view, proj);
    double d[3] = {cos(alt_deg * deg) * sin(az_deg * deg), sin(alt_deg * deg), -cos(alt_deg * deg) * cos(az_deg * deg)};
    double e[4], c[4];
    for (int r = 0; r < 4; r++) e[r] = view[r] * d[0] + view[4 + r] * d[1] + view[8 + r] * d[2];
    for (int r = 0; r < 4; r++) c[r] = proj[r] * e[0] + proj[4 + r] * e[1] + proj[8 + r] * e[2];
    if (c[3] <= 0.0) return -1;
    *px = (c[0] / c[3] + 1.0) * 0.5 * sc->w;
    *py = (1.0 - c[1] / c[3]) * 0.5 * sc->h;
    return 0;
}

double image_blob(const image *im, double cx, double cy, int r, double *bx, double *by)
{
    double peak = 0.0;
    for (int y = (int)cy - r; y <= (int)cy + r; y++)
        for (int x = (int)cx - r; x <= (int)cx + r; x++)
            if (x >= 0 && y >= 0 && x < im->w && y < im->h) peak = fmax(peak, image_luminance(im, x, y));
    double sx = 0, sy = 0, sw = 0;
    for (int y = (int)cy - r; y <= (int)cy + r; y++)
        for (int x = (int)cx - r; x <= (int)cx + r; x++)
            if (x >= 0 && y >= 0 && x < im->w && y < im->h) {
                double l = image_luminance(im, x, y);
                if (l > 0.3 * peak) sx += l * (x + 0.5), sy += l * (y + 0.5), sw += l;
            }
    *bx = sw > 0 ? sx / sw : -1;
    *by = sw > 0 ? sy / sw : -1;
    return peak;
}

double image_centre_sum(const float *rgba, int n, int radius)
{
    double ring[2048];
    int nr = 0;
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            double r = hypot(x + 0.5 - n / 2.0, y + 0.5 - n / 2.0);
            if (r > radius + 2 && r <= radius + 6 && nr < 2048) {
                const float *q = rgba + 4 * (y * n + x);
                ring[nr++] = 0.2126 * q[0] + 0.7152 * q[1] + 0.0722 * q[2];
            }
        }
    for (int i = 1; i < nr; i++) /* insertion sort: a few hundred values */
        for (int j = i; j > 0 && ring[j] < ring[j - 1]; j--) {
            double t = ring[j];
            ring[j] = ring[j - 1], ring[j - 1] = t;
        }
    double bg = nr ? ring[nr / 2] : 0.0, sum = 0.0;
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++)
            if (hypot(x + 0.5 - n / 2.0, y + 0.5 - n / 2.0) <= radius) {
                const float *q = rgba + 4 * (y * n + x);
                sum += 0.2126 * q[0] + 0.7152 * q[1] + 0.0722 * q[2] - bg;
            }
    return sum;
}

int render_scene(const scene *sc, int hdr, sky_gl_profile want, image *out)
{
    char err[512];
    sky_osmesa ctx;
    memset(out, 0, sizeof *out);
    sky_gl_profile ctx_kind = want == SKY_GL_COMPAT20 ? SKY_GL_COMPAT20 : want;
    if (sky_osmesa_create(&ctx, sc->w, sc->h, ctx_kind, hdr, err, sizeof err)) {
        printf("    render_scene: %s\n", err);
        return -1;
    }
    sky_config cfg = sc->cfg;
    cfg.get_proc_address = sky_osmesa_loader();
    cfg.output = hdr ? SKY_OUTPUT_HDR : SKY_OUTPUT_LDR;
    cfg.gl_profile = want;
    cfg.check_gl_errors = 1; /* the tests want every GL error the sky makes */
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        printf("    render_scene: %s\n", err);
        sky_osmesa_destroy(&ctx);
        return -1;
    }
    int rc = 0;
    if (sky_set_params(s, &sc->params) < 0 || sky_set_elapsed(s, sc->seconds) < 0 ||
        (sc->has_observer && sky_set_observer(s, &sc->observer) != SKY_OK) ||
        sky_set_exposure_bias(s, sc->exposure_bias) != SKY_OK)
        rc = -1;
    float view[16], proj[16];
    scene_camera(sc, view, proj);
    if (!rc && (sc->fisheye ? sky_draw_fisheye(s) : sky_draw(s, view, proj)) < 0) {
        printf("    render_scene: %s\n", sky_last_error(s));
        rc = -1;
    }
    sky_osmesa_finish(&ctx);
    if (!rc) {
        out->w = sc->w;
        out->h = sc->h;
        out->px = malloc(sizeof(float) * 3u * (size_t)sc->w * (size_t)sc->h);
        for (int y = 0; y < sc->h; y++)
            for (int x = 0; x < sc->w; x++)
                for (int c = 0; c < 3; c++) {
                    size_t src = ((size_t)(sc->h - 1 - y) * (size_t)sc->w + (size_t)x) * 4u + (size_t)c;
                    float v = hdr ? ((const float *)ctx.pixels)[src] : ((const unsigned char *)ctx.pixels)[src] / 255.0f;
                    out->px[((size_t)y * (size_t)sc->w + (size_t)x) * 3u + (size_t)c] = v;
                }
    }
    sky_destroy(s);
    sky_osmesa_destroy(&ctx);
    return rc;
}

int fixture_open(fixture *f, sky_gl_profile profile, const sky_config *base)
{
    return fixture_open_sized(f, 64, 48, 0, profile, base);
}

sky_observer equator_equinox(void)
{
    sky_observer o;
    memset(&o, 0, sizeof o);
    o.julian_day_utc = sky_julian_day(2026, 3, 20, 12, 0, 0.0);
    o.time_from_params = 1;
    return o;
}

int fixture_open_sized(fixture *f, int w, int h, int float_buffer, sky_gl_profile profile, const sky_config *base)
{
    char err[512];
    memset(f, 0, sizeof *f);
    if (sky_osmesa_create(&f->ctx, w, h, profile, float_buffer, err, sizeof err)) {
        printf("    %s\n", err);
        return -1;
    }
    sky_config cfg;
    if (base)
        cfg = *base;
    else
        memset(&cfg, 0, sizeof cfg);
    cfg.get_proc_address = sky_osmesa_loader();
    cfg.gl_profile = profile;
    cfg.check_gl_errors = 1; /* the tests want every GL error the sky makes */
    f->s = sky_create(&cfg, err, sizeof err);
    if (!f->s) {
        printf("    sky_create: %s\n", err);
        sky_osmesa_destroy(&f->ctx);
        return -1;
    }
    return 0;
}

void fixture_close(fixture *f)
{
    sky_destroy(f->s);
    sky_osmesa_destroy(&f->ctx);
}

void image_free(image *im)
{
    free(im->px);
    im->px = NULL;
}

float image_luminance(const image *im, int x, int y)
{
    const float *p = im->px + ((size_t)y * (size_t)im->w + (size_t)x) * 3u;
    return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
}

int image_load_png(const char *path, image *out)
{
    int w, h, n;
    memset(out, 0, sizeof *out);
    unsigned char *p = stbi_load(path, &w, &h, &n, 3);
    if (!p) return -1;
    out->w = w;
    out->h = h;
    out->px = malloc(sizeof(float) * 3u * (size_t)w * (size_t)h);
    for (size_t i = 0; i < 3u * (size_t)w * (size_t)h; i++) out->px[i] = p[i] / 255.0f;
    stbi_image_free(p);
    return 0;
}

/* PSNR in dB of two images of one size, on values 0..1 (99 when equal). */
double image_psnr(const image *a, const image *b)
{
    double se = 0.0;
    size_t n = 3u * (size_t)a->w * (size_t)a->h;
    for (size_t i = 0; i < n; i++) se += ((double)a->px[i] - b->px[i]) * ((double)a->px[i] - b->px[i]);
    double mse = se / (double)n;
    return mse > 0.0 ? 10.0 * log10(1.0 / mse) : 99.0;
}

char *read_text_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = size >= 0 ? malloc((size_t)size + 1) : NULL;
    size_t got = buf ? fread(buf, 1, (size_t)size, f) : 0;
    fclose(f);
    if (buf) buf[got] = '\0';
    if (len) *len = got;
    return buf;
}

const char *bin_path(const char *name, char *buf, size_t len)
{
    const char *dir = getenv("SKY_BIN");
    snprintf(buf, len, "%s/%s", dir ? dir : "build/bin", name);
    return buf;
}

const char *tmp_path(const char *name, char *buf, size_t len)
{
    const char *dir = getenv("TMPDIR");
    snprintf(buf, len, "%s/sky-test-%d-%s", dir ? dir : "/tmp", (int)getpid(), name);
    return buf;
}

int run_command(const char *cmd, char *buf, size_t len)
{
    FILE *p = popen(cmd, "r");
    if (!p) return -1;
    size_t used = 0;
    if (buf && len) buf[0] = '\0';
    char chunk[512];
    size_t n;
    while ((n = fread(chunk, 1, sizeof chunk, p)) > 0)
        if (buf && used + 1 < len) {
            size_t k = n < len - 1 - used ? n : len - 1 - used;
            memcpy(buf + used, chunk, k);
            used += k;
            buf[used] = '\0';
        }
    int status = pclose(p);
#ifdef _WIN32
    return status; /* the command's exit code */
#else
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
#endif
}

/* Seconds on a monotonic clock, for the log's durations. */
static double now_seconds(void)
{
#ifdef _WIN32
    LARGE_INTEGER count, frequency;
    QueryPerformanceCounter(&count);
    QueryPerformanceFrequency(&frequency);
    return (double)count.QuadPart / (double)frequency.QuadPart;
#else
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
#endif
}

/* ---- runner ----------------------------------------------------------------- */

int main(int argc, char **argv)
{
    static const test_case tests[] = {
#define ENTRY(name, slow) {#name, test_##name, slow},
        TESTS(ENTRY)
#undef ENTRY
    };
    setvbuf(stdout, NULL, _IOLBF, 0);
    int fast = argc > 1 && strcmp(argv[1], "--fast") == 0;
    const char *filter = argc > 1 + fast ? argv[1 + fast] : NULL;
    int passed = 0, failed = 0, skipped = 0, left_out = 0;
    for (size_t i = 0; i < sizeof tests / sizeof tests[0]; i++) {
        if (filter && !strstr(tests[i].name, filter)) continue;
        if (fast && tests[i].slow) {
            left_out++;
            continue;
        }
        test_failures = 0;
        test_skipped = 0;
        printf("  %s\n", tests[i].name);
        double t0 = now_seconds();
        tests[i].fn();
        double took = now_seconds() - t0;
        if (test_failures) {
            printf("FAIL %s (%.2f s)\n", tests[i].name, took);
            failed++;
        } else if (test_skipped) {
            printf("skip %s (%.2f s)\n", tests[i].name, took);
            skipped++;
        } else {
            printf("ok   %s (%.2f s)\n", tests[i].name, took);
            passed++;
        }
    }
    if (left_out) printf("(%d slow tests left to make test)\n", left_out);
    /* the skip count only when there is one, so a complete run ends with
     * exactly "N passed, N failed" */
    if (skipped) printf("%d passed, %d failed, %d skipped\n", passed, failed, skipped);
    else printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
