/*
 * The atmosphere reference: a CPU, double-precision, spectral model of
 * the sky's light that the real-time paths are measured against (issue 6,
 * sky-bench). Not real-time: milliseconds to seconds per direction.
 *
 * Model: a spherical planet and atmospheric shell (sky_atmosphere_params),
 * Rayleigh + Mie (Cornette-Shanks phase) + ozone with the same constants
 * as the real-time paths, interpolated to SKY_REF_WAVELENGTHS wavelengths
 * across the visible range; a Lambertian ground. Single scattering by
 * deterministic quadrature along the view ray (optical depth integrated
 * per segment analytically); orders >= 2 by Monte Carlo path tracing that
 * reports its own standard error. Spectra go to CIE 1931 XYZ (an analytic
 * fit of the colour matching functions) and to linear sRGB. The sun's
 * spectrum, the colour matching and the coefficients at any wavelength
 * are spectrum.h's, shared with the library.
 *
 * Not part of libsky: sky-bench and the tests compile it in.
 *
 * Frame: the horizon frame of sky.h (+y up). Directions are unit vectors;
 * view points away from the observer, sun points toward the sun.
 */
#ifndef SKY_ATMOSPHERE_REFERENCE_H
#define SKY_ATMOSPHERE_REFERENCE_H

#include "../sky.h"
#include "spectrum.h"

/* the shared spectral samples (spectrum.h): 400, 420, ..., 700 nm */
#define SKY_REF_WAVELENGTHS SKY_SPECTRUM_SAMPLES

typedef struct sky_ref_options {
    int view_segments;  /* single scattering: segments along the view ray; 0 = 256 */
    int sun_segments;   /* optical depth toward the sun per sample; 0 = 128        */
    int paths;          /* Monte Carlo paths per wavelength for orders >= 2; 0 = 256 */
    int max_order;      /* highest scattering order; 0 = all (Russian roulette), 1 = single only */
    unsigned long long seed; /* 0 = a fixed default: results are reproducible  */
    double only_nm;     /* 0: all wavelengths; else this one wavelength alone,
                           reported in spectral[0] (xyz and rgb stay zero)     */
    double max_distance_km; /* 0: the whole view ray; else only the light
                           scattered into it within this distance of the eye
                           (aerial perspective), and transmittance[] to there */
} sky_ref_options;

typedef struct sky_ref_result {
    double spectral[SKY_REF_WAVELENGTHS];         /* W m^-2 sr^-1 nm^-1     */
    double spectral_std_err[SKY_REF_WAVELENGTHS]; /* of the Monte Carlo part */
    double single[SKY_REF_WAVELENGTHS];           /* the single-scattering part alone */
    double xyz[3];             /* Y = luminance in kcd/m^2                  */
    double rgb[3];             /* linear sRGB primaries, same scale as xyz  */
    double luminance_std_err;  /* kcd/m^2                                   */
    double transmittance[SKY_REF_WAVELENGTHS]; /* eye to the ray's end (or to
                                  max_distance_km), per spectral sample       */
    double transmittance_rgb[3]; /* of sunlight, per sRGB channel: rgb(E T) /
                                  rgb(E)                                       */
} sky_ref_result;

/* Transmittance from an observer at altitude_km along dir to space (0 if
 * the ray hits the ground), per spectral sample. */
void sky_ref_transmittance(const sky_atmosphere_params *atm, double altitude_km, const double dir[3],
                           double transmittance[SKY_REF_WAVELENGTHS]);
/* Radiance of the sky (the sun's disc excluded) seen from altitude_km
 * (0 .. above the top) along view. Returns 0, or -1 for bad input (an
 * invalid atmosphere, non-unit or non-finite vectors, options out of range). */
int sky_ref_radiance(const sky_atmosphere_params *atm, double altitude_km, const double view[3],
                     const double sun[3], const sky_ref_options *opt, sky_ref_result *out);

#endif
