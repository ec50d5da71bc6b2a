/*
 * The weather (sky.h, "Weather"; docs/guide.md, "Weather"): the named
 * states, the checks of sky_set_weather, the transitions on the sky's own
 * clock, the wind's drift, and what a state does to the picture and to
 * the host's light at noon (the sun at 50 degrees: the default date and
 * place, the equinox at 40 N, time 0.5).
 */
#define GL_GLEXT_PROTOTYPES 1
#include "test.h"
#include "cli.h"
#include "sky_internal.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* (test.h) a named state's numbers */
sky_weather weather_preset(sky_weather_state state)
{
    sky_weather w;
    memset(&w, 0, sizeof w);
    sky_weather_preset(state, &w);
    return w;
}

static double luma(const float *rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

/* A sky of the default features (the weather's included) in a small
 * context; -1 after a failed CHECK. open_two_skies: two, or none. */
static int open_sky(fixture *f)
{
    if (fixture_open(f, SKY_GL_AUTO, NULL) == 0) return 0;
    CHECK(0, "no sky");
    return -1;
}
static int open_two_skies(fixture *a, fixture *b)
{
    if (open_sky(a)) return -1;
    if (open_sky(b) == 0) return 0;
    fixture_close(a);
    return -1;
}

TEST(weather_states_named_and_in_range)
{
    for (int i = 0; i < SKY_WEATHER_COUNT; i++) {
        const char *name = sky_weather_name((sky_weather_state)i);
        CHECK(name && sky_weather_from_name(name) == i, "state %d's name '%s' round-trips", i, name ? name : "");
        sky_weather w;
        CHECK(sky_weather_preset((sky_weather_state)i, &w) == SKY_OK, "state %d has numbers", i);
        CHECK(w.cover >= 0 && w.cover <= 1 && w.density >= 0 && w.density <= 1 && w.upper >= 0 && w.upper <= 1 &&
                  w.visibility_km >= 0.05f && w.visibility_km <= 300 && w.light_through > 0 && w.light_through <= 1 &&
                  w.precipitation >= 0 && w.precipitation <= 1,
              "%s's numbers lie in their ranges", name);
        CHECK((w.precipitation > 0) == (w.precipitation_kind != SKY_PRECIPITATION_NONE),
              "%s: a kind exactly when something falls", name);
    }
    sky_weather w;
    CHECK(sky_weather_preset(SKY_WEATHER_COUNT, &w) == SKY_ERR_INVALID_ARGUMENT, "out of range refused");
    CHECK(sky_weather_preset((sky_weather_state)-1, &w) == SKY_ERR_INVALID_ARGUMENT, "negative refused");
    CHECK(sky_weather_preset(SKY_WEATHER_FOG, NULL) == SKY_ERR_INVALID_ARGUMENT, "NULL refused");
    CHECK(sky_weather_name(SKY_WEATHER_COUNT) == NULL && sky_weather_from_name("drizzle") == -1 &&
              sky_weather_from_name(NULL) == -1,
          "unknown names and states");
    /* the orderings: fog closes the range, a storm has lightning */
    CHECK(weather_preset(SKY_WEATHER_FOG).visibility_km <= 1.0f, "fog: visibility <= 1 km");
    CHECK(weather_preset(SKY_WEATHER_STORM).lightning_per_minute > 0 && weather_preset(SKY_WEATHER_RAIN).lightning_per_minute == 0,
          "only the storm has lightning");
    CHECK(weather_preset(SKY_WEATHER_SNOW).precipitation_kind == SKY_PRECIPITATION_SNOW, "snow falls as snow");
    CHECK(weather_preset(SKY_WEATHER_CIRRUS).upper > 0.5f && weather_preset(SKY_WEATHER_CIRRUS).cover < 0.2f,
          "cirrus: the thin high layer, little else");
}

TEST(weather_set_rejects_and_clamps)
{
    fixture f;
    if (open_sky(&f)) return;
    sky_weather storm = weather_preset(SKY_WEATHER_STORM), before, after, bad;
    CHECK(sky_set_weather(NULL, &storm, 0) == SKY_ERR_INVALID_ARGUMENT, "NULL sky");
    sky_get_weather(f.s, &before, NULL);
    CHECK(sky_set_weather(f.s, NULL, 0) == SKY_ERR_INVALID_ARGUMENT, "NULL target");
    bad = storm;
    bad.density = NAN;
    CHECK(sky_set_weather(f.s, &bad, 0) == SKY_ERR_INVALID_ARGUMENT && strstr(sky_last_error(f.s), "density"),
          "NaN density refused, named: %s", sky_last_error(f.s));
    bad = storm;
    bad.precipitation_kind = (sky_precipitation)7;
    CHECK(sky_set_weather(f.s, &bad, 0) == SKY_ERR_INVALID_ARGUMENT, "an unknown kind refused");
    static const double seconds[3] = {-1.0, NAN, INFINITY};
    for (int i = 0; i < 3; i++)
        CHECK(sky_set_weather(f.s, &storm, seconds[i]) == SKY_ERR_INVALID_ARGUMENT, "seconds %g refused", seconds[i]);
    sky_get_weather(f.s, &after, NULL);
    CHECK(!memcmp(&before, &after, sizeof before), "a refused call changes nothing");
    bad = storm;
    bad.cover = 2.0f;
    bad.wind_from_deg = 450.0f;
    bad.wind_speed_ms = INFINITY;
    CHECK(sky_set_weather(f.s, &bad, 0) == SKY_CLAMPED && strstr(sky_last_error(f.s), "cover"),
          "cover 2 clamped, named: %s", sky_last_error(f.s));
    int moving = -1;
    sky_get_weather(f.s, &after, &moving);
    CHECK(after.cover == 1.0f && fabsf(after.wind_from_deg - 90.0f) < 1e-3f && after.wind_speed_ms == 60.0f &&
              moving == 0,
          "clamped to 1, the wind from 90 at 60 m/s, not moving (%g, %g, %g, %d)", after.cover, after.wind_from_deg,
          after.wind_speed_ms, moving);
    CHECK(sky_get_weather(f.s, NULL, NULL) == SKY_ERR_INVALID_ARGUMENT, "NULL out");
    fixture_close(&f);
    /* a sky made without the weather's shading says so */
    sky_config plain;
    memset(&plain, 0, sizeof plain);
    plain.features = SKY_CLOUDS | SKY_SUN;
    if (fixture_open(&f, SKY_GL_AUTO, &plain) == 0) {
        CHECK(sky_set_weather(f.s, &storm, 0.0) == SKY_ERR_UNSUPPORTED && strstr(sky_last_error(f.s), "SKY_WEATHER"),
              "without SKY_WEATHER: %s", sky_last_error(f.s));
        fixture_close(&f);
    }
}

/* Once set, the weather owns cover and density; sky_set_params keeps the
 * rest. Before, sky_get_weather reports the sliders' clouds. */
TEST(weather_owns_cover_and_density)
{
    fixture f;
    if (open_sky(&f)) return;
    sky_params p = sky_default_params();
    p.cover = 0.3f;
    p.density = 0.6f;
    sky_set_params(f.s, &p);
    sky_weather w;
    sky_get_weather(f.s, &w, NULL);
    CHECK(w.cover == 0.3f && w.density == 0.6f && w.light_through == 1.0f, "without a weather: the sliders' clouds");
    sky_weather overcast = weather_preset(SKY_WEATHER_OVERCAST);
    CHECK(sky_set_weather(f.s, &overcast, 0.0) == SKY_OK, "set: %s", sky_last_error(f.s));
    p.cover = 0.1f;
    p.density = 0.1f;
    p.time = 0.3f;
    sky_set_params(f.s, &p);
    sky_params now;
    sky_get_params(f.s, &now);
    CHECK(now.cover == overcast.cover && now.density == overcast.density && now.time == 0.3f,
          "the weather's cover and density (%g, %g), the host's time (%g)", now.cover, now.density, now.time);
    fixture_close(&f);
}

/* A transition is a function of the running clock: every number eases
 * monotonically from the one state to the other, and a sky stepped there
 * in many small steps stands where one set to that time stands. */
TEST(weather_transition_follows_the_clock)
{
    fixture a, b;
    if (open_two_skies(&a, &b)) return;
    sky_weather fair = weather_preset(SKY_WEATHER_FAIR), storm = weather_preset(SKY_WEATHER_STORM);
    fair.wind_from_deg = 350.0f;
    storm.wind_from_deg = 20.0f; /* the shorter way round is through north */
    sky *skies[2] = {a.s, b.s};
    for (int k = 0; k < 2; k++) {
        sky_set_weather(skies[k], &fair, 0.0);
        sky_set_weather(skies[k], &storm, 20.0);
    }
    sky_weather prev = fair, w;
    int monotone = 1, wind_short = 1;
    for (int i = 0; i <= 100; i++) {
        sky_set_elapsed(a.s, 0.25 * i);
        sky_get_weather(a.s, &w, NULL);
        monotone &= w.cover >= prev.cover && w.density >= prev.density && w.light_through <= prev.light_through &&
                    w.visibility_km <= prev.visibility_km && w.lightning_per_minute >= prev.lightning_per_minute;
        wind_short &= w.wind_from_deg >= 349.9f || w.wind_from_deg <= 20.1f;
        prev = w;
    }
    CHECK(monotone, "every number moves one way from fair to storm");
    CHECK(wind_short, "the wind turns from 350 to 20 through north");
    CHECK(prev.cover == storm.cover && prev.light_through == storm.light_through, "it arrives exactly (t 25 s: %a %a against %a %a)",
          prev.cover, prev.light_through, storm.cover, storm.light_through);
    sky_set_elapsed(a.s, 0.1);
    sky_get_weather(a.s, &w, NULL);
    CHECK(w.density - fair.density < 0.01f * (storm.density - fair.density), "it eases out of the start");
    /* many small steps against one jump to the same time */
    sky_set_elapsed(a.s, 11.0);
    sky_set_elapsed(b.s, 0.0);
    for (int i = 0; i < 330; i++) sky_update(b.s, 1.0 / 30.0);
    sky_weather wa, wb;
    sky_get_weather(a.s, &wa, NULL);
    sky_get_weather(b.s, &wb, NULL);
    CHECK(fabsf(wa.cover - wb.cover) < 1e-5f && fabsf(wa.wind_from_deg - wb.wind_from_deg) < 1e-3f,
          "stepped or set: the same weather (%g / %g)", wa.cover, wb.cover);
    const double *oa = sky_clouds_offsets(a.s->layer_state[SKY_LAYER_CLOUDS]),
                 *ob = sky_clouds_offsets(b.s->layer_state[SKY_LAYER_CLOUDS]);
    double worst = 0.0;
    for (int i = 0; i < 2 * SKY_CLOUD_LAYERS; i++) {
        double d = fabs(oa[i] - ob[i]);
        worst = fmax(worst, fmin(d, 1.0 - d)); /* offsets wrap at 1 */
    }
    NOTE("cloud offsets, stepped against set: %.2g texture periods apart", worst);
    CHECK(worst < 1e-9, "the drift is the wind's integral, however stepped (%g)", worst);
    fixture_close(&a);
    fixture_close(&b);
}

/* The wind carries the clouds: a weather whose wind is the sliders' own
 * (5 m/s along the first layer's direction) drifts them as the sliders
 * do; from the west they move east. */
TEST(weather_wind_drives_the_drift)
{
    fixture a, b;
    if (open_two_skies(&a, &b)) return;
    sky_weather own;
    sky_get_weather(a.s, &own, NULL); /* the sliders' weather */
    sky_set_weather(b.s, &own, 0.0);
    sky_set_elapsed(a.s, 37.0);
    sky_set_elapsed(b.s, 37.0);
    const double *oa = sky_clouds_offsets(a.s->layer_state[SKY_LAYER_CLOUDS]),
                 *ob = sky_clouds_offsets(b.s->layer_state[SKY_LAYER_CLOUDS]);
    double worst = 0.0;
    for (int i = 0; i < 2 * SKY_CLOUD_LAYERS; i++) worst = fmax(worst, fabs(oa[i] - ob[i]));
    CHECK(worst < 1e-6, "the sliders' wind drifts as the sliders do (%g apart)", worst);
    sky_weather west = own;
    west.wind_from_deg = 270.0f;
    west.wind_speed_ms = 10.0f;
    sky_set_weather(b.s, &west, 0.0); /* at once, from the running time 37 */
    sky_set_elapsed(b.s, 40.0);
    double x0 = ob[0], y0 = ob[1];
    sky_set_elapsed(b.s, 41.0);
    double dx = ob[0] - x0, dy = ob[1] - y0;
    /* the texture's offset moves against the clouds: the clouds go east
     * (+x in the dome's plane) when the first layer's offset goes -x */
    CHECK(dx < 0.0 && fabs(dy) < 0.05 * fabs(dx), "a west wind moves the first layer east (offset %g, %g)", dx, dy);
    double speed = hypot(sky_cloud_velocity[0][0], sky_cloud_velocity[0][1]) * 0.2 /* speed slider */ * 10.0 / 5.0;
    CHECK(fabs(hypot(dx, dy) - speed) < 1e-6, "at twice the sliders' rate for 10 m/s (%g, want %g)", hypot(dx, dy),
          speed);
    fixture_close(&a);
    fixture_close(&b);
}

/* ---- the picture and the light at noon -------------------------------------------- */

enum { W = 192, H = 108 };

/* The mean display luminance of a W x H RGBA8 frame (Rec. 709 weights on
 * the 8-bit values), 0..255. */
static double frame_mean(const unsigned char *px)
{
    double sum = 0.0;
    for (int i = 0; i < W * H; i++) sum += 0.2126 * px[4 * i] + 0.7152 * px[4 * i + 1] + 0.0722 * px[4 * i + 2];
    return sum / (W * H);
}

typedef struct shot {
    double mean_display; /* 8-bit: Rec. 709 luminance of the sRGB values / 255 */
    double hdr_sky;      /* HDR: the mean luminance above the horizon, kcd/m^2 */
    double hdr_max, hdr_median;
    int blue;            /* pixels above the horizon bluer than grey       */
    double saturation;   /* 8-bit: mean (max - min) / max above the horizon */
    double above[3], below[3]; /* 8-bit: mean colour (0..255) of the rows
                                  2-8 above and below the horizon's     */
    double horizon_row;  /* 8-bit: the brightest row within 2 of the
                            horizon's, its mean luminance (0..255)       */
    sky_lighting light;
} shot;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The weather at time of day `time` (the time slider), seen from yaw and
 * pitch, in 8 bits and in HDR. */
static int shot_at(const sky_weather *w, float time, double yaw, double pitch, shot *out)
{
    memset(out, 0, sizeof *out);
    for (int hdr = 0; hdr < 2; hdr++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.features = SKY_CLOUDS | SKY_SUN | SKY_WEATHER;
        cfg.output = hdr ? SKY_OUTPUT_HDR : SKY_OUTPUT_LDR;
        fixture f;
        if (fixture_open_sized(&f, W, H, hdr, SKY_GL_AUTO, &cfg)) return -1;
        sky_params p = sky_default_params();
        p.time = time;
        sky_set_params(f.s, &p);
        if (w) sky_set_weather(f.s, w, 0.0);
        sky_set_elapsed(f.s, 3.0);
        float view[16], proj[16];
        sky_cli_camera_at(yaw, pitch, 60.0, W, H, view, proj);
        sky_draw(f.s, view, proj);
        sky_osmesa_finish(&f.ctx);
        scene sc = scene_default();
        sc.w = W, sc.h = H, sc.pitch = pitch, sc.yaw = yaw;
        double hx, hy;
        int horizon = scene_project(&sc, 0.0, yaw, &hx, &hy) == 0 ? (int)hy - 2 : H; /* rows above it */
        if (horizon > H) horizon = H;
        if (!hdr) {
            const unsigned char *px = f.ctx.pixels;
            out->mean_display = frame_mean(px) / 255.0;
            int n = 0;
            for (int y = 0; y < horizon; y++) /* rows bottom first: image row H-1-y */
                for (int x = 0; x < W; x++) {
                    const unsigned char *q = px + 4 * ((H - 1 - y) * W + x);
                    out->blue += q[2] > q[0] + 24;
                    int hi = q[0] > q[1] ? (q[0] > q[2] ? q[0] : q[2]) : (q[1] > q[2] ? q[1] : q[2]);
                    int lo = q[0] < q[1] ? (q[0] < q[2] ? q[0] : q[2]) : (q[1] < q[2] ? q[1] : q[2]);
                    out->saturation += hi ? (double)(hi - lo) / hi : 0.0;
                    n++;
                }
            if (n) out->saturation /= n;
            sky_get_lighting(f.s, &out->light);
            double band[2][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
            int rows[2] = {0, 0};
            for (int k = 0; k < 2; k++)
                for (int y = (int)hy + (k ? 2 : -8); y < (int)hy + (k ? 8 : -2); y++) {
                    if (y < 0 || y >= H) continue;
                    for (int x = 0; x < W; x++)
                        for (int i = 0; i < 3; i++) band[k][i] += px[4 * ((H - 1 - y) * W + x) + i];
                    rows[k]++;
                }
            for (int i = 0; i < 3; i++) {
                out->above[i] = rows[0] ? band[0][i] / (rows[0] * W) : 0.0;
                out->below[i] = rows[1] ? band[1][i] / (rows[1] * W) : 0.0;
            }
            for (int y = (int)hy - 2; y <= (int)hy + 2; y++) {
                if (y < 0 || y >= H) continue;
                double row = 0.0;
                for (int x = 0; x < W; x++) {
                    const unsigned char *q = px + 4 * ((H - 1 - y) * W + x);
                    row += 0.2126 * q[0] + 0.7152 * q[1] + 0.0722 * q[2];
                }
                out->horizon_row = fmax(out->horizon_row, row / W);
            }
        } else {
            const float *px = f.ctx.pixels;
            double *lum = malloc(sizeof(double) * W * H), sum = 0.0;
            int n = 0;
            for (int y = 0; y < horizon && lum; y++)
                for (int x = 0; x < W; x++) {
                    double l = luma(px + 4 * ((H - 1 - y) * W + x));
                    lum[n++] = l;
                    sum += l;
                }
            if (lum && n) {
                qsort(lum, (size_t)n, sizeof *lum, cmp_double);
                out->hdr_sky = sum / n;
                out->hdr_max = lum[n - 1];
                out->hdr_median = lum[n / 2];
            }
            free(lum);
        }
        fixture_close(&f);
    }
    return 0;
}

/* At noon (the sun at 50 degrees on the default date and place), looking
 * south as sky-render's camera does. */
static int noon_shot(const sky_weather *w, double pitch, shot *out) { return shot_at(w, 0.5f, 180.0, pitch, out); }

TEST(weather_overcast_and_storm_at_noon)
{
    sky_weather clear = weather_preset(SKY_WEATHER_CLEAR), overcast = weather_preset(SKY_WEATHER_OVERCAST),
                storm = weather_preset(SKY_WEATHER_STORM);
    shot c, o, s, sun;
    if (noon_shot(&clear, 20.0, &c) || noon_shot(&overcast, 20.0, &o) || noon_shot(&storm, 20.0, &s) ||
        noon_shot(&overcast, 50.0, &sun)) {
        CHECK(0, "the shots rendered");
        return;
    }
    double direct_c = luma(c.light.sun_color), direct_o = luma(o.light.sun_color);
    NOTE("direct sun: overcast %.3f of clear's, storm %.3f", direct_o / direct_c, luma(s.light.sun_color) / direct_c);
    CHECK(direct_o <= 0.2 * direct_c, "overcast: the direct sun <= 0.2 of clear's (%.3f)", direct_o / direct_c);
    NOTE("overcast: %d bluish pixels above the horizon (clear: %d)", o.blue, c.blue);
    CHECK(o.blue == 0 && c.blue > W * H / 4, "overcast: a deck without blue gaps (%d bluish pixels)", o.blue);
    NOTE("overcast facing the sun: brightest %.3g, median %.3g kcd/m^2 (ratio %.2f)", sun.hdr_max, sun.hdr_median,
         sun.hdr_max / sun.hdr_median);
    CHECK(sun.hdr_max <= 1.5 * sun.hdr_median, "overcast facing the sun: brightest <= 1.5 x median (%.2f)",
          sun.hdr_max / sun.hdr_median);
    NOTE("storm: HDR sky %.3f of clear's light; 8-bit mean %.3f against clear's %.3f (%.2f)", s.hdr_sky / c.hdr_sky,
         s.mean_display, c.mean_display, s.mean_display / c.mean_display);
    CHECK(s.hdr_sky <= 0.2 * c.hdr_sky, "storm: its HDR sky <= 0.2 of clear's (%.3f)", s.hdr_sky / c.hdr_sky);
    CHECK(s.mean_display <= 0.75 * c.mean_display, "storm: its 8-bit frame <= 0.75 of clear's mean (%.2f)",
          s.mean_display / c.mean_display);
    /* the ambient greys under a deck: its channels closer together */
    double spread_c = (c.light.ambient_color[2] - c.light.ambient_color[0]) / luma(c.light.ambient_color),
           spread_o = (o.light.ambient_color[2] - o.light.ambient_color[0]) / luma(o.light.ambient_color);
    CHECK(spread_o < 0.5 * spread_c, "overcast's ambient greyer than clear's (blue-red %.3f against %.3f)", spread_o,
          spread_c);
}

/* Rain dimmer and greyer than overcast, snow a flat bright grey: brighter
 * than rain, its beam weak beside its ambient (soft shadows). */
TEST(weather_rain_and_snow_light)
{
    shot o, r, sn;
    sky_weather overcast = weather_preset(SKY_WEATHER_OVERCAST), rain = weather_preset(SKY_WEATHER_RAIN),
                snow = weather_preset(SKY_WEATHER_SNOW);
    if (noon_shot(&overcast, 20.0, &o) || noon_shot(&rain, 20.0, &r) || noon_shot(&snow, 20.0, &sn)) {
        CHECK(0, "the shots rendered");
        return;
    }
    CHECK(r.mean_display < o.mean_display && luma(r.light.ambient_color) < luma(o.light.ambient_color),
          "rain dimmer than overcast (%.3f < %.3f)", r.mean_display, o.mean_display);
    CHECK(sn.mean_display > r.mean_display, "snow's light brighter than rain's (%.3f > %.3f)", sn.mean_display,
          r.mean_display);
    /* greyer: the sky's colour nearer grey under rain than under overcast */
    NOTE("saturation above the horizon: overcast %.3f, rain %.3f", o.saturation, r.saturation);
    CHECK(r.saturation < o.saturation, "rain greyer than overcast (%.3f < %.3f)", r.saturation, o.saturation);
    double beam = luma(sn.light.sun_color) * sin(50.0 * 3.14159265358979 / 180.0), ambient = luma(sn.light.ambient_color);
    NOTE("snow: beam on the level %.2f klx, ambient %.2f klx", beam, ambient);
    CHECK(beam < ambient, "snow: the shadows soft (beam %.2f < ambient %.2f klx)", beam, ambient);
}

/* The weather's light goes through the day's end's exposure as the clear
 * sky's does: a storm at dusk (the sun 4 degrees up, looking at it) shows
 * darker than the clear dusk, never re-brightened. */
TEST(weather_storm_at_dusk_stays_dark)
{
    sky_weather clear = weather_preset(SKY_WEATHER_CLEAR), storm = weather_preset(SKY_WEATHER_STORM);
    shot c, s;
    if (shot_at(&clear, 0.73631f, 267.0, 10.0, &c) || shot_at(&storm, 0.73631f, 267.0, 10.0, &s)) {
        CHECK(0, "the shots rendered");
        return;
    }
    NOTE("dusk: storm's 8-bit mean %.3f against clear's %.3f; HDR sky %.3f of clear's", s.mean_display,
         c.mean_display, s.hdr_sky / c.hdr_sky);
    CHECK(s.mean_display <= 0.75 * c.mean_display && s.hdr_sky <= 0.2 * c.hdr_sky,
          "a storm at dusk darker than the clear dusk (%.3f against %.3f)", s.mean_display, c.mean_display);
}

/* Fog closes the range below a kilometre and swallows the horizon: the
 * rows just above it and just below it alike, where a clear day's sky and
 * ground differ; the host's fog density is Koschmieder's for the range. */
TEST(weather_fog_swallows_the_horizon)
{
    sky_weather clear = weather_preset(SKY_WEATHER_CLEAR), fog = weather_preset(SKY_WEATHER_FOG);
    shot c, f;
    if (noon_shot(&clear, 0.0, &c) || noon_shot(&fog, 0.0, &f)) {
        CHECK(0, "the shots rendered");
        return;
    }
    double step_c = 0.0, step_f = 0.0; /* the largest channel's difference, 8-bit */
    for (int i = 0; i < 3; i++) {
        step_c = fmax(step_c, fabs(c.above[i] - c.below[i]));
        step_f = fmax(step_f, fabs(f.above[i] - f.below[i]));
    }
    NOTE("across the horizon, the colour's largest step: clear %.1f/255, fog %.1f/255", step_c, step_f);
    CHECK(fog.visibility_km <= 1.0f, "fog's range under a kilometre (%g km)", fog.visibility_km);
    CHECK(step_f < 2.0 && step_c > 20.0, "fog swallows the horizon (%.1f/255; clear %.1f/255)", step_f, step_c);
    CHECK(fabs(f.light.fog_density - 3.912 / (1000.0 * fog.visibility_km)) < 1e-6 &&
              fabs(c.light.fog_density - 3.912 / (1000.0 * clear.visibility_km)) < 1e-8,
          "fog_density = 3.912 / V (%g, %g per metre)", f.light.fog_density, c.light.fog_density);
}

/* A deck without haze (a host's own weather: overcast's deck, the clear
 * state's range) closes the sky down to the horizon: no band of the clear
 * sky's bright horizon between the deck and the ground. */
TEST(weather_deck_closes_the_horizon)
{
    sky_weather deck = weather_preset(SKY_WEATHER_OVERCAST);
    deck.visibility_km = weather_preset(SKY_WEATHER_CLEAR).visibility_km;
    shot d;
    if (shot_at(&deck, 0.5f, 180.0, 3.0, &d)) {
        CHECK(0, "the shot rendered");
        return;
    }
    double above = 0.2126 * d.above[0] + 0.7152 * d.above[1] + 0.0722 * d.above[2];
    double below = 0.2126 * d.below[0] + 0.7152 * d.below[1] + 0.0722 * d.below[2];
    NOTE("a deck without haze: the horizon's brightest row %.1f/255, the deck above %.1f, the ground below %.1f",
         d.horizon_row, above, below);
    CHECK(d.horizon_row <= fmax(above, below) + 2.0, "no bright band at the horizon (%.1f against %.1f and %.1f)",
          d.horizon_row, above, below);
}

/* A 10-second change of weather seen at 30 frames a second: no frame
 * moves the 8-bit frame's mean by more than 0.5/255, and the frames darken
 * from fair to overcast overall. */
SLOW_TEST(weather_transition_free_of_jumps)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_CLOUDS | SKY_SUN | SKY_WEATHER;
    fixture f;
    if (fixture_open_sized(&f, W, H, 0, SKY_GL_AUTO, &cfg)) {
        CHECK(0, "no sky");
        return;
    }
    sky_params p = sky_default_params();
    p.time = 0.5f;
    sky_set_params(f.s, &p);
    sky_weather fair = weather_preset(SKY_WEATHER_FAIR), overcast = weather_preset(SKY_WEATHER_OVERCAST);
    sky_set_weather(f.s, &fair, 0.0);
    sky_set_weather(f.s, &overcast, 10.0);
    float view[16], proj[16];
    sky_cli_camera_at(180.0, 20.0, 60.0, W, H, view, proj);
    double prev = -1.0, worst = 0.0, first = 0.0, last = 0.0;
    int worst_at = 0;
    for (int k = 0; k <= 300; k++) {
        sky_set_elapsed(f.s, k / 30.0);
        sky_draw(f.s, view, proj);
        sky_osmesa_finish(&f.ctx);
        double mean = frame_mean(f.ctx.pixels);
        if (prev >= 0.0 && fabs(mean - prev) > worst) worst = fabs(mean - prev), worst_at = k;
        if (!k) first = mean;
        last = mean;
        prev = mean;
    }
    NOTE("fair to overcast in 10 s at 30 fps: the largest step of the mean %.3f/255 (frame %d); %.1f -> %.1f", worst,
         worst_at, first, last);
    CHECK(worst <= 0.5, "no frame jumps (%.3f/255 at frame %d)", worst, worst_at);
    CHECK(last < first, "overcast darker than fair (%.1f -> %.1f)", first, last);
    fixture_close(&f);
}

/* sky-render's options: --weather, --weather-to, --weather-seconds, and
 * --stats' "weather" and "lighting". */
TEST(weather_command_line)
{
    char render[512], cmd[1024], out[16384];
    bin_path("sky-render", render, sizeof render);
    snprintf(cmd, sizeof cmd, "%s --weather fair --weather-to storm --weather-seconds 20 --seconds 10 --size 64x36 --stats 2>&1",
             render);
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 0, "sky-render with a weather ran (exit %d): %.300s", rc, out);
    const char *weather = strstr(out, "\"weather\":{"), *lighting = strstr(out, "\"lighting\":{");
    CHECK(weather && lighting && strstr(lighting, "\"sun_color\":[") && strstr(lighting, "\"ambient_color\":["),
          "--stats has \"weather\" and \"lighting\": %.300s", out);
    double cover = weather ? strtod(strstr(weather, "\"cover\":") + 8, NULL) : -1.0;
    CHECK(cover > 0.5 && cover < 1.0 && strstr(weather, "\"moving\":true"),
          "half way from fair (0.35) to storm (1): cover %g, moving", cover);
    snprintf(cmd, sizeof cmd, "%s --weather drizzle --size 8x8 2>&1", render);
    rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 2 && strstr(out, "--weather") && strstr(out, "drizzle"), "an unknown weather refused (exit %d): %s", rc,
          out);
}

/* ---- lightning ------------------------------------------------------------------------ */

static int strikes_of(unsigned seed, const sky_weather *w, double t0, double t1, sky_lightning_strike *out, int max)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.seed = seed;
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, &cfg)) return -1;
    int count = -1;
    if (w) sky_set_weather(f.s, w, 0.0);
    if (sky_get_lightning(f.s, t0, t1, out, max, &count) != SKY_OK) count = -1;
    fixture_close(&f);
    return count;
}

/* Strikes at the storm's rate, the same for one seed and different for
 * another, none where nothing is stormy. */
TEST(weather_lightning_follows_the_seed)
{
    enum { MAX = 200 };
    static sky_lightning_strike a[MAX], b[MAX], c[MAX];
    sky_weather storm = weather_preset(SKY_WEATHER_STORM), rain = weather_preset(SKY_WEATHER_RAIN);
    int na = strikes_of(7, &storm, 0.0, 600.0, a, MAX), nb = strikes_of(7, &storm, 0.0, 600.0, b, MAX),
        nc = strikes_of(8, &storm, 0.0, 600.0, c, MAX);
    double expected = storm.lightning_per_minute * 10.0;
    NOTE("seed 7: %d strikes in 10 minutes, seed 8: %d (expected %.0f)", na, nc, expected);
    CHECK(na == nb && na > 0 && !memcmp(a, b, sizeof a[0] * (size_t)(na < MAX ? na : MAX)),
          "one seed, the same strikes (%d, %d)", na, nb);
    CHECK(nc > 0 && (nc != na || memcmp(a, c, sizeof a[0] * (size_t)(na < MAX ? na : MAX))),
          "another seed, other strikes");
    /* a Poisson count: within four standard deviations */
    CHECK(fabs(na - expected) < 4.0 * sqrt(expected) && fabs(nc - expected) < 4.0 * sqrt(expected),
          "the storm's rate (%d and %d against %.0f)", na, nc, expected);
    int ordered = 1, sane = 1;
    for (int i = 0; i < na && i < MAX; i++) {
        ordered &= !i || a[i].time >= a[i - 1].time;
        sane &= a[i].time >= 0.0 && a[i].time < 600.0 && a[i].azimuth_deg >= 0.0f && a[i].azimuth_deg < 360.0f &&
                a[i].altitude_deg > 0.0f && a[i].altitude_deg < 90.0f && a[i].distance_m >= 500.0f &&
                a[i].distance_m <= 15000.0f && a[i].strokes >= 3 && a[i].strokes <= 4;
    }
    CHECK(ordered && sane, "in time order, every number in its range");
    /* a window inside the span lists the same strikes */
    sky_lightning_strike part[MAX];
    int np = strikes_of(7, &storm, 100.0, 200.0, part, MAX), inside = 0;
    for (int i = 0; i < na && i < MAX; i++) inside += a[i].time >= 100.0 && a[i].time < 200.0;
    CHECK(np == inside, "a window holds the span's strikes in it (%d, %d)", np, inside);
    for (int i = 0, j = 0; i < na && i < MAX && j < np; i++)
        if (a[i].time >= 100.0 && a[i].time < 200.0) CHECK(a[i].time == part[j++].time, "the same strike %d", j);
    CHECK(strikes_of(7, &rain, 0.0, 600.0, NULL, 0) == 0, "rain has no lightning");
    CHECK(strikes_of(7, NULL, 0.0, 600.0, NULL, 0) == 0, "no weather, no lightning");
}

TEST(weather_lightning_rejects_bad_windows)
{
    fixture f;
    if (open_sky(&f)) return;
    sky_lightning_strike s[4];
    int n = 5;
    CHECK(sky_get_lightning(NULL, 0, 1, s, 4, &n) == SKY_ERR_INVALID_ARGUMENT, "NULL sky");
    CHECK(sky_get_lightning(f.s, NAN, 1, s, 4, &n) == SKY_ERR_INVALID_ARGUMENT && n == 0, "NaN start");
    CHECK(sky_get_lightning(f.s, 0, INFINITY, s, 4, &n) == SKY_ERR_INVALID_ARGUMENT, "infinite end");
    CHECK(sky_get_lightning(f.s, -1, 1, s, 4, &n) == SKY_ERR_INVALID_ARGUMENT, "negative start");
    CHECK(sky_get_lightning(f.s, 5, 1, s, 4, &n) == SKY_ERR_INVALID_ARGUMENT, "end before start");
    CHECK(sky_get_lightning(f.s, 0, 86401, s, 4, &n) == SKY_ERR_INVALID_ARGUMENT &&
              strstr(sky_last_error(f.s), "day"),
          "over a day: %s", sky_last_error(f.s));
    CHECK(sky_get_lightning(f.s, 0, 1, NULL, 4, &n) == SKY_ERR_INVALID_ARGUMENT, "out NULL with max 4");
    CHECK(sky_get_lightning(f.s, 0, 1, s, -1, &n) == SKY_ERR_INVALID_ARGUMENT, "negative max");
    CHECK(sky_get_lightning(f.s, 0, 1, NULL, 0, NULL) == SKY_OK, "counting nothing is fine");
    fixture_close(&f);
}

/* A flash lights the deck and the host's scene for a fraction of a second,
 * from the strike's direction, flickering with its strokes. */
/* A storm of seed 7 at the time slider's time in a W x H context; -1
 * after a failed CHECK. */
static int open_storm(fixture *f, float time)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_CLOUDS | SKY_SUN | SKY_WEATHER;
    cfg.seed = 7;
    if (fixture_open_sized(f, W, H, 0, SKY_GL_AUTO, &cfg)) {
        CHECK(0, "no sky");
        return -1;
    }
    sky_params p = sky_default_params();
    p.time = time;
    sky_set_params(f->s, &p);
    sky_weather storm = weather_preset(SKY_WEATHER_STORM);
    sky_set_weather(f->s, &storm, 0.0);
    return 0;
}

TEST(weather_lightning_flashes)
{
    fixture f;
    if (open_storm(&f, 0.5f)) return;
    sky_lightning_strike s[64];
    int n = 0;
    sky_get_lightning(f.s, 0.0, 600.0, s, 64, &n);
    /* a strike with a second clear before it and after it */
    int k = -1;
    for (int i = 0; i < n && i < 64 && k < 0; i++)
        if ((i == 0 || s[i].time - s[i - 1].time > 1.0) && (i + 1 >= n || s[i + 1].time - s[i].time > 1.0)) k = i;
    CHECK(k >= 0, "an isolated strike among %d", n);
    if (k < 0) {
        fixture_close(&f);
        return;
    }
    float view[16], proj[16];
    sky_cli_camera_at(s[k].azimuth_deg, 15.0, 60.0, W, H, view, proj);
    static const double after[4] = {-0.5, 0.005, 0.04, 0.8};
    double mean[4], klx[4];
    sky_lighting l[4];
    for (int j = 0; j < 4; j++) {
        sky_set_elapsed(f.s, s[k].time + after[j]);
        sky_draw(f.s, view, proj);
        sky_osmesa_finish(&f.ctx);
        mean[j] = frame_mean(f.ctx.pixels);
        sky_get_lighting(f.s, &l[j]);
        klx[j] = luma(l[j].flash_color);
    }
    NOTE("strike at %.3f s, %.0f m: frame mean %.1f before, %.1f at the first stroke, %.1f 40 ms on, %.1f after; "
         "flash %.3g klx",
         s[k].time, s[k].distance_m, mean[0], mean[1], mean[2], mean[3], klx[1]);
    CHECK(klx[0] == 0.0 && klx[3] == 0.0 && fabs(mean[3] - mean[0]) < 1.0,
          "no flash before and 0.8 s after (%g, %g klx; mean %.1f, %.1f)", klx[0], klx[3], mean[0], mean[3]);
    CHECK(klx[1] > 0.0 && mean[1] > mean[0] + 1.0, "the first stroke lights the deck and the scene (%.1f > %.1f)",
          mean[1], mean[0]);
    CHECK(klx[2] < klx[1], "and fades between strokes (%.3g < %.3g klx)", klx[2], klx[1]);
    double km = s[k].distance_m / 1000.0;
    CHECK(fabs(klx[1] / (2.0 / (km * km)) - 1.0) < 0.2,
          "its illuminance about 2 klx at a kilometre, by the square of the distance (%.3g at %.1f km)", klx[1], km);
    double az = s[k].azimuth_deg * 3.14159265358979 / 180.0, alt = s[k].altitude_deg * 3.14159265358979 / 180.0;
    double want[3] = {cos(alt) * sin(az), sin(alt), -cos(alt) * cos(az)}, dot = 0.0;
    for (int i = 0; i < 3; i++) dot += want[i] * l[1].flash_direction[i];
    CHECK(dot > 0.9999, "flash_direction points at the strike (cos %.5f)", dot);
    fixture_close(&f);
}

/* At night a flash's light on the host's scene is held as the lit cloud
 * is: a white surface facing it shows at one display white (the cloud at
 * up to two), where the physical 2 klx at a kilometre would show a white
 * page dozens of whites over; by day it is the physical light (above). */
TEST(weather_lightning_at_night_held)
{
    fixture f;
    if (open_storm(&f, 0.95f)) return;
    sky_lightning_strike s[8];
    int n = 0;
    sky_get_lightning(f.s, 0.0, 120.0, s, 8, &n);
    CHECK(n > 0, "strikes in two minutes of a storm");
    if (n > 0) {
        sky_set_elapsed(f.s, s[0].time + 0.005);
        sky_lighting l;
        sky_get_lighting(f.s, &l);
        double km = s[0].distance_m / 1000.0, physical = 2.0 / (km * km);
        double white = luma(l.flash_color) / 3.14159265358979 * l.exposure;
        NOTE("a strike %.1f km away: %.3g klx physically, a white surface facing it at %.3f display whites (%.0f unheld)",
             km, physical, white, physical / 3.14159265358979 * l.exposure);
        CHECK(physical / 3.14159265358979 * l.exposure > 2.0 && white > 0.99 && white < 1.01,
              "the flash held to one display white on a white surface (%.3f)", white);
    }
    fixture_close(&f);
}

/* ---- cloud shadows ------------------------------------------------------------------- */

static double shadowed(const unsigned char *px, int n)
{
    double sum = 0.0;
    for (int i = 0; i < n; i++) sum += 1.0 - px[i] / 255.0;
    return sum / n;
}

/* The shadowed share of the ground follows the cover: none at cover 0,
 * more with more cloud, about what the clouds' mean opacity keeps from
 * the beam (a cloud passes a fifth of it). */
TEST(weather_cloud_shadows_follow_cover)
{
    fixture f;
    if (open_sky(&f)) return;
    enum { N = 128 };
    static unsigned char px[N * N];
    static const float covers[4] = {0.0f, 0.25f, 0.5f, 0.75f};
    double prev = -1.0;
    for (int k = 0; k < 4; k++) {
        sky_params p = sky_default_params();
        p.time = 0.5f;
        p.cover = covers[k];
        sky_set_params(f.s, &p);
        CHECK(sky_cloud_shadow_image(f.s, 20000.0f, N, N, px) == SKY_OK, "the map: %s", sky_last_error(f.s));
        double share = shadowed(px, N * N), opacity = f.s->core.frame.cloud_mean[0];
        NOTE("cover %.2f: %.3f of the beam shadowed; the clouds' mean opacity %.3f", covers[k], share, opacity);
        if (k == 0) CHECK(share == 0.0, "nothing shadowed at cover 0 (%.4f)", share);
        CHECK(share > prev, "more shadow with more cover (%.3f after %.3f)", share, prev);
        CHECK(fabs(share - 0.8 * opacity) < 0.06, "about 0.8 of the mean opacity (%.3f against %.3f)", share,
              0.8 * opacity);
        prev = share;
    }
    /* at night, or with the sun too low, the map stays lit */
    sky_params night = sky_default_params();
    night.time = 0.0f;
    night.cover = 0.7f;
    sky_set_params(f.s, &night);
    sky_cloud_shadow_image(f.s, 20000.0f, N, N, px);
    CHECK(shadowed(px, N * N) == 0.0, "no shadows at midnight");
    CHECK(sky_cloud_shadow_image(NULL, 1e4f, N, N, px) == SKY_ERR_INVALID_ARGUMENT &&
              sky_cloud_shadow_image(f.s, 1e4f, N, N, NULL) == SKY_ERR_INVALID_ARGUMENT &&
              sky_cloud_shadow_image(f.s, 1e4f, 0, N, px) == SKY_ERR_INVALID_ARGUMENT &&
              sky_cloud_shadow_image(f.s, NAN, N, N, px) == SKY_ERR_INVALID_ARGUMENT &&
              sky_cloud_shadow_image(f.s, 5.0f, N, N, px) == SKY_ERR_INVALID_ARGUMENT,
          "NULL, an empty image, a NaN or tiny extent refused");
    fixture_close(&f);
}

/* The shadows drift with the drawn clouds: the map a minute later is the
 * map moved by the first layer's drift over that minute (in metres: its
 * offset's change over the texture's period on the ground, height over
 * the height slider's scale), downwind. */
TEST(weather_cloud_shadows_drift_with_the_clouds)
{
    fixture f;
    if (open_sky(&f)) return;
    enum { N = 160 };
    const float extent = 16000.0f; /* 100 m a pixel */
    static unsigned char a[N * N], b[N * N];
    sky_params p = sky_default_params();
    p.time = 0.5f;
    p.cover = 0.5f;
    sky_set_params(f.s, &p);
    sky_weather west;
    sky_get_weather(f.s, &west, NULL);
    west.wind_from_deg = 270.0f;
    west.wind_speed_ms = 5.0f;
    sky_set_weather(f.s, &west, 0.0);
    const double *off = sky_clouds_offsets(f.s->layer_state[SKY_LAYER_CLOUDS]);
    sky_set_elapsed(f.s, 10.0);
    double u0 = off[0];
    sky_cloud_shadow_image(f.s, extent, N, N, a);
    sky_set_elapsed(f.s, 40.0);
    double du = off[0] - u0;
    sky_cloud_shadow_image(f.s, extent, N, N, b);
    /* the texture moves -du periods across the plane: clouds go east */
    const sky_frame *fr = &f.s->core.frame;
    double period_m = 1500.0 / fr->cloud_uv_scale; /* height (slider 0.5) over the plane's scale */
    double want_px = -du * period_m / (extent / N);
    /* the shift of b against a with the best match, over +-12 px */
    int best_x = 0, best_y = 0;
    double best = 1e30;
    for (int dy = -12; dy <= 12; dy++)
        for (int dx = -12; dx <= 12; dx++) {
            double sum = 0.0;
            for (int y = 20; y < N - 20; y++)
                for (int x = 20; x < N - 20; x++) {
                    double d = (double)b[(y + dy) * N + x + dx] - a[y * N + x];
                    sum += d * d;
                }
            if (sum < best) best = sum, best_x = dx, best_y = dy;
        }
    NOTE("in 30 s: the map moved %d px east, %d px south; the clouds' drift %.1f px east", best_x, best_y, want_px);
    CHECK(want_px > 2.0 && abs(best_x - (int)lround(want_px)) <= 1 && abs(best_y) <= 1,
          "the shadows move with the clouds, east in a west wind (%d, %d px against %.1f)", best_x, best_y, want_px);
    fixture_close(&f);
}

/* The texture, its matrix and the host's GLSL: a host program that calls
 * sky_cloud_shadow at the observer and 3 km east reads the map's texels
 * there, and the map's mean at its edge and beyond, in both desktop
 * profiles. */
static void cloud_shadow_host(sky_gl_profile profile)
{
    fixture f;
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_CLOUDS | SKY_SUN | SKY_WEATHER;
    if (fixture_open_sized(&f, 16, 16, 1, profile, &cfg)) {
        CHECK(0, "no sky");
        return;
    }
    int core = profile == SKY_GL_CORE33;
    sky_params p = sky_default_params();
    p.time = 0.5f;
    p.cover = 0.6f;
    sky_set_params(f.s, &p);
    sky_cloud_shadow map;
    CHECK(sky_get_cloud_shadow(f.s, 2.0f, 10000.0f, &map) == SKY_OK, "the map: %s", sky_last_error(f.s));
    CHECK(map.texture != 0 && map.size == 64 && fabsf(map.height_m - 1500.0f) < 0.01f && map.extent_m == 10000.0f,
          "texture %u, %d texels, %.0f m up", map.texture, map.size, map.height_m);
    /* the matrix: the observer at the centre; 1500 units (3 km) east at
     * 0.5 + 0.3 on s */
    float e = map.matrix[0] * 1500.0f + map.matrix[12], t = map.matrix[1] * 1500.0f + map.matrix[13];
    CHECK(map.matrix[12] == 0.5f && map.matrix[13] == 0.5f && fabsf(e - 0.8f) < 1e-5f && fabsf(t - 0.5f) < 1e-5f,
          "the matrix maps the observer to the centre and 3 km east to s 0.8 (%g, %g)", e, t);
    const char *body = "uniform vec3 where;\nvoid main() { FRAG = vec4(sky_cloud_shadow(where), 0.0, 0.0, 1.0); }\n";
    unsigned prog = test_snippet_program(core, sky_cloud_shadow_glsl(), body), vao = 0, buf = 0;
    CHECK(prog != 0, "the host's program with the snippet links");
    if (!prog) {
        fixture_close(&f);
        return;
    }
    test_fullscreen_triangle(core, &vao, &buf);
    CHECK(sky_cloud_shadow_bind(f.s, prog, 1) == SKY_OK, "bind: %s", sky_last_error(f.s));
    static unsigned char grey[64 * 64];
    sky_cloud_shadow_image(f.s, 10000.0f, 64, 64, grey);
    glUseProgram(prog);
    GLint at = glGetUniformLocation(prog, "where");
    static const float where[2][3] = {{0.0f, 0.0f, 0.0f}, {1500.0f, 0.0f, 0.0f}};
    static const int texel[2][2] = {{32, 32}, {51, 32}}; /* s 0.5 and 0.8 (51.2) */
    unsigned sum = 0;
    for (int i = 0; i < 64 * 64; i++) sum += grey[i];
    CHECK(fabs(map.mean - sum / (255.0 * 64 * 64)) < 1e-4, "the map's mean %.4f, its texels' %.4f", map.mean,
          sum / (255.0 * 64 * 64));
    for (int k = 0; k < 2; k++) {
        glUniform3fv(at, 1, where[k]);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        float px[4];
        glReadPixels(8, 8, 1, 1, GL_RGBA, GL_FLOAT, px);
        /* between the four texels around the point (linear filtering) */
        double lo = 1.0, hi = 0.0;
        for (int dy = -1; dy <= 0; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                double v = grey[(texel[k][1] + dy) * 64 + texel[k][0] + dx] / 255.0;
                lo = fmin(lo, v), hi = fmax(hi, v);
            }
        CHECK(px[0] >= lo - 0.01 && px[0] <= hi + 0.01, "%s: the GLSL reads the map at point %d: %.3f in %.3f..%.3f",
              core ? "core" : "compat", k, px[0], lo, hi);
    }
    /* beyond the map (the edge's texels would streak to the horizon) and
     * at its edge, the map's mean */
    static const float beyond[2][3] = {{0.0f, 0.0f, 40000.0f}, {2500.0f, 0.0f, 0.0f}};
    for (int k = 0; k < 2; k++) {
        glUniform3fv(at, 1, beyond[k]);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        float px[4];
        glReadPixels(8, 8, 1, 1, GL_RGBA, GL_FLOAT, px);
        CHECK(fabsf(px[0] - map.mean) < 0.01f, "%s: %s the map, its mean %.3f (read %.3f)", core ? "core" : "compat",
              k ? "at the edge of" : "beyond", map.mean, px[0]);
    }
    glUseProgram(0);
    test_fullscreen_free(vao, buf);
    glDeleteProgram(prog);
    CHECK(sky_cloud_shadow_bind(f.s, 0, 1) == SKY_ERR_INVALID_ARGUMENT &&
              sky_cloud_shadow_bind(f.s, 123456, 1) == SKY_ERR_INVALID_ARGUMENT &&
              sky_get_cloud_shadow(f.s, 0.0f, 1e4f, &map) == SKY_ERR_INVALID_ARGUMENT &&
              sky_get_cloud_shadow(f.s, 1.0f, 1e4f, NULL) == SKY_ERR_INVALID_ARGUMENT,
          "no program, not a program, no scale, no out refused");
    fixture_close(&f);
}

TEST(weather_cloud_shadow_for_the_host_core) { cloud_shadow_host(SKY_GL_CORE33); }
TEST(weather_cloud_shadow_for_the_host_compat) { cloud_shadow_host(SKY_GL_COMPAT20); }

/* sky_get_cloud_shadow spreads its work: after the clouds drift, each call
 * refreshes a quarter of the texture's rows, and four calls leave it as
 * sky_cloud_shadow_image computes it whole. */
TEST(weather_cloud_shadow_texture_catches_up)
{
    fixture f;
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_CLOUDS | SKY_SUN | SKY_WEATHER;
    if (fixture_open_sized(&f, 16, 16, 0, SKY_GL_COMPAT20, &cfg)) {
        CHECK(0, "no sky");
        return;
    }
    sky_params p = sky_default_params();
    p.time = 0.5f;
    p.cover = 0.6f;
    p.speed = 1.0f;
    sky_set_params(f.s, &p);
    sky_cloud_shadow map;
    sky_get_cloud_shadow(f.s, 1.0f, 8000.0f, &map);
    sky_update(f.s, 20.0); /* the clouds a few texels on */
    static unsigned char want[64 * 64], got[64 * 64 * 4];
    sky_cloud_shadow_image(f.s, 8000.0f, 64, 64, want);
    int differ[4];
    for (int call = 0; call < 4; call++) {
        sky_get_cloud_shadow(f.s, 1.0f, 8000.0f, &map);
        glBindTexture(GL_TEXTURE_2D, map.texture);
        glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, got);
        glBindTexture(GL_TEXTURE_2D, 0);
        differ[call] = 0;
        for (int i = 0; i < 64 * 64; i++) differ[call] += got[4 * i] != want[i];
    }
    NOTE("texels still stale after 1..4 calls: %d %d %d %d", differ[0], differ[1], differ[2], differ[3]);
    CHECK(differ[0] > 0 && differ[1] < differ[0] && differ[2] < differ[1] && differ[3] == 0,
          "a quarter of the rows a call, all after four (%d %d %d %d)", differ[0], differ[1], differ[2], differ[3]);
    fixture_close(&f);
}

/* The host's ambient light from the sky (sky_get_irradiance_sh) and its
 * environment cube map (sky_capture_environment) see the weather's deck
 * and haze: under fog their colour is the fog's grey, where the clear
 * sky's is blue. */
TEST(weather_in_the_irradiance_and_capture)
{
    enum { CAP = 16 };
    double ratio[2], capture_ratio[2] = {0.0, 0.0}, fog_ratio = 0.0;
    static const sky_weather_state states[2] = {SKY_WEATHER_CLEAR, SKY_WEATHER_FOG};
    for (int k = 0; k < 2; k++) {
        fixture f;
        if (open_sky(&f)) return;
        sky_params p = sky_default_params();
        p.time = 0.5f;
        sky_set_params(f.s, &p);
        sky_weather w = weather_preset(states[k]);
        sky_set_weather(f.s, &w, 0.0);
        sky_irradiance_sh sh;
        float up[3] = {0.0f, 1.0f, 0.0f}, e[3];
        sky_get_irradiance_sh(f.s, &sh);
        sky_irradiance_sh_eval(&sh, up, e);
        ratio[k] = e[2] / e[0];
        sky_lighting l;
        sky_get_lighting(f.s, &l);
        if (k) fog_ratio = l.fog_color[2] / l.fog_color[0];
        /* the cube map's face above (+Y: GL's third), blue over red */
        static unsigned char face[CAP * CAP * 4];
        CHECK(sky_capture_environment(f.s, 0, CAP, 2, 0) == SKY_OK, "capture: %s", sky_last_error(f.s));
        glBindTexture(GL_TEXTURE_CUBE_MAP, sky_environment_texture(f.s));
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glGetTexImage(GL_TEXTURE_CUBE_MAP_POSITIVE_Y, 0, GL_RGBA, GL_UNSIGNED_BYTE, face);
        glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
        double sum[3] = {0.0, 0.0, 0.0};
        for (int i = 0; i < CAP * CAP; i++)
            for (int c = 0; c < 3; c++) sum[c] += face[4 * i + c];
        if (sum[0] > 0.0) capture_ratio[k] = sum[2] / sum[0];
        fixture_close(&f);
    }
    NOTE("the sky's irradiance from above, blue over red: clear %.3f, fog %.3f (the fog's colour %.3f); the capture's "
         "face above: clear %.3f, fog %.3f", ratio[0], ratio[1], fog_ratio, capture_ratio[0], capture_ratio[1]);
    CHECK(ratio[0] > 1.3 && fabs(ratio[1] / fog_ratio - 1.0) < 0.1,
          "clear's irradiance blue, fog's the fog's grey (%.3f, %.3f against %.3f)", ratio[0], ratio[1], fog_ratio);
    CHECK(capture_ratio[0] > 1.3 && capture_ratio[1] > 0.9 && capture_ratio[1] < 1.1,
          "the capture's sky above: clear's blue, fog's grey (%.3f, %.3f)", capture_ratio[0], capture_ratio[1]);
}
