/*
 * Spectra the library and its atmosphere reference share: the sampled
 * visible range, the sun's spectrum, the CIE 1931 colour matching
 * functions, and the atmosphere description's coefficients at any
 * wavelength. The library takes its sun and its render wavelengths from
 * here; the reference (reference.c, built into sky-bench and the tests
 * only) renders its spectra through the same code, so the real-time paths
 * and their yardstick are lit and coloured alike.
 *
 * Kept free of sky_internal.h so that the reference, which lives outside
 * the library, needs nothing of the library's internals.
 */
#ifndef SKY_ATMOSPHERE_SPECTRUM_H
#define SKY_ATMOSPHERE_SPECTRUM_H

#include "../sky.h"

#define SKY_SPECTRUM_SAMPLES 16    /* 400, 420, ..., 700 nm */
#define SKY_SPECTRUM_STEP_NM 20.0  /* nm between samples: each is a rectangle this wide */
#define SKY_SPECTRUM_LM_PER_W 683.0 /* lm/W: the luminous efficacy at 555 nm (CIE) */

/* Wavelength of spectral sample i (clamped to 0 .. SKY_SPECTRUM_SAMPLES-1), nm. */
double sky_spectrum_wavelength_nm(int i);
/* A quantity the atmosphere description gives at 680/550/440 nm
 * (v[0], v[1], v[2]) at any wavelength: ln(value) quadratic in ln(lambda)
 * through the three when all are positive (a power law comes out
 * exactly), else piecewise linear in lambda, constant outside 440..680 nm.
 * Never negative. */
double sky_spectrum_interpolate(const float v[3], double lambda_nm);
/* The atmosphere's sea-level coefficients (1/km) at any wavelength,
 * interpolated through the 680/550/440 nm values of the description (the
 * zero description or NULL is Earth); mie_extinction is never below
 * mie_scattering. Any output pointer may be NULL. */
void sky_spectrum_coefficients(const sky_atmosphere_params *atm, double lambda_nm, double *rayleigh_scattering,
                               double *mie_scattering, double *mie_extinction, double *ozone_absorption);
/* Solar spectral irradiance at the top of the atmosphere, W m^-2 nm^-1
 * (a 5778 K blackbody scaled to 1361 W/m^2); 0 for a non-positive or
 * non-finite wavelength. */
double sky_spectrum_solar_irradiance(double lambda_nm);
/* The CIE 1931 2-degree colour matching functions x, y, z at lambda_nm
 * (Wyman, Sloan & Shirley's analytic fit). */
void sky_spectrum_cmf(double lambda_nm, double xyz_bar[3]);
/* A spectrum sampled at the SKY_SPECTRUM_SAMPLES wavelengths to CIE XYZ:
 * radiance (W m^-2 sr^-1 nm^-1) gives kcd/m^2, irradiance klx. */
void sky_spectrum_to_xyz(const double s[SKY_SPECTRUM_SAMPLES], double xyz[3]);
/* The sun's illuminance above the atmosphere as CIE XYZ, klx (Y ~ 128). */
void sky_spectrum_sun_xyz(double xyz[3]);
/* CIE XYZ to linear sRGB: the library's own matrix, for callers that do
 * not see sky_internal.h. */
void sky_spectrum_xyz_to_linear_srgb(const double xyz[3], double rgb[3]);

#endif
