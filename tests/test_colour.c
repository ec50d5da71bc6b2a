/*
 * Look: what the 8-bit output keeps of the sky's colours, and the one
 * ground below the horizon (tools/colour.c measures both, as sky-bench's
 * colour section does).
 */
#include "test.h"
#include "colour.h"

#include <math.h>
#include <string.h>

static int measure(sky_atmosphere_path path, sky_tone_map tm, double sun, int toward, sky_colour_row *r)
{
    char err[256];
    if (sky_colour_measure(path, tm, SKY_GL_AUTO, sun, toward, 320, 180, r, err, sizeof err)) {
        CHECK(0, "colour measure: %s", err);
        return -1;
    }
    return 0;
}

/* Two paths at three sun heights, facing the sun, with the default tone
 * map: the targets (hue shift median <= 3, p90 <= 8 degrees;
 * saturation kept median >= 0.85, p10 >= 0.6; clipped <= 1 %). */
TEST(colour_hue_and_saturation_kept)
{
    const sky_atmosphere_path paths[2] = {SKY_ATMOSPHERE_RAYLEIGH, SKY_ATMOSPHERE_HILLAIRE};
    const double suns[3] = {0.5, 8.0, 30.0};
    for (int p = 0; p < 2; p++)
        for (int k = 0; k < 3; k++) {
            sky_colour_row r;
            if (measure(paths[p], SKY_TONE_MAP_HUE, suns[k], 1, &r)) return;
            NOTE("%s, sun %g: %d pixels, saturation kept %.2f / %.2f, hue shift %.1f / %.1f deg, clipped %.2f %%",
                 p ? "hillaire" : "rayleigh", suns[k], r.counted, r.saturation_kept_median, r.saturation_kept_p10,
                 r.hue_shift_median, r.hue_shift_p90, 100.0 * r.clipped);
            char why[128];
            CHECK(r.counted > 1000, "enough coloured sky pixels (%d)", r.counted);
            CHECK(sky_colour_row_ok(&r, why, sizeof why), "%s, sun %g: %s", p ? "hillaire" : "rayleigh", suns[k], why);
        }
}

/* The measure sees what the issue saw in the per-channel filmic curve:
 * near the horizon at sunset, orange turned yellow and pale. */
TEST(colour_old_curve_fails_the_measure)
{
    sky_colour_row r;
    if (measure(SKY_ATMOSPHERE_RAYLEIGH, SKY_TONE_MAP_FILMIC, 0.5, 1, &r)) return;
    NOTE("filmic, rayleigh, sun 0.5: saturation kept %.2f / %.2f, hue shift %.1f / %.1f deg", r.saturation_kept_median,
         r.saturation_kept_p10, r.hue_shift_median, r.hue_shift_p90);
    CHECK(r.hue_shift_p90 > 8.0 && r.saturation_kept_median < 0.85, "the old curve shifts hue (%.1f) and pales (%.2f)",
          r.hue_shift_p90, r.saturation_kept_median);
}

/* Below the horizon: no column under a low sun (the analytic paths used
 * to mirror the horizon downward), and a twilight sky lights its ground
 * (Hillaire's table left it black). */
TEST(colour_one_ground_below_the_horizon)
{
    const sky_atmosphere_path paths[4] = {SKY_ATMOSPHERE_GRADIENT, SKY_ATMOSPHERE_PREETHAM, SKY_ATMOSPHERE_RAYLEIGH,
                                          SKY_ATMOSPHERE_HILLAIRE};
    static const char *const names[4] = {"gradient", "preetham", "rayleigh", "hillaire"};
    for (int p = 0; p < 4; p++) {
        sky_colour_row low, twilight;
        if (measure(paths[p], SKY_TONE_MAP_HUE, 3.0, 1, &low) || measure(paths[p], SKY_TONE_MAP_HUE, -4.0, 1, &twilight))
            return;
        NOTE("%s: ground under a 3-degree sun %.3f x the rest; at -4 degrees the ground is %.3f of the sky", names[p],
             low.pillar, twilight.ground_to_sky);
        CHECK(low.pillar > 0.0 && low.pillar <= 1.05, "%s: no column under the sun (%.3f)", names[p], low.pillar);
        CHECK(twilight.ground_to_sky >= 0.05, "%s: a twilight ground, not black (%.3f)", names[p],
              twilight.ground_to_sky);
    }
}

static double mean_luminance_of(const image *im)
{
    double s = 0.0;
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++) s += image_luminance(im, x, y);
    return s / (im->w * im->h);
}

/* The new default keeps noon about as bright as the old curve showed it
 * (within 10 %). */
TEST(colour_noon_as_bright_as_before)
{
    scene hue = scene_default(), filmic;
    hue.params.time = 0.5f;
    hue.params.cover = 0.35f;
    hue.w = 320;
    hue.h = 180;
    filmic = hue;
    filmic.cfg.tone_map = SKY_TONE_MAP_FILMIC;
    image a, b;
    if (render_scene(&hue, 0, SKY_GL_AUTO, &a) || render_scene(&filmic, 0, SKY_GL_AUTO, &b)) {
        CHECK(0, "render failed");
        return;
    }
    double la = mean_luminance_of(&a), lb = mean_luminance_of(&b);
    NOTE("noon's mean luminance: %.4f with hue, %.4f with filmic", la, lb);
    CHECK(fabs(la / lb - 1.0) <= 0.10, "noon within 10 %% of the old brightness (%.3f)", la / lb);
    image_free(&a);
    image_free(&b);
}

/* The day's end (issue "Dusk and night"): on the default path and on
 * Hillaire's the sky shows at most 0.5 of noon's brightness at -6
 * degrees, 0.2 at -12 and 0.1 at -18, never brightens by more than 5 %
 * from one step to the next below 4 degrees, and sunset is no brighter
 * than noon (sky_dusk_ok). Under full adaptation (the exposure before it)
 * the default path showed 0.88 of noon at -6 and 0.65 at -12, Hillaire's
 * sunset 1.16. */
SLOW_TEST(colour_day_ends_darker)
{
    static const sky_atmosphere_path paths[] = {SKY_ATMOSPHERE_GRADIENT, SKY_ATMOSPHERE_HILLAIRE};
    for (int p = 0; p < 2; p++) {
        double rel[SKY_DUSK_SUNS];
        char err[256], why[128];
        if (sky_dusk_measure(paths[p], SKY_GL_AUTO, 320, 180, rel, err, sizeof err)) {
            CHECK(0, "%s", err);
            continue;
        }
        NOTE("%s: -6 %.3f, -12 %.3f, -18 %.3f of noon; sunset %.3f", p ? "hillaire" : "gradient", rel[5], rel[7],
             rel[9], rel[3]);
        CHECK(sky_dusk_ok(rel, why, sizeof why), "%s: %s", p ? "hillaire" : "gradient", why);
    }
}

/* The partial adaptation leaves daylight alone: noon shows the same with
 * any exposure_range, while at nautical dusk the smallest range (nearly
 * the old full adaptation) shows the sky brighter than the default. */
TEST(colour_exposure_range_spares_noon)
{
    static const float times[2] = {0.5f, 0.79f}; /* noon; the sun near -10 degrees */
    for (int t = 0; t < 2; t++) {
        scene def = scene_default(), full;
        def.params.time = times[t];
        def.params.cover = 0.0f;
        def.w = 160;
        def.h = 90;
        full = def;
        full.cfg.exposure_range = 0.01f;
        image a, b;
        if (render_scene(&def, 0, SKY_GL_AUTO, &a) || render_scene(&full, 0, SKY_GL_AUTO, &b)) {
            CHECK(0, "render failed");
            return;
        }
        double la = mean_luminance_of(&a), lb = mean_luminance_of(&b);
        NOTE("time %.2f: mean luminance %.4f by default, %.4f nearly fully adapted", (double)times[t], la, lb);
        if (t == 0)
            CHECK(fabs(la / lb - 1.0) <= 0.01, "noon moved with the exposure range: %.4f against %.4f", la, lb);
        else
            CHECK(la < 0.6 * lb, "dusk is not darker than under full adaptation: %.4f against %.4f", la, lb);
        image_free(&a);
        image_free(&b);
    }
}

/* The night (issue "Dusk and night"), on the default path and Hillaire's:
 * a moonless sky dark blue (hue 190-260, b/r >= 1.2, its brightest
 * channel's median 8-40 of 255), a full moon's sky a day-for-night blue
 * you can see (hue 190-250, brightest >= 40, at most 0.35 of noon) and
 * brighter than the moonless one (its blue median, 47-93 against 35); the full
 * moon's disc keeps its HDR hue within 12 degrees (it is bright enough for
 * the cones: 33 against 33; 347 before the disc's own exposure was
 * undone for the shift). Before, both were grey (b/r 1.0-1.3)
 * and the full moon's darker than the moonless sky. The b/r >= 1.6
 * for the full moon, its sky each path's own model lit by the moon: the
 * blue point's display ratio is 1.67. */
SLOW_TEST(colour_night_is_blue)
{
    static const sky_atmosphere_path paths[] = {SKY_ATMOSPHERE_GRADIENT, SKY_ATMOSPHERE_HILLAIRE};
    for (int p = 0; p < 2; p++) {
        const char *name = p ? "hillaire" : "gradient";
        sky_night_view v[2];
        double noon;
        char err[256], why[128];
        if (sky_dusk_brightness(paths[p], SKY_GL_AUTO, 50.0, 320, 180, &noon, err, sizeof err) ||
            sky_night_measure(paths[p], SKY_GL_AUTO, 0, 320, 180, &v[0], err, sizeof err) ||
            sky_night_measure(paths[p], SKY_GL_AUTO, 1, 320, 180, &v[1], err, sizeof err)) {
            CHECK(0, "%s: %s", name, err);
            continue;
        }
        for (int m = 0; m < 2; m++)
            NOTE("%s, %s: median (%d, %d, %d), hue %.0f, b/r %.2f, %.3f of noon", name, m ? "full moon" : "moonless",
                 v[m].median[0], v[m].median[1], v[m].median[2], v[m].hue, v[m].b_over_r, v[m].mean / noon);
        CHECK(sky_night_ok(&v[0], 0, noon, why, sizeof why), "%s, moonless: %s", name, why);
        int top = v[1].median[2] > v[1].median[1] ? v[1].median[2] : v[1].median[1];
        CHECK(v[1].hue >= 190.0 && v[1].hue <= 250.0 && v[1].b_over_r >= 1.6 && top >= 40 && v[1].mean <= 0.35 * noon,
              "%s, full moon: hue %.0f, b/r %.2f, brightest %d, %.3f of noon", name, v[1].hue, v[1].b_over_r, top,
              v[1].mean / noon);
        /* the moon's disc, bright enough for the cones, keeps its hue */
        double hdr_hue, ldr_hue;
        if (sky_moon_disc_hues(paths[p], SKY_GL_AUTO, 96, 96, &hdr_hue, &ldr_hue, err, sizeof err))
            CHECK(0, "%s: %s", name, err);
        else
            CHECK(fabs(remainder(ldr_hue - hdr_hue, 360.0)) <= 12.0,
                  "%s: the moon's disc's hue %.1f in HDR, %.1f in 8 bits", name, hdr_hue, ldr_hue);
        /* (medians: the mean of the moonless view is the flicker stars'; a
         * quarter brighter at least: Hillaire's sky 110 degrees from the
         * moon is its darkest, 47 against 35, where the gradient's is 93) */
        CHECK(v[1].median[2] > 1.25 * v[0].median[2], "%s: the full moon's sky (blue median %d) not brighter than the "
              "moonless one's (%d)", name, v[1].median[2], v[0].median[2]);
    }
}
