/*
 * The physical paths against published photometry of real skies (issue
 * Real skies): the shape of the clear sky against the CIE standard general
 * skies (ISO 15469 / CIE S 011), zenith luminance against Radiance's
 * gensky clear sky, illuminances against the IES clear-sky formulas and
 * Bond & Henderson's twilight, the night zenith against Garstang and Benn &
 * Ellison. Measured on HDR renders of the upper hemisphere (the discs left
 * out) and on sky_get_lighting. sky-bench prints it; the tests hold the
 * figures that meet their targets.
 */
#ifndef SKY_PHOTOMETRY_H
#define SKY_PHOTOMETRY_H

#include "sky.h"

#include <stddef.h>

/* Sun altitudes of the CIE shape rows, degrees. */
#define SKY_PHOT_SHAPES 4
extern const double sky_phot_shape_suns[SKY_PHOT_SHAPES];

typedef struct sky_photometry {
    /* median over the sky (zenith angle < 75 deg, > 12 deg from the sun)
     * of |(L/Lz) / CIE - 1| against the closest of types 11, 12 and 13,
     * and that type */
    double cie_median[SKY_PHOT_SHAPES];
    int cie_type[SKY_PHOT_SHAPES];
    double glow_ratio_30;     /* mean L/Lz on the ring 5-8 deg around the sun, sun 30 deg */
    double horizon_ratio_70;  /* mean L/Lz at zenith angles 80-85 deg within
                                 15 deg of the azimuth opposite the sun, sun 70 */
    double zenith_kcd_70;     /* zenith luminance, sun 70 deg, kcd/m^2          */
    double diffuse_klx_30;    /* sky illuminance on a horizontal surface, sun 30 */
    double direct_klx_10;     /* sun_color's luminance (direct normal), sun 10   */
    double civil_lx;          /* sky illuminance on a horizontal surface, sun -6 */
    double nautical_lx;       /* the same, sun -12                               */
    double night_zenith_mag;  /* zenith at sun -30, no moon, mag/arcsec^2        */
} sky_photometry;

/* The published figures, in the same fields (cie_median 0: no published
 * shape error; the CIE ratios from the type 12 formula). */
void sky_photometry_published(sky_photometry *out);

/* The CIE standard general sky of type 11, 12 or 13: L/Lz for a sky
 * element at zenith angle z_rad, chi_rad from the sun at zenith angle
 * zs_rad (ISO 15469:2004 / CIE S 011/E:2003, its gradation and indicatrix
 * functions). */
double sky_cie_ratio(int type, double z_rad, double chi_rad, double zs_rad);

/* The formulas the published figures come from: Radiance gensky's clear
 * sky zenith luminance (Karayel et al. 1984), kcd/m^2, for turbidity t and
 * sun altitude; IES clear-sky diffuse horizontal and direct normal
 * illuminance, klx. */
double sky_gensky_zenith_kcd(double turbidity, double sun_alt_deg);
double sky_ies_diffuse_klx(double sun_alt_deg);
double sky_ies_direct_normal_klx(double sun_alt_deg);
/* Luminance in kcd/m^2 as mag/arcsec^2 (1 cd/m^2 = 12.58). */
double sky_mag_arcsec2(double kcd);

/* Measures a config's sky (its atmosphere path and description; output,
 * features and the rest are set here). Needs no current context. Returns
 * 0 or -1 with err. */
int sky_photometry_measure(const sky_config *cfg, sky_photometry *out, char *err, size_t err_len);

/* The sky's illuminance on a horizontal surface, lx, for the sun at each
 * of alts (degrees, apparent), as sky_photometry_measure takes it. */
int sky_photometry_sky_lux(const sky_config *cfg, const double *alts, int n, double *lux, char *err, size_t err_len);

#endif
