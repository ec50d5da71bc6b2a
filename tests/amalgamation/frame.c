/*
 * A program built from the amalgamation alone (test_amalgamation.c copies
 * it beside build/amalgamation/sky.c and sky.h and compiles the three at
 * -std=c11 -pedantic): one fisheye frame through OSMesa, with the inputs
 * sky-render gives a sky for the same options, written as a binary PPM
 * (rows top first, as sky-render's PNG).
 *
 *   frame OUT.ppm SIZE core|compat FEATURES COVER HEIGHT DENSITY SUNSET SPEED TIME
 *
 * FEATURES is the sky_features mask as a number; the sliders are parsed as
 * sky-render parses them (strtod, then float).
 */
#include "sky.h"

#include <GL/osmesa.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static sky_gl_proc loader(const char *name) { return (sky_gl_proc)OSMesaGetProcAddress(name); }

int main(int argc, char **argv)
{
    if (argc != 11) {
        fprintf(stderr, "usage: frame OUT.ppm SIZE core|compat FEATURES COVER HEIGHT DENSITY SUNSET SPEED TIME\n");
        return 2;
    }
    int n = atoi(argv[2]), core = !strcmp(argv[3], "core");
    if (n < 1 || n > 4096) return 2;
    /* as demo/osmesa_ctx.c asks: a 3.3 core context, or any legacy one */
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE,
                           core ? OSMESA_CORE_PROFILE : OSMESA_COMPAT_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION,
                           core ? 3 : 1, OSMESA_CONTEXT_MINOR_VERSION, core ? 3 : 0, 0};
    OSMesaContext ctx = OSMesaCreateContextAttribs(attribs, NULL);
    unsigned char *px = malloc((size_t)n * (size_t)n * 4);
    if (!ctx || !px || !OSMesaMakeCurrent(ctx, px, GL_UNSIGNED_BYTE, n, n)) {
        fprintf(stderr, "frame: no OSMesa context\n");
        return 1;
    }
    /* the configuration sky-render makes (demo/cli.c, sky_cli_config) */
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = (unsigned)strtoul(argv[4], NULL, 10);
    cfg.gl_profile = core ? SKY_GL_CORE33 : SKY_GL_COMPAT20;
    cfg.output = SKY_OUTPUT_LDR;
    sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_EARTH, &cfg.atmosphere_params);
    cfg.get_proc_address = loader;
    char err[512];
    sky *s = sky_create(&cfg, err, sizeof err);
    if (!s) {
        fprintf(stderr, "frame: %s\n", err);
        return 1;
    }
    sky_params p = sky_default_params();
    float *slider[6] = {&p.cover, &p.height, &p.density, &p.sunset, &p.speed, &p.time};
    for (int k = 0; k < 6; k++) *slider[k] = (float)strtod(argv[5 + k], NULL);
    /* sky-render's observer without --date: sky.h's default place and day */
    sky_observer where;
    memset(&where, 0, sizeof where);
    where.julian_day_utc = sky_julian_day(2026, 3, 20, 12, 0, 0.0);
    where.latitude_deg = 40.0;
    where.time_from_params = 1;
    if (sky_set_params(s, &p) < 0 || sky_set_observer(s, &where) < 0 || sky_set_elapsed(s, 0.0) < 0 ||
        sky_set_exposure_bias(s, 0.0f) < 0 || sky_draw_fisheye(s) < 0) {
        fprintf(stderr, "frame: %s\n", sky_last_error(s));
        return 1;
    }
    void (*finish)(void) = (void (*)(void))loader("glFinish");
    if (finish) finish();
    FILE *f = fopen(argv[1], "wb");
    if (!f) return 1;
    fprintf(f, "P6\n%d %d\n255\n", n, n);
    for (int y = n - 1; y >= 0; y--) /* OSMesa's rows are bottom first */
        for (int x = 0; x < n; x++) fwrite(px + ((size_t)y * (size_t)n + (size_t)x) * 4, 1, 3, f);
    int rc = fclose(f) == 0 ? 0 : 1;
    sky_destroy(s);
    OSMesaDestroyContext(ctx);
    free(px);
    return rc;
}
