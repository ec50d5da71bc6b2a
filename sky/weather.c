/*
 * The weather (sky.h, "Weather"): the named states, the transition from
 * one weather to another on the sky's running clock, the wind's drift
 * integrated over that clock (so that a frame at time T is the same
 * however the sky was stepped there), and what a weather does to the
 * frame. sky_set_weather and sky_get_weather, which hold the sky handle,
 * are weather_api.c's.
 */
#include "core.h"
#include "solar_eclipse.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

/* Each state's numbers. cover and density are the sliders' (Roden &
 * Parberry's line 15 and 19-23); upper the thin layer's amount (0.35 x
 * cover is the sliders' own); visibility the meteorological range (WMO's
 * classes: fog under 1 km, mist 1-5, haze 2-5, clear air 20 and more);
 * light_through the share of the light above a deck that reaches below it
 * (Kasten & Czeplak 1980 fit the global light under N oktas as
 * 1 - 0.75 (N / 8)^3.4 of the clear sky's: a quarter under a full cover;
 * rain's and a storm's thicker decks pass less). */
static const struct {
    const char *name;
    sky_weather w;
} states[SKY_WEATHER_COUNT] = {
    /*            cover density upper vis   precip kind                      drop lightning wind  m/s   through */
    {"clear",    {0.00f, 0.20f, 0.00f, 60.0f, 0.0f, SKY_PRECIPITATION_NONE, 0.0f, 0.0f, 270.0f, 4.0f, 1.00f}},
    {"fair",     {0.35f, 0.20f, 0.12f, 40.0f, 0.0f, SKY_PRECIPITATION_NONE, 0.0f, 0.0f, 270.0f, 5.0f, 1.00f}},
    {"cirrus",   {0.08f, 0.10f, 0.90f, 40.0f, 0.0f, SKY_PRECIPITATION_NONE, 0.0f, 0.0f, 270.0f, 12.0f, 0.95f}},
    {"cloudy",   {0.70f, 0.45f, 0.25f, 25.0f, 0.0f, SKY_PRECIPITATION_NONE, 0.0f, 0.0f, 270.0f, 7.0f, 0.75f}},
    {"overcast", {1.00f, 0.85f, 0.00f, 15.0f, 0.0f, SKY_PRECIPITATION_NONE, 0.0f, 0.0f, 270.0f, 6.0f, 0.32f}},
    {"rain",     {1.00f, 0.95f, 0.00f, 6.0f, 0.6f, SKY_PRECIPITATION_RAIN, 1.5f, 0.0f, 250.0f, 9.0f, 0.20f}},
    {"showers",  {0.60f, 0.70f, 0.10f, 12.0f, 0.4f, SKY_PRECIPITATION_RAIN, 2.5f, 0.0f, 280.0f, 10.0f, 0.45f}},
    {"storm",    {1.00f, 1.00f, 0.00f, 3.0f, 1.0f, SKY_PRECIPITATION_RAIN, 3.0f, 6.0f, 240.0f, 15.0f, 0.06f}},
    {"fog",      {1.00f, 0.60f, 0.00f, 0.3f, 0.0f, SKY_PRECIPITATION_NONE, 0.0f, 0.0f, 270.0f, 1.0f, 0.45f}},
    {"snow",     {1.00f, 0.80f, 0.00f, 2.0f, 0.5f, SKY_PRECIPITATION_SNOW, 5.0f, 0.0f, 20.0f, 4.0f, 0.40f}},
};

sky_result sky_weather_preset(sky_weather_state state, sky_weather *out)
{
    if (!out || (int)state < 0 || (int)state >= SKY_WEATHER_COUNT) return SKY_ERR_INVALID_ARGUMENT;
    *out = states[state].w;
    return SKY_OK;
}

const char *sky_weather_name(sky_weather_state state)
{
    return (int)state >= 0 && (int)state < SKY_WEATHER_COUNT ? states[state].name : NULL;
}

int sky_weather_from_name(const char *name)
{
    for (int i = 0; name && i < SKY_WEATHER_COUNT; i++)
        if (!strcmp(states[i].name, name)) return i;
    return -1;
}

/* ---- checks --------------------------------------------------------------- */

typedef struct weather_field {
    const char *name;
    size_t offset;
    float lo, hi;
} weather_field;

#define WEATHER_FIELD(f, lo, hi) {#f, offsetof(sky_weather, f), lo, hi}
static const weather_field fields[] = {
    WEATHER_FIELD(cover, 0.0f, 1.0f),          WEATHER_FIELD(density, 0.0f, 1.0f),
    WEATHER_FIELD(upper, 0.0f, 1.0f),          WEATHER_FIELD(visibility_km, 0.05f, 300.0f),
    WEATHER_FIELD(precipitation, 0.0f, 1.0f),  WEATHER_FIELD(drop_size_mm, 0.0f, 10.0f),
    WEATHER_FIELD(lightning_per_minute, 0.0f, 60.0f), WEATHER_FIELD(wind_from_deg, -1e9f, 1e9f),
    WEATHER_FIELD(wind_speed_ms, 0.0f, 60.0f), WEATHER_FIELD(light_through, 0.0f, 1.0f),
};
#define FIELD_COUNT (int)(sizeof fields / sizeof fields[0])

static float *field_at(sky_weather *w, int i) { return (float *)(void *)((char *)w + fields[i].offset); }
static double field_value(const sky_weather *w, int i)
{
    float v;
    memcpy(&v, (const char *)w + fields[i].offset, sizeof v);
    return v;
}

/* (core.h) */
sky_result sky_weather_checked(const sky_weather *in, sky_weather *out, char *err, size_t err_len)
{
    *out = *in;
    sky_result rc = SKY_OK;
    if ((int)in->precipitation_kind < SKY_PRECIPITATION_NONE || (int)in->precipitation_kind > SKY_PRECIPITATION_SNOW) {
        snprintf(err, err_len, "sky_set_weather: precipitation_kind %d is none of SKY_PRECIPITATION_*",
                 (int)in->precipitation_kind);
        return SKY_ERR_INVALID_ARGUMENT;
    }
    for (int i = 0; i < FIELD_COUNT; i++) {
        float *v = field_at(out, i);
        if (isnan(*v)) {
            snprintf(err, err_len, "sky_set_weather: %s is NaN", fields[i].name);
            return SKY_ERR_INVALID_ARGUMENT;
        }
        float c = sky_clampf(*v, fields[i].lo, fields[i].hi);
        if (c != *v && rc == SKY_OK) {
            snprintf(err, err_len, "sky_set_weather: %s = %g clamped to %g (range %g..%g)", fields[i].name,
                     (double)*v, (double)c, (double)fields[i].lo, (double)fields[i].hi);
            rc = SKY_CLAMPED;
        }
        *v = c;
    }
    out->wind_from_deg = (float)fmod(fmod((double)out->wind_from_deg, 360.0) + 360.0, 360.0);
    return rc;
}

/* ---- the clock -------------------------------------------------------------- */

/* The wind as the clouds' texture offsets move under it: their rate's
 * direction in the dome's plane (x east, y south), which is against the
 * way the clouds are carried, times its speed in m/s. */
static void wind_vector(const sky_weather *w, double v[2])
{
    double from = w->wind_from_deg * SKY_PI / 180.0;
    v[0] = w->wind_speed_ms * sin(from);
    v[1] = -w->wind_speed_ms * cos(from);
}

/* (core.h) */
const float sky_flash_tint[3] = {0.85f, 0.92f, 1.0f};

/* (core.h) */
float sky_weather_wind_from(double vx, double vy)
{
    return (float)fmod(atan2(vx, -vy) * 180.0 / SKY_PI + 360.0, 360.0);
}

/* (core.h) */
double sky_weather_progress(const sky_weather_clock *c, double t)
{
    if (!(c->seconds > 0.0)) return t >= c->start ? 1.0 : 0.0;
    return sky_clampd((t - c->start) / c->seconds, 0.0, 1.0);
}

/* The smoothstep every number eases by, and its integral from 0 (u^3 -
 * u^4 / 2 over 0..1, then growing as u). */
static double ease(double u) { return u * u * (3.0 - 2.0 * u); }
static double ease_integral(double u)
{
    if (u <= 0.0) return 0.0;
    if (u >= 1.0) return 0.5 + (u - 1.0);
    return u * u * u - 0.5 * u * u * u * u;
}

void sky_weather_at(const sky_weather_clock *c, double t, sky_weather *out)
{
    double e = ease(sky_weather_progress(c, t));
    *out = c->to;
    for (int i = 0; i < FIELD_COUNT; i++) {
        /* in double, so that the end is the target exactly */
        double a = field_value(&c->from, i), b = field_value(&c->to, i);
        *field_at(out, i) = (float)(a + (b - a) * e);
    }
    /* the wind turns as a vector, the shorter way round */
    double va[2], vb[2];
    wind_vector(&c->from, va);
    wind_vector(&c->to, vb);
    double vx = va[0] + (vb[0] - va[0]) * e, vy = va[1] + (vb[1] - va[1]) * e;
    double speed = sqrt(vx * vx + vy * vy);
    out->wind_speed_ms = (float)speed;
    if (speed > 1e-6) out->wind_from_deg = sky_weather_wind_from(vx, vy);
    /* the kind is the one that falls: the target's once it does */
    out->precipitation_kind = c->to.precipitation > 0.0f && (e >= 0.5 || c->from.precipitation <= 0.0f)
                                  ? c->to.precipitation_kind
                                  : c->from.precipitation > 0.0f ? c->from.precipitation_kind : c->to.precipitation_kind;
}

/* The wind vector (wind_vector's) integrated over the running clock from
 * t0 to t1: the eased vector's integral, exact for any step. */
void sky_weather_wind_integral(const sky_weather_clock *c, double t0, double t1, double out[2])
{
    double va[2], vb[2];
    wind_vector(&c->from, va);
    wind_vector(&c->to, vb);
    double d = c->seconds > 0.0 ? c->seconds : 0.0, ramp;
    if (d > 0.0) {
        ramp = d * (ease_integral((t1 - c->start) / d) - ease_integral((t0 - c->start) / d));
    } else { /* at once: the target's wind from the start */
        ramp = fmax(t1, c->start) - fmax(t0, c->start);
    }
    for (int i = 0; i < 2; i++) out[i] = va[i] * (t1 - t0) + (vb[i] - va[i]) * ramp;
}

/* The haze a weather adds to the clear sky's (whose range the atmosphere
 * already draws: the clear state's 60 km): Koschmieder's extinction
 * 3.912 / V (a black object's contrast falls to 2 % at the range V), less
 * the clear sky's, in a layer of height H above the ground (a fifth of the
 * range, 30 m for the thickest fog .. 400 m: a radiation fog's depth, rain's
 * below the cloud base). Seen at elevation
 * e the path through it is H / sin e, up to the flat layer's horizon path
 * sqrt(2 R H) on a sphere of radius R. Out: the optical depth straight up
 * and H over that horizon path (clouds.glsl's sky_weather_haze). */
static void weather_haze(const sky_weather *w, float out[2], float *beta_per_m)
{
    const double clear_km = states[SKY_WEATHER_CLEAR].w.visibility_km, earth_m = 6.371e6;
    double v = fmax(w->visibility_km, 0.05);
    double beta = fmax(3.912 / (v * 1000.0) - 3.912 / (clear_km * 1000.0), 0.0); /* per metre */
    double height = sky_clampd(0.2 * v * 1000.0, 30.0, 400.0);
    *beta_per_m = (float)beta;
    out[0] = (float)(beta * height);
    out[1] = (float)sqrt(height / (2.0 * earth_m));
}

/* (sky.c's compute_frame, before the layers) */
void sky_weather_frame(sky_core *c)
{
    sky_frame *f = &c->frame;
    float deck_kcd = 0.0f;
    if (c->weather.set) {
        sky_weather w;
        sky_weather_at(&c->weather, c->running, &w);
        c->params.cover = w.cover;
        c->params.density = w.density;
        f->upper_cover = w.upper / 0.35f;
        f->light_through = w.light_through;
        /* the layers alone leave gaps even at cover 1 (R-P line 15 keeps
         * the photo's dark texels clear): a weather's cover closes them
         * into a deck from 0.75 up */
        f->deck = (float)sky_smoothstep(0.75, 1.0, w.cover);
        weather_haze(&w, f->haze, &f->haze_beta);
        f->visibility_km = w.visibility_km;
        sky_flash flash;
        sky_lightning_flash(&c->weather, c->cfg.seed, c->running, &flash);
        f->flash_klx = flash.klx;
        for (int i = 0; i < 3; i++) f->flash_dir[i] = flash.dir[i];
        f->flash_dir[3] = flash.sharpness;
        deck_kcd = flash.deck_kcd;
    } else {
        f->upper_cover = c->params.cover;
        f->light_through = 1.0f;
        f->deck = 0.0f;
        f->haze[0] = 0.0f;
        f->haze[1] = 1.0f;
        f->haze_beta = 0.0f;
        f->visibility_km = states[SKY_WEATHER_CLEAR].w.visibility_km;
        f->flash_klx = 0.0f;
    }
    f->flash_deck_kcd = deck_kcd; /* (lit in sky_weather_light, once the exposure is known) */
    /* without the clouds layer, whose texture's mean replaces it */
    f->deck_opacity = c->params.cover * (0.5f + 0.5f * c->params.density);
}

double sky_weather_deck_share(const sky_frame *f) { return f->deck_opacity * (1.0 - f->light_through); }

/* sky_weather_light's dimming: where the deck covers the sky (its share
 * of the light) it passes light_through of the light above, diffused. */
static void dim_under_deck(sky_core *c)
{
    sky_frame *f = &c->frame;
    double lt = f->light_through, deck = sky_weather_deck_share(f);
    if (!(deck > 0.0)) return;
    /* the light that reaches the deck: the sky's and the sun's beam on the
     * level, which the deck spreads over the sky below it */
    double beam = fmax(sin(f->sun_altitude), 0.0) * sky_solar_eclipse_light_left(c);
    static const double luma[3] = {0.2126, 0.7152, 0.0722};
    double above = 0.0, fog = 0.0, ground = 0.0;
    for (int i = 0; i < 3; i++) {
        above += luma[i] * (f->ambient_rgb[i] + c->sun_irradiance_klx[i] * f->sun_transmittance[i] * beam);
        fog += luma[i] * f->fog_rgb[i];
        ground += luma[i] * f->ground_rgb[i];
    }
    for (int i = 0; i < 3; i++) {
        f->ambient_rgb[i] = (float)((1.0 - deck) * f->ambient_rgb[i] + deck * lt * above);
        f->fog_rgb[i] = (float)((1.0 - deck) * f->fog_rgb[i] + deck * lt * fog);
        f->ground_rgb[i] = (float)((1.0 - deck) * f->ground_rgb[i] + deck * lt * ground);
    }
}

/* (sky.c's compute_frame, after the layers: the deck's opacity is the
 * clouds layer's) Where a weather's deck covers the sky it passes
 * light_through of the light above, diffused: the sky's light on the
 * ground (the ambient), the horizon and the ground itself fall to that
 * share of what they were, grey. */
void sky_weather_light(sky_core *c)
{
    sky_frame *f = &c->frame;
    /* The deck lit from inside by lightning, in the flash's blue-white. An
     * eye adapted to the night sees a flash as a brilliant sky, not a white
     * page: its luminance is held to two display whites (exposure 1 is one),
     * where the cloud's own grey still shows; and the flash's light on the
     * host's scene to what lights a white surface facing it to one display
     * white (luminance = illuminance / pi), below the lit cloud: the scene
     * flashes into sight, not into a white page brighter than the sky. */
    float deck_kcd = f->flash_deck_kcd;
    if (f->exposure > 0.0f) {
        if (deck_kcd > 2.0f / f->exposure) deck_kcd = 2.0f / f->exposure;
        if (f->flash_klx > (float)SKY_PI / f->exposure) f->flash_klx = (float)SKY_PI / f->exposure;
    }
    for (int i = 0; i < 3; i++) f->flash_light[i] = deck_kcd * sky_flash_tint[i];
    dim_under_deck(c);
    /* Under a closed deck the horizon is its base seen far off: the deck's
     * own light (the clouds' mean grey in their light, which the deck has
     * dimmed already), where the clear sky's had shown as a bright band
     * between deck and ground. */
    if (f->deck > 0.0f && f->cloud_mean[0] > 0.0f) {
        double grey = f->cloud_mean[1] / f->cloud_mean[0];
        for (int i = 0; i < 3; i++)
            f->fog_rgb[i] = (float)((1.0 - f->deck) * f->fog_rgb[i] + f->deck * grey * f->cloud_light[i]);
    }
}
