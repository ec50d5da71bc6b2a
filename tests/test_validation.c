/*
 * One rule for the public API's input: what is out of range is refused by
 * name (Reliability II, items 9-12).
 */
#include "test.h"
#include "cli.h"

#include <limits.h>
#include <math.h>
#include <string.h>

/* Dates: no signed overflow, no float-cast overflow, no silent nonsense. */
TEST(validation_dates)
{
    CHECK(isnan(sky_julian_day(0, INT_MIN, 1, 0, 0, 0.0)), "a month of INT_MIN is refused (NaN)");
    CHECK(isnan(sky_julian_day(INT_MAX, 1, 1, 0, 0, 0.0)), "a year of INT_MAX is refused (NaN)");
    CHECK(isnan(sky_julian_day(2026, 13, 1, 0, 0, 0.0)) && isnan(sky_julian_day(2026, 1, 1, 0, 0, NAN)),
          "month 13 and a NaN second are refused");
    double jd = sky_julian_day(2026, 3, 20, 12, 0, 0.0);
    int y = 0, m = 0, d = 0;
    double f = -1.0;
    CHECK(sky_calendar(jd, &y, &m, &d, &f) == SKY_OK && y == 2026 && m == 3 && d == 20 && fabs(f - 0.5) < 1e-9,
          "2026-03-20 12:00 round-trips (%d-%d-%d %.3f)", y, m, d, f);
    const double bad[6] = {3e18, 1e17, -1e19, 1e19, NAN, INFINITY};
    for (int i = 0; i < 6; i++) {
        y = m = d = 7;
        sky_result rc = sky_calendar(bad[i], &y, &m, &d, &f);
        CHECK(rc == SKY_ERR_INVALID_ARGUMENT && y == 0 && m == 0 && d == 0, "sky_calendar(%g) is refused (%d)", bad[i],
              rc);
    }
    CHECK(sky_calendar(sky_julian_day(-999999, 1, 1, 0, 0, 0.0), &y, NULL, NULL, NULL) == SKY_OK && y == -999999,
          "a million years back still converts (%d)", y);
}

/* The config's fields: out of range, NaN or infinite is refused, naming
 * the field; an empty sky cannot carry features. */
TEST(validation_config_fields_named)
{
    char err[256];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, 16, 16, SKY_GL_AUTO, 0, err, sizeof err)) {
        CHECK(0, "%s", err);
        return;
    }
    /* each refused by every field: moon_scale, star_control_magnitude,
     * bortle (0 or 1..9), solar_activity (0..1 with solar_activity_manual) */
    const float values[5] = {NAN, INFINITY, -1.0f, 1e30f, 0.2f};
    static const char *const names[4] = {"moon_scale", "star_control_magnitude", "bortle", "solar_activity"};
    for (int field = 0; field < 4; field++)
        for (int i = 0; i < 5; i++) {
            if (field == 3 && values[i] == 0.2f) continue; /* a fine activity */
            sky_config cfg;
            memset(&cfg, 0, sizeof cfg);
            cfg.get_proc_address = sky_osmesa_loader();
            if (field == 0) cfg.moon_scale = values[i];
            else if (field == 1) cfg.star_control_magnitude = values[i];
            else if (field == 2) cfg.bortle = values[i];
            else {
                cfg.solar_activity_manual = 1;
                cfg.solar_activity = values[i];
            }
            const char *name = names[field];
            sky *s = sky_create(&cfg, err, sizeof err);
            CHECK(s == NULL && strstr(err, name), "%s = %g is refused by name: %s", name, (double)values[i], err);
            sky_destroy(s);
        }
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.get_proc_address = sky_osmesa_loader();
    cfg.features = 0xffffffffu;
    sky *s = sky_create(&cfg, err, sizeof err);
    CHECK(s == NULL && strstr(err, "features"), "features 0xffffffff is refused, not an empty sky: %s", err);
    sky_destroy(s);
    cfg.features = SKY_FEATURES_NONE;
    s = sky_create(&cfg, err, sizeof err);
    CHECK(s != NULL, "SKY_FEATURES_NONE alone is the empty sky: %s", err);
    sky_destroy(s);
    /* solar_activity_manual is 0 or 1; bortle 1..9 and a manual activity
     * of 0 (solar minimum) are accepted */
    cfg.features = 0;
    cfg.solar_activity_manual = 2;
    s = sky_create(&cfg, err, sizeof err);
    CHECK(s == NULL && strstr(err, "solar_activity_manual"), "solar_activity_manual 2 is refused: %s", err);
    sky_destroy(s);
    cfg.solar_activity_manual = 1;
    cfg.solar_activity = 0.0f;
    cfg.bortle = 9.0f;
    s = sky_create(&cfg, err, sizeof err);
    CHECK(s != NULL, "Bortle 9 at solar minimum is accepted: %s", err);
    sky_destroy(s);
    sky_osmesa_destroy(&ctx);
}

/* A projection of aspect 1:8192 (and 8192:1) is not singular. */
TEST(validation_extreme_aspect_ratio)
{
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, NULL)) {
        CHECK(0, "fixture");
        return;
    }
    float view[16], proj[16];
    for (int k = 0; k < 2; k++) {
        int w = k ? 8192 : 1, h = k ? 1 : 8192;
        sky_cli_camera_at(180.0, 20.0, 60.0, w, h, view, proj);
        sky_result rc = sky_draw(f.s, view, proj);
        CHECK(rc == SKY_OK, "%dx%d: %s", w, h, sky_last_error(f.s));
    }
    fixture_close(&f);
}

/* LDR output into a float target: display values within 0..1 (the dither
 * must not push a black pixel to -0.5/255). */
TEST(validation_ldr_in_float_target_stays_in_range)
{
    enum { W = 64, H = 48 };
    fixture f;
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.output = SKY_OUTPUT_LDR;
    if (fixture_open_sized(&f, W, H, 1, SKY_GL_AUTO, &cfg)) {
        CHECK(0, "fixture");
        return;
    }
    sky_params p = sky_default_params();
    p.time = 0.0f; /* a night: values near 0, where the dither could go below */
    sky_set_params(f.s, &p);
    float view[16], proj[16];
    sky_cli_camera_at(180.0, -30.0, 60.0, W, H, view, proj); /* much of it below the horizon */
    CHECK(sky_draw(f.s, view, proj) == SKY_OK, "draw: %s", sky_last_error(f.s));
    sky_osmesa_finish(&f.ctx);
    const float *px = f.ctx.pixels;
    float lo = 1.0f, hi = 0.0f;
    for (int i = 0; i < W * H * 4; i++)
        if (i % 4 != 3) lo = px[i] < lo ? px[i] : lo, hi = px[i] > hi ? px[i] : hi;
    NOTE("LDR values in a float target: %g .. %g", (double)lo, (double)hi);
    CHECK(lo >= 0.0f && hi <= 1.0f, "within 0..1 (%g .. %g)", (double)lo, (double)hi);
    fixture_close(&f);
}
