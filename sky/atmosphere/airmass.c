/*
 * Extinction along a ray from the ground: the analytic paths' direct beam
 * (Kasten & Young's air mass over fixed zenith optical depths: the
 * gradient sky's sun and moon, the sun's colour where no table is built),
 * and the night's extinction through the frame's spherical shell (the
 * stars, the moon, the night glows). A leaf: the paths, the dispatcher and
 * the layers call it, it calls none of them.
 */
#include "atmosphere.h"

#include <math.h>

void sky_sun_transmittance(double altitude, float out[3])
{
    /* Zenith optical depths at 680, 550, 440 nm: Rayleigh (Bruneton's
     * coefficients times an 8 km scale height) plus aerosol of optical
     * depth 0.1 at 550 nm with Angstrom exponent 1.3. */
    static const double tau[3] = {0.046 + 0.076, 0.108 + 0.100, 0.265 + 0.134};
    /* Kasten & Young (1989) air mass, fitted down to the horizon. Below it
     * the fit is meaningless (its air mass peaks near -2 degrees and falls
     * again towards its pole at -6.08, so the beam would brighten as the
     * sun sinks); a ray there meets the ground, and what still reaches the eye is the
     * rim of a setting disc, seen along the horizon: hold the horizon's
     * value. How much of the disc is left is sky_disc_above_horizon's. */
    double h_deg = sky_clampd(altitude * 180.0 / SKY_PI, 0.0, 90.0);
    double airmass = 1.0 / (sin(h_deg * SKY_PI / 180.0) + 0.50572 * pow(h_deg + 6.07995, -1.6364));
    for (int i = 0; i < 3; i++) out[i] = (float)exp(-tau[i] * airmass);
}

void sky_night_extinction(const sky_core *s, const double d[3], double t[3])
{
    const sky_frame *f = &s->frame;
    double a = f->night_shell[0], b = f->night_shell[1], c = sky_clampd(d[1], -1.0, 1.0);
    double path = sqrt(fmax(b * b - a * a * (1.0 - c * c), 0.0)) - a * c;
    double airmass = path / fmax(f->night_shell[2], 1e-3);
    for (int i = 0; i < 3; i++) t[i] = exp(-f->night_depth[i] * airmass);
}
