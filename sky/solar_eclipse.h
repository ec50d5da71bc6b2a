/*
 * The solar eclipse room: what the moon in front of the sun does to the
 * frame, from astro.c's geometry (sky_solar_eclipse: obscuration,
 * magnitude, the limb-darkened light left). With SKY_SOLAR_ECLIPSE left
 * out, the sky, the sun and the host's light ignore it (the astronomy
 * still reports it). The atmosphere calls it for the sky's dimming; the
 * sun layer for its disc.
 */
#ifndef SKY_SOLAR_ECLIPSE_H
#define SKY_SOLAR_ECLIPSE_H

#include "gl/gl.h"

/* The share of the sun's light the moon leaves, 0..1 (1 without the
 * feature). */
double sky_solar_eclipse_light_left(const sky_core *s);
/* Dims the day sky's part of the frame (atmosphere.glsl's
 * sky_eclipse_dim and the CPU summary); fog_sine: the elevation sine the
 * atmosphere took its fog at. */
void sky_solar_eclipse_sky(sky_core *s, double fog_sine);
/* The sun disc's eclipse uniforms (sun.frag): the moon's true disc, the
 * glare's share and Baumbach's corona, for a sun of the given disc-centre
 * luminance (kcd/m^2). */
void sky_solar_eclipse_sun(sky_core *s, double sun_luminance);
/* Their uniform rows (sun.frag's u_eclipse_sun, u_eclipse_moon_dir). */
extern const sky_snippet sky_solar_eclipse_sun_snippet;

#endif /* SKY_SOLAR_ECLIPSE_H */
