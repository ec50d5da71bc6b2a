/*
 * The gradient atmosphere: Roden & Parberry's day sky (a blue gradient by
 * elevation, baked into the dome's vertices) scaled to physical luminance
 * by the sun's altitude. The cheapest path: no texture, no lookup table.
 */
#include "atmosphere.h"
#include "layer.h"
#include "moonlight.h"

#include <math.h>

static const sky_uniform_desc gradient_uniforms[] = {
    SKY_UL("u_day_luminance", SKY_U_F1, day_luminance, 1u),
    SKY_UF("u_sun_transmittance", SKY_U_F3, sun_transmittance),
    SKY_UF("u_horizon_tint", SKY_U_F3, horizon_tint),
    SKY_UL("u_moon_sky", SKY_U_F3, moon_sky, SKY_RGB),
    SKY_UF("u_moon_beam", SKY_U_F3, moon_beam),
};
/* in both stages: the dome evaluates this path per vertex (dome.vert) */
const sky_snippet sky_gradient_snippet = {"SKY_HAS_GRADIENT", "gradient.glsl", gradient_uniforms,
                                          SKY_UNIFORM_COUNT(gradient_uniforms), "gradient.glsl", NULL, NULL};

void sky_gradient_vertex(const unsigned char *gradient, const float d[3], float rgb[3])
{
    /* texel coordinate sqrt(elevation sine) * 255: more texels near the
     * horizon, where the gradient changes */
    double t = sqrt(sky_clampd(d[1], 0.0, 1.0)) * 255.0;
    int i0 = (int)t, i1 = i0 < 255 ? i0 + 1 : 255;
    double f = t - i0;
    for (int c = 0; c < 3; c++) rgb[c] = (float)((gradient[4 * i0 + c] * (1.0 - f) + gradient[4 * i1 + c] * f) / 255.0);
}

/* Luminance scale of the day sky (kcd/m^2) for a sun at altitude h. Above
 * the horizon it grows like (sin h + 0.25)^0.6 to 9.3 kcd/m^2 at the
 * zenith; below it falls by a decade every 3 degrees, which matches the
 * measured twilight sky: about 3 cd/m^2 at -6 (civil), 0.03 at -12
 * (nautical) and 3e-4 cd/m^2 at -18 degrees. The offset 0.25 makes the
 * two sides meet with the same slope (a bare sin^0.6 has an infinite one:
 * the sky jumped by 16 % in the first 0.01 degree of sunrise). */
static double day_sky_luminance(double altitude)
{
    double h_deg = altitude * 180.0 / SKY_PI;
    if (h_deg >= 0.0) {
        const double s0 = 0.25, base = pow(s0, 0.6);
        return 0.3 + 9.0 * (pow(sin(altitude) + s0, 0.6) - base) / (pow(1.0 + s0, 0.6) - base);
    }
    return 0.3 * pow(10.0, sky_clampd(h_deg, -90.0, 0.0) / 3.0);
}

/* The moonlit sky (Jensen et al. 2001: the day sky's own model lit by the
 * moon): the gradient for a sun at the moon's altitude, scaled by the
 * moon's light over the sun's above the air, per channel (phase, distance
 * and the moon's redder colour), with an aureole around the moon tinted
 * by its beam through the air. A full moon 67 degrees up gives a zenith
 * of 5.7 mcd/m^2 (test_atmosphere_moonlit_sky; Preetham's model gives 20,
 * measured skies near full moon 17-18 mag/arcsec^2, 7-17 mcd/m^2).
 * Returns the zenith's luminance, for the night's adaptation. */
double sky_gradient_moon(sky_core *s)
{
    sky_frame *f = &s->frame;
    for (int i = 0; i < 3; i++) f->moon_sky[i] = f->moon_beam[i] = 0.0f;
    if (!(s->features & SKY_MOON)) return 0.0;
    double alt = s->astro.moon.alt, top[3];
    sky_moon_light_above_air(s, top);
    double scale = day_sky_luminance(alt);
    for (int i = 0; i < 3; i++) f->moon_sky[i] = (float)(scale * top[i] / s->sun_irradiance_klx[i]);
    sky_sun_transmittance(alt, f->moon_beam);
    static const float zenith[3] = {0.0f, 1.0f, 0.0f};
    float day[3];
    sky_gradient_vertex(s->gradient_texels, zenith, day);
    return 0.2126 * f->moon_sky[0] * day[0] + 0.7152 * f->moon_sky[1] * day[1] + 0.0722 * f->moon_sky[2] * day[2];
}

void sky_gradient_frame(sky_core *s)
{
    sky_frame *f = &s->frame;
    f->day_luminance = f->sky_luminance = (float)day_sky_luminance(f->sun_altitude);
    /* The low-sun horizon colour: the square root of the direct beam's
     * transmittance (light that travelled about half the sun's path),
     * normalised to its red channel, and only 70 % saturated: the horizon
     * also sees light scattered from higher, bluer air. Per frame here,
     * not per pixel. */
    double red = f->sun_transmittance[0] > 1e-6f ? f->sun_transmittance[0] : 1e-6;
    for (int i = 0; i < 3; i++) f->horizon_tint[i] = (float)(0.3 + 0.7 * sqrt(f->sun_transmittance[i] / red));
    /* Lighting for the host: the sky irradiance on an upward surface is pi
     * times a mean sky luminance of about 0.35 of the gradient's scale
     * (blue-weighted), plus the night sky; fog takes the horizon's. */
    static const float sky_tint[3] = {0.55f, 0.75f, 1.0f};
    for (int i = 0; i < 3; i++) {
        f->ambient_rgb[i] = (float)SKY_PI * (0.35f * f->sky_luminance + f->night_luminance) * sky_tint[i];
        f->fog_rgb[i] = (0.8f * f->sky_luminance + f->night_luminance) * (0.75f + 0.25f * sky_tint[i]);
    }
}
