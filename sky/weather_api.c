/*
 * sky_set_weather and sky_get_weather (sky.h, "Weather"): the calls that
 * hold the sky handle. The states, the clock and what a weather does to
 * the frame are weather.c's.
 */
#include "sky_internal.h"

#include <math.h>

/* The weather a sky without one shows: the clear state with the sliders'
 * clouds, the thin layer as they draw it and the sliders' drift (5 m/s
 * along the first layer's own direction). */
static void sliders_weather(const sky_core *c, sky_weather *w)
{
    sky_weather_preset(SKY_WEATHER_CLEAR, w);
    w->cover = c->params.cover;
    w->density = c->params.density;
    w->upper = 0.35f * c->params.cover;
    w->wind_speed_ms = 5.0f;
    /* the first layer's velocity as a wind */
    w->wind_from_deg = sky_weather_wind_from(sky_cloud_velocity[0][0], sky_cloud_velocity[0][1]);
}

sky_result sky_set_weather(sky *s, const sky_weather *target, double seconds)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!target) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_set_weather: target is NULL");
    if (!(s->core.features & SKY_WEATHER))
        return sky_fail(s, SKY_ERR_UNSUPPORTED,
                        "sky_set_weather: the sky was created without SKY_WEATHER (its shaders lack the weather's "
                        "deck, haze and flash)");
    if (!isfinite(seconds) || seconds < 0.0)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_set_weather: seconds = %g must be finite and >= 0", seconds);
    sky_weather to;
    char msg[sizeof s->error];
    sky_result rc = sky_weather_checked(target, &to, msg, sizeof msg);
    if (rc == SKY_ERR_INVALID_ARGUMENT) return sky_fail(s, rc, "%s", msg);
    sky_core *c = &s->core;
    sky_weather now;
    if (c->weather.set)
        sky_weather_at(&c->weather, c->running, &now);
    else
        sliders_weather(c, &now);
    c->weather.from = now;
    c->weather.to = to;
    c->weather.start = c->running;
    c->weather.seconds = seconds;
    c->weather.set = 1;
    sky_update(s, 0.0); /* the frame recomputed, nothing advanced */
    return rc == SKY_CLAMPED ? sky_fail(s, rc, "%s", msg) : SKY_OK;
}

sky_result sky_get_weather(const sky *s, sky_weather *out, int *moving)
{
    if (!s || !out) return SKY_ERR_INVALID_ARGUMENT;
    const sky_core *c = &s->core;
    if (c->weather.set)
        sky_weather_at(&c->weather, c->running, out);
    else
        sliders_weather(c, out);
    if (moving) {
        double u = c->weather.set ? sky_weather_progress(&c->weather, c->running) : 1.0;
        *moving = u > 0.0 && u < 1.0;
    }
    return SKY_OK;
}


sky_result sky_get_lightning(sky *s, double t0, double t1, sky_lightning_strike *out, int max, int *count)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (count) *count = 0;
    if (!isfinite(t0) || !isfinite(t1) || t0 < 0.0 || t1 < t0)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_get_lightning: the window %g .. %g must be finite, from 0 up",
                        t0, t1);
    if (t1 - t0 > 86400.0)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_get_lightning: a window of %g s is over a day", t1 - t0);
    if (max < 0 || (max > 0 && !out))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_get_lightning: max %d with out %s", max,
                        out ? "given" : "NULL");
    int n = sky_lightning_strikes(&s->core.weather, s->core.cfg.seed, t0, t1, out, max);
    if (count) *count = n;
    return SKY_OK;
}
