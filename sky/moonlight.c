/*
 * The moon as a light: its photometry (the full moon's luminance, the
 * phase law, its colour) and the light it sends above the air. Below the
 * layers: the atmosphere's moonlit sky, the clouds and the moon's disc
 * (moon.c) all take the one scale from here.
 */
#include "moonlight.h"

#include <math.h>

/* The moon's photometry, one scale for the drawn disc and the host's
 * moonlight (sky_get_lighting): the full moon's visual magnitude at its
 * mean distance, -12.73 (Krisciunas & Schaefer 1991, eq. 8 at phase angle
 * 0), through the V = 0 illuminance the stars use (layer.h): 0.314 lx
 * above the atmosphere, 0.255 lx at the zenith after this library's
 * extinction (published: about 0.24-0.27 lx). Spread over the true disc at
 * that distance it is a mean luminance of 4.9 kcd/m^2 (lighting handbooks'
 * round 2.5 kcd/m^2 gives only half the published illuminance). */
#define MOON_FULL_V (-12.73)
#define MOON_MEAN_DISTANCE_KM 384400.0 /* K&S's normalising distance */
/* The full moon's mean luminance above the atmosphere, kcd/m^2: its
 * illuminance at the mean distance over the solid angle of its disc there
 * (a cap of angular radius asin(R / d): 2 pi (1 - cos)). Luminance does not
 * change with distance; the disc's solid angle carries the 1 / r^2. */
double sky_moon_full_luminance(void)
{
    double e = SKY_V0_ILLUMINANCE_KLX * pow(10.0, -0.4 * MOON_FULL_V);
    double sd = asin(SKY_MOON_RADIUS_KM / MOON_MEAN_DISTANCE_KM);
    return e / (2.0 * SKY_PI * (1.0 - cos(sd)));
}

/* The moon's phase law relative to full, Krisciunas & Schaefer (1991)
 * eq. 8 (after Allen's Astrophysical Quantities): the magnitude grows by
 * 0.026 |a| + 4e-9 a^4, a the phase angle in degrees. */
double sky_moon_phase_law(double phase)
{
    double a = sky_clampd(fabs(phase), 0.0, SKY_PI) * 180.0 / SKY_PI;
    return pow(10.0, -0.4 * (0.026 * a + 4e-9 * a * a * a * a));
}

/* Mueller's k_lambda (sec. 2.2.2), scaled to unit luminance: the moon's
 * reddish colour, in the disc and in its light alike. */
const double sky_moon_k_lambda[3] = {0.92 / 0.807, 0.79 / 0.807, 0.64 / 0.807};

/* The direction to the sun seen from the moon (both topocentric,
 * geometric: the exact phase geometry for this observer), and its angle
 * from the direction back to the observer: the phase angle. */
double sky_moon_sun_from_moon(const sky_astro *a, double l[3])
{
    const double *mt = a->moon.dir_geometric;
    double n = 0.0;
    for (int i = 0; i < 3; i++) {
        l[i] = a->sun.dir_geometric[i] * a->sun.topo_distance_km - mt[i] * a->moon.topo_distance_km;
        n += l[i] * l[i];
    }
    n = sqrt(n);
    double c = 0.0;
    for (int i = 0; i < 3; i++) l[i] /= n > 0.0 ? n : 1.0, c -= l[i] * mt[i];
    return acos(sky_clampd(c, -1.0, 1.0));
}

void sky_moon_light_above_air(const sky_core *s, double light[3])
{
    const sky_astro *a = &s->astro;
    /* what the true-size disc sums to (moon.c's frame): the full moon's
     * mean luminance over the disc's solid angle at its distance from the
     * observer (1 / r^2: +-14 % between perigee and apogee), times the
     * phase law and the moon's colour */
    double l[3];
    double phase = sky_moon_sun_from_moon(a, l);
    double omega = 2.0 * SKY_PI * (1.0 - cos(a->moon_topo_semidiameter));
    double e = sky_moon_full_luminance() * omega * sky_moon_phase_law(phase);
    for (int i = 0; i < 3; i++) light[i] = e * sky_moon_k_lambda[i];
}
