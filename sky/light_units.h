/*
 * Light units and colour shared by the rooms that turn magnitudes and
 * colour indices into light (the stars, the planets, the moon, the night
 * glows, the atmosphere's night floor): one zero point, the surface
 * brightness conversions and the colour of a B - V. Pure C, no GL, no
 * state: a module every room may include without depending on another.
 */
#ifndef SKY_LIGHT_UNITS_H
#define SKY_LIGHT_UNITS_H

#include <math.h>

/* Illuminance of a V = 0 source above the atmosphere, 2.54e-6 lux (Allen's
 * Astrophysical Quantities), in klx: the one zero point the stars and the
 * moon's magnitude share. */
#define SKY_V0_ILLUMINANCE_KLX 2.54e-9
/* A surface brightness in V mag/arcsec^2 as luminance (kcd/m^2) and back,
 * from that zero point: 0 mag/arcsec^2 is 108 kcd/m^2, 22 is 0.17 mcd/m^2. */
#define SKY_ARCSEC2_SR 2.35044305391e-11
static inline double sky_mag_arcsec2_to_kcd(double mag)
{
    return SKY_V0_ILLUMINANCE_KLX / SKY_ARCSEC2_SR * pow(10.0, -0.4 * mag);
}
/* (the way back is in light_units.c: only the tests call it, and a static
 * function nothing calls would be flagged in the amalgamation, where this
 * header is part of the one source file) */
double sky_kcd_to_mag_arcsec2(double kcd);

/* B - V to linear sRGB of unit luminance (light_units.c). */
void sky_star_color(double bv, float rgb[3]);
/* CIE 1931 XYZ to linear sRGB (IEC 61966-2-1). */
void sky_xyz_to_linear_srgb(const double xyz[3], double rgb[3]);

#endif /* SKY_LIGHT_UNITS_H */
