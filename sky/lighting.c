/*
 * The light a host's scene receives from the sky: the sun's and the
 * moon's direct light, the ambient and fog colours (sky_get_lighting),
 * the irradiance as spherical harmonics (sky_get_irradiance_sh, from
 * irradiance.c's projection of the sky) and its evaluation for a normal.
 */
#include "sky_internal.h"

#include <math.h>
#include <string.h>

void sky_sun_beam(const sky_core *c, float rgb[3])
{
    const sky_frame *f = &c->frame;
    /* Solar illuminance above the atmosphere (sun.c: 128 klx at 1 au, what
     * the drawn disc sums to), through the atmosphere, times the part of
     * the disc not yet set */
    float above = (float)sky_disc_above_horizon(f->sun_altitude, c->astro.sun_semidiameter);
    /* and the share of its light a solar eclipse leaves */
    above *= (float)sky_solar_eclipse_light_left(c);
    float e0 = (float)sky_sun_illuminance_klx(c);
    for (int i = 0; i < 3; i++) rgb[i] = e0 * f->sun_transmittance[i] * above;
    /* a weather's deck (weather.c), which covers the sky alike, lets
     * light_through of the light above pass, diffused: the beam keeps the
     * square of that share (what passes unscattered is far less than what
     * passes at all). The broken layers' shadows are the cloud shadow
     * map's (sky_get_cloud_shadow), not this. Without a weather nothing
     * changes. */
    if (f->deck > 0.0f) {
        float direct = 1.0f - f->deck * (1.0f - f->light_through * f->light_through);
        for (int i = 0; i < 3; i++) rgb[i] *= direct;
    }
}

double sky_optics_light(const sky_core *c, int sun_allowed, int moon_allowed, float rgb[3], float dir[3],
                        int *by_moon)
{
    const sky_frame *f = &c->frame;
    float beam[3], moon[3] = {0.0f, 0.0f, 0.0f};
    sky_sun_beam(c, beam);
    if (c->features & SKY_MOON) sky_moon_lighting(c, moon);
    double sun_y = sun_allowed ? 0.2126 * beam[0] + 0.7152 * beam[1] + 0.0722 * beam[2] : 0.0;
    double moon_y = moon_allowed ? 0.2126 * moon[0] + 0.7152 * moon[1] + 0.0722 * moon[2] : 0.0;
    *by_moon = moon_y > sun_y;
    const float *d = *by_moon ? f->moon_dir : f->sun_dir;
    for (int i = 0; i < 3; i++) {
        rgb[i] = *by_moon ? (float)moon_y : beam[i];
        dir[i] = d[i];
    }
    return fmax(sun_y, moon_y);
}

sky_result sky_get_lighting(const sky *s, sky_lighting *out)
{
    if (!s || !out) return SKY_ERR_INVALID_ARGUMENT;
    const sky_core *c = &s->core;
    const sky_frame *f = &c->frame;
    memset(out, 0, sizeof *out);
    sky_camera_to_world(c, f->sun_dir, out->sun_direction);
    out->sun_altitude_deg = (float)(f->sun_altitude * 180.0 / SKY_PI);
    sky_sun_beam(c, out->sun_color);
    /* sky irradiance and horizon: the atmosphere path's (atmosphere.c; the
     * ambient and fog colours greyed by a weather's deck: weather.c) */
    for (int i = 0; i < 3; i++) {
        out->ambient_color[i] = f->ambient_rgb[i];
        out->fog_color[i] = f->fog_rgb[i];
    }
    out->daylight = f->daylight;
    out->exposure = f->exposure;
    out->fog_density = 3.912f / (1000.0f * f->visibility_km); /* Koschmieder */
    /* lightning: the flash's light (weather.c), in its tint scaled to a
     * luminance (Rec. 709) of one */
    const float *tint = sky_flash_tint;
    float tint_luma = 0.2126f * tint[0] + 0.7152f * tint[1] + 0.0722f * tint[2];
    sky_camera_to_world(c, f->flash_dir, out->flash_direction);
    for (int i = 0; i < 3; i++) out->flash_color[i] = f->flash_klx * tint[i] / tint_luma;
    if (c->features & SKY_MOON) {
        sky_camera_to_world(c, f->moon_dir, out->moon_direction);
        sky_moon_lighting(c, out->moon_color);
    }
    return SKY_OK;
}

sky_result sky_get_irradiance_sh(sky *s, sky_irradiance_sh *out)
{
    if (!s || !out) return SKY_ERR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    const double(*sh)[3] = sky_irradiance_cached(&s->core, &s->irradiance);
    for (int k = 0; k < SKY_SH_COUNT; k++)
        for (int i = 0; i < 3; i++) {
            if (k < 9)
                out->radiance[k][i] = (float)sh[k][i];
            else if (k < 18)
                out->radiance_l4[k - 9][i] = (float)sh[k][i];
            else
                out->radiance_zonal[k - 18][i] = (float)sh[k][i];
        }
    float up_h[3] = {0.0f, 1.0f, 0.0f};
    sky_camera_to_world(&s->core, up_h, out->up);
    sky_lighting l;
    sky_get_lighting(s, &l);
    for (int i = 0; i < 3; i++) {
        out->sun_direction[i] = l.sun_direction[i];
        out->sun_color[i] = l.sun_color[i];
        out->moon_direction[i] = l.moon_direction[i];
        out->moon_color[i] = l.moon_color[i];
    }
    return SKY_OK;
}

sky_result sky_irradiance_sh_eval(const sky_irradiance_sh *sh, const float normal[3], float irradiance[3])
{
    if (!sh || !normal || !irradiance) return SKY_ERR_INVALID_ARGUMENT;
    irradiance[0] = irradiance[1] = irradiance[2] = 0.0f;
    double len = 0.0;
    for (int i = 0; i < 3; i++) {
        if (!isfinite(normal[i])) return SKY_ERR_INVALID_ARGUMENT;
        len += (double)normal[i] * normal[i];
    }
    len = sqrt(len);
    if (!(len > 0.0) || !isfinite(len)) return SKY_ERR_INVALID_ARGUMENT;
    double n[3] = {normal[0] / len, normal[1] / len, normal[2] / len}, c[SKY_SH_COUNT][3], e[3];
    double up[3] = {sh->up[0], sh->up[1], sh->up[2]};
    for (int k = 0; k < SKY_SH_COUNT; k++)
        for (int i = 0; i < 3; i++)
            c[k][i] = k < 9 ? sh->radiance[k][i] : k < 18 ? sh->radiance_l4[k - 9][i] : sh->radiance_zonal[k - 18][i];
    /* (the cast: C before C23 makes no implicit double (*)[3] -> const double (*)[3]) */
    sky_irradiance_eval((const double(*)[3])c, n, up, e);
    /* a degree-2 sum can dip below zero facing a dark hemisphere */
    for (int i = 0; i < 3; i++) irradiance[i] = (float)fmax(e[i], 0.0);
    return SKY_OK;
}
