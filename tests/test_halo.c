/*
 * The halos (SKY_HALO, halo.c), measured as the light they add: the same
 * HDR frame with and without the feature, each pixel's difference binned
 * by its angle from the sun. In cirrus with the sun 30 degrees up: the
 * 22 degree halo's red peak at 22 +- 0.7 degrees and inside its blue (ice's
 * minimum deviation, dispersion), the parhelia at the sun's elevation as
 * far out in azimuth as horizontal plates put them and brighter than the
 * halo there; nothing without the thin layer's ice.
 */
#include "test.h"
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { W = 480, H = 270, BINS = 240 }; /* bins of 0.25 degrees, 0..60 */
#define BIN_DEG 0.25
#define SUN_TIME 0.3625f /* the sun 29.2 degrees up at the equinox at 40 N, azimuth 118.1 */

/* An HDR frame of a weather with or without the halos (test_rainbow.c's
 * optics_frame, at 40 N). */
static int frame(sky_weather_state state, double yaw, double pitch, int halo, sky_gl_profile profile, float *rgb,
                 sky_lighting *light, int *drawn)
{
    sky_weather w;
    sky_weather_preset(state, &w);
    return optics_frame(halo ? SKY_HALO : 0, "halo", &w, SUN_TIME, 40.0, yaw, pitch, profile, W, H, rgb, light,
                        drawn);
}

static void halo_checks(sky_gl_profile gl, const char *name)
{
    static float with[W * H * 3], without[W * H * 3];
    sky_lighting l;
    double yaw = 118.1, pitch = 29.2;
    int drawn = 0;
    if (frame(SKY_WEATHER_CIRRUS, yaw, pitch, 1, gl, with, &l, &drawn) ||
        frame(SKY_WEATHER_CIRRUS, yaw, pitch, 0, gl, without, NULL, NULL)) {
        CHECK(0, "%s: the frames rendered", name);
        return;
    }
    CHECK(drawn, "%s: the halo is drawn in cirrus with the sun out", name);
    float view[16], proj[16];
    sky_cli_camera_at(yaw, pitch, 90.0, W, H, view, proj);
    const float *s = l.sun_direction;
    double sun_el = asin(s[1]);
    static double sum[BINS][3];
    static int count[BINS];
    memset(sum, 0, sizeof sum);
    memset(count, 0, sizeof count);
    /* the parhelia: along the sun's elevation, the added light by azimuth from it */
    double dog_best = 0.0, dog_at = 0.0, halo_above = 0.0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double d[3];
            optics_pixel_dir(view, proj, W, H, x, y, d);
            const float *a = with + 3 * (y * W + x), *b = without + 3 * (y * W + x);
            double added[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
            double luma = 0.2126 * added[0] + 0.7152 * added[1] + 0.0722 * added[2];
            double el = asin(d[1]), rho = acos(fmin(fmax(d[0] * s[0] + d[1] * s[1] + d[2] * s[2], -1.0), 1.0));
            if (fabs(el - sun_el) < 0.3 * M_PI / 180.0) {
                double az = fabs(atan2(d[0] * s[2] - d[2] * s[0], d[0] * s[0] + d[2] * s[2])) * 180.0 / M_PI;
                if (az > 15.0 && az < 45.0 && luma > dog_best) dog_best = luma, dog_at = az;
            }
            if (fabs(el - sun_el) < 6.0 * M_PI / 180.0) continue; /* the halo away from the parhelia */
            int k = (int)(rho * 180.0 / M_PI / BIN_DEG);
            if (k < 0 || k >= BINS) continue;
            for (int c = 0; c < 3; c++) sum[k][c] += added[c];
            count[k]++;
        }
    double red = 0.0, blue = 0.0, red_v = -1.0, blue_v = -1.0;
    for (int k = (int)(18.0 / BIN_DEG); k < (int)(27.0 / BIN_DEG); k++) {
        if (count[k] < 4) continue;
        if (sum[k][0] / count[k] > red_v) red_v = sum[k][0] / count[k], red = (k + 0.5) * BIN_DEG;
        if (sum[k][2] / count[k] > blue_v) blue_v = sum[k][2] / count[k], blue = (k + 0.5) * BIN_DEG;
    }
    /* the halo's light at the parhelia's angular distance from the sun, off their row */
    double dog_rho = acos(sin(sun_el) * sin(sun_el) + cos(sun_el) * cos(sun_el) * cos(dog_at * M_PI / 180.0)) *
                     180.0 / M_PI;
    int k = (int)(dog_rho / BIN_DEG);
    if (k >= 0 && k < BINS && count[k])
        halo_above = (0.2126 * sum[k][0] + 0.7152 * sum[k][1] + 0.0722 * sum[k][2]) / count[k];
    /* where horizontal plates put them: the minimum deviation for Bravais'
     * index at the sun's elevation, ice at 550 nm (1.3097) */
    double n = 1.3097, np = sqrt(n * n - sin(sun_el) * sin(sun_el)) / cos(sun_el);
    double want = (2.0 * asin(np * 0.5) - M_PI / 3.0) * 180.0 / M_PI;
    NOTE("%s: the 22 degree halo's red peak at %.2f, blue at %.2f degrees; parhelia %.2f degrees out in azimuth "
         "(plates: %.2f), %.3g kcd/m^2 against the halo's %.3g there", name, red, blue, dog_at, want, dog_best,
         halo_above);
    CHECK(fabs(red - 22.0) <= 0.7, "%s: the halo's red peak at 22 +- 0.7 degrees (%.2f)", name, red);
    CHECK(red < blue, "%s: its red inside its blue (%.2f < %.2f)", name, red, blue);
    CHECK(fabs(dog_at - want) <= 1.5, "%s: the parhelia %.2f degrees out (plates: %.2f)", name, dog_at, want);
    CHECK(dog_best > 1.5 * halo_above, "%s: brighter than the halo (%.3g against %.3g)", name, dog_best, halo_above);
}

TEST(halo_22_and_parhelia_core) { halo_checks(SKY_GL_CORE33, "core"); }
TEST(halo_22_and_parhelia_compat) { halo_checks(SKY_GL_COMPAT20, "compat"); }

/* No ice, no halo: the clear state has no thin layer; the frame is the
 * one without the feature and the optics variant stays undrawn. A halo
 * without the clouds is refused. */
TEST(halo_none_without_ice)
{
    static float with[W * H * 3], without[W * H * 3];
    int drawn = 1;
    if (frame(SKY_WEATHER_CLEAR, 118.1, 29.2, 1, SKY_GL_AUTO, with, NULL, &drawn) ||
        frame(SKY_WEATHER_CLEAR, 118.1, 29.2, 0, SKY_GL_AUTO, without, NULL, NULL)) {
        CHECK(0, "the frames rendered");
        return;
    }
    double most = 0.0;
    for (int i = 0; i < W * H * 3; i++) most = fmax(most, fabs(with[i] - without[i]));
    CHECK(!drawn && most == 0.0, "clear: no halo drawn (drawn %d, largest difference %.3g)", drawn, most);
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_SUN | SKY_HALO;
    cfg.get_proc_address = sky_osmesa_loader();
    char err[256] = "";
    sky *s = sky_create(&cfg, err, sizeof err);
    CHECK(!s && strstr(err, "SKY_HALO"), "SKY_HALO without the clouds refused: %s", err);
    sky_destroy(s);
}
