/*
 * The moon as a light (moonlight.c): one photometric scale for the drawn
 * disc, the moonlit sky, the clouds and the host's moonlight. Reads only
 * the frame's astronomy, so any room may use it.
 */
#ifndef SKY_MOONLIGHT_H
#define SKY_MOONLIGHT_H

#include "core.h"

#define SKY_MOON_RADIUS_KM 1737.4
/* The full moon's mean luminance above the atmosphere, kcd/m^2. */
double sky_moon_full_luminance(void);
/* The phase law relative to full at phase angle phase (radians). */
double sky_moon_phase_law(double phase);
/* Mueller's k_lambda scaled to unit luminance: the moon's colour. */
extern const double sky_moon_k_lambda[3];
/* The direction to the sun seen from the moon (topocentric, geometric)
 * into l; returns the phase angle. */
double sky_moon_sun_from_moon(const sky_astro *a, double l[3]);
/* The moon's illuminance above the air on a surface facing it, klx per
 * channel (phase, distance and colour; no extinction): what the moonlit
 * sky scatters. */
void sky_moon_light_above_air(const sky_core *s, double light[3]);

#endif /* SKY_MOONLIGHT_H */
