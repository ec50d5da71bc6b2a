/*
 * The solar eclipse room (solar_eclipse.h).
 */
#include "solar_eclipse.h"

#include <math.h>

static const sky_uniform_desc eclipse_sun_uniforms[] = {
    SKY_UL("u_eclipse_sun", SKY_U_F4, eclipse_sun, 1u << 2),
    SKY_UF("u_eclipse_moon_dir", SKY_U_F3, eclipse_moon_dir),
};
const sky_snippet sky_solar_eclipse_sun_snippet = {NULL, NULL, eclipse_sun_uniforms, SKY_UNIFORM_COUNT(eclipse_sun_uniforms),
                                                   NULL, NULL, NULL};

double sky_solar_eclipse_light_left(const sky_core *s)
{
    if (!(s->features & SKY_SOLAR_ECLIPSE)) return 1.0;
    return sky_clampd(s->astro.solar_flux_fraction, 0.0, 1.0);
}

/* A solar eclipse takes from the day sky the light the moon hides
 * (astro.c's limb-darkened fraction); around totality the air outside the
 * moon's shadow leaves a twilight glow, brightest along the horizon
 * (atmosphere.glsl's sky_eclipse_dim). The CPU summary that the exposure,
 * clouds, moon and host lighting read is dimmed by the same amounts:
 * the ring's (1 - sin h)^8 averages 1/9 over the hemisphere's solid angle,
 * 1/45 weighted by the cosine (irradiance), and for fog takes its value
 * where the fog was taken (fog_sine: its elevation sine). The night
 * sky's own light is not the sun's and stays. */
void sky_solar_eclipse_sky(sky_core *s, double fog_sine)
{
    sky_frame *f = &s->frame;
    double left = sky_solar_eclipse_light_left(s);
    /* the ring's colour, of unit luminance: sunlight reddened by a long
     * low path */
    static const double ring_tint[3] = {1.34, 0.94, 0.60};
    double base = left + (1.0 - left) * SKY_ECLIPSE_ZENITH_RESIDUAL;
    double ring = (1.0 - left) * (SKY_ECLIPSE_HORIZON_RESIDUAL - SKY_ECLIPSE_ZENITH_RESIDUAL);
    f->eclipse_sky[0] = (float)base;
    for (int i = 0; i < 3; i++) f->eclipse_sky[1 + i] = (float)(ring * ring_tint[i]);
    f->eclipse_sky_mean = (float)(base + ring / 9.0);
    if (left >= 1.0) return;
    f->sky_luminance *= f->eclipse_sky_mean;
    double e = 1.0 - fog_sine, e2 = e * e, e4 = e2 * e2;
    for (int i = 0; i < 3; i++) {
        double irr = base + ring * ring_tint[i] / 45.0, fog = base + ring * ring_tint[i] * e4 * e4;
        f->ambient_rgb[i] = (float)(f->ambient_rgb[i] * irr + SKY_PI * f->night_luminance * (1.0 - irr));
        f->fog_rgb[i] = (float)(f->fog_rgb[i] * fog + f->night_luminance * (1.0 - fog));
    }
}

/* Sun.frag hides what lies behind the moon's true disc. Both discs take
 * their true sizes, the one scale at which the contacts fall at the right
 * times (moon.c draws the moon at it near the sun). The glare keeps the
 * uncovered light's share, and the corona shows once the sun's last 10 %
 * go: Baumbach's (1937) brightness relative to the sun's mean disc is
 * 1e-6 (0.0532 r^-2.5 + 1.425 r^-7 + 2.565 r^-17), r in solar radii;
 * sun.frag evaluates the bracket, and the factor before it is 1e-6 times
 * the mean disc, 0.8 of the centre's luminance. */
void sky_solar_eclipse_sun(sky_core *s, double sun_luminance)
{
    sky_frame *f = &s->frame;
    const sky_astro *a = &s->astro;
    f->eclipse_sun.unused = 0.0f;
    if (!(s->features & SKY_SOLAR_ECLIPSE)) { /* no moon in front: nothing hidden */
        for (int i = 0; i < 3; i++) f->eclipse_moon_dir[i] = 0.0f;
        f->eclipse_sun.moon_radius = 0.0f;
        f->eclipse_sun.light_left = 1.0f;
        f->eclipse_sun.corona_scale = 0.0f;
        return;
    }
    for (int i = 0; i < 3; i++) f->eclipse_moon_dir[i] = (float)a->moon.dir_geometric[i];
    f->eclipse_sun.moon_radius = (float)a->moon_topo_semidiameter;
    f->eclipse_sun.light_left = (float)a->solar_flux_fraction;
    f->eclipse_sun.corona_scale =
        (float)(1e-6 * 0.8 * sun_luminance * sky_smoothstep(0.9, 0.999, a->solar_obscuration));
}
