/*
 * The atmosphere paths measured against the CPU reference (issue 6): the
 * cached reference sky (an all-sky grid of directions for ten sun
 * elevations, computed by sky/atmosphere/reference.c) and the error of a
 * rendered sky against it. sky-bench prints it next to the run time; the
 * tests hold it under its target.
 */
#ifndef SKY_ATMO_ERROR_H
#define SKY_ATMO_ERROR_H

#include "osmesa_ctx.h"
#include "sky.h"

#include <stdio.h>

/* Sun elevations of the table, degrees: day (>= 0) and twilight (< 0). */
#define SKY_ATMO_SUNS 10
extern const double sky_atmo_sun_elevations[SKY_ATMO_SUNS];
/* Directions: equal-area rings (elevation sine (k + 0.5) / RINGS) times
 * azimuths from the sun's vertical 0..180 degrees (the sky is symmetric
 * about it). */
#define SKY_ATMO_RINGS 8
#define SKY_ATMO_AZIMUTHS 9
#define SKY_ATMO_DIRECTIONS (SKY_ATMO_RINGS * SKY_ATMO_AZIMUTHS)

typedef struct sky_atmo_reference {
    int paths;                                  /* Monte Carlo paths per wavelength */
    double rgb[SKY_ATMO_SUNS][SKY_ATMO_DIRECTIONS][3]; /* linear sRGB, kcd/m^2 */
    double std_err[SKY_ATMO_SUNS][SKY_ATMO_DIRECTIONS]; /* of the luminance    */
} sky_atmo_reference;

/* Direction k of the grid for a sun at azimuth sun_az_deg: elevation and
 * azimuth in degrees, and its weight (solid angle share, sums to 1). */
void sky_atmo_direction(int k, double sun_az_deg, double *elevation_deg, double *azimuth_deg, double *weight);

/* Computes the reference (Earth preset, observer at sea level) with the
 * given paths, on `threads` threads, progress dots to progress (or NULL),
 * and writes it to path. Minutes. Returns 0 or -1 with err. */
int sky_atmo_reference_make(const char *path, int paths, int threads, FILE *progress, char *err, size_t err_len);
int sky_atmo_reference_load(const char *path, sky_atmo_reference *ref, char *err, size_t err_len);

typedef struct sky_atmo_errors {
    double mean_rel[SKY_ATMO_SUNS], max_rel[SKY_ATMO_SUNS], mean_de2000[SKY_ATMO_SUNS];
    double mean_rel_day, max_rel_day, mean_rel_twilight, mean_de2000_day, mean_de2000_twilight;
} sky_atmo_errors;

/* Renders the sky of cfg (output forced to HDR, features to none) for
 * each sun elevation of the table, reads it at the grid's directions and
 * compares with the reference: relative luminance error (against the
 * reference luminance, floored at 1 % of that sky's mean) and CIEDE2000
 * after a fixed exposure (the reference sky's mean luminance at L* 76).
 * Needs no current context (makes its own). Returns 0 or -1 with err. */
int sky_atmo_measure(const sky_atmo_reference *ref, const sky_config *cfg, sky_atmo_errors *out, char *err,
                     size_t err_len);

/* An HDR sky of a config (features none, every pixel) rendered into the
 * six faces of a cube in a context of its own, so that any direction of
 * the upper hemisphere can be read: what the error table and the
 * photometry measure (and the ground below, for the irradiance). The observer stands on the 2026 March equinox
 * where the noon sun reaches the zenith. */
typedef struct sky_atmo_hemisphere sky_atmo_hemisphere;
sky_atmo_hemisphere *sky_atmo_hemisphere_create(const sky_config *cfg, char *err, size_t err_len);
void sky_atmo_hemisphere_destroy(sky_atmo_hemisphere *h);
/* Renders the sky with the sun's apparent centre at sun_alt_deg (the
 * morning sun), giving the sun's elevation and azimuth as the sky has
 * them. Returns 0 or -1 with err. */
int sky_atmo_hemisphere_render(sky_atmo_hemisphere *h, double sun_alt_deg, double *elevation_deg,
                               double *azimuth_deg, char *err, size_t err_len);
/* Linear sRGB (kcd/m^2) in direction d of the horizon frame (y up). */
void sky_atmo_hemisphere_read(const sky_atmo_hemisphere *h, const double d[3], double rgb[3]);
/* The irradiance (klx) of the rendered sphere on a surface of unit
 * normal n (horizon frame), summed over every pixel of the six faces. */
void sky_atmo_hemisphere_irradiance(const sky_atmo_hemisphere *h, const double n[3], double rgb[3]);
/* For the sky last rendered, the luminance (klx) of its irradiance on a
 * surface of unit normal n: from the render (as above), from
 * sky_get_irradiance_sh with every coefficient, and from its 9 of degree
 * <= 2 alone (what a shader reading only those gets). */
void sky_atmo_hemisphere_sh_check(sky_atmo_hemisphere *h, const double n[3], double *rendered, double *sh_all,
                                  double *sh_nine);
/* The sky, for its lighting (sky_get_lighting after a render). */
sky *sky_atmo_hemisphere_sky(sky_atmo_hemisphere *h);
/* Its GL context (current while h lives), for a caller's own GL calls. */
const sky_osmesa *sky_atmo_hemisphere_context(const sky_atmo_hemisphere *h);
/* The clouds the next renders draw (a config with SKY_CLOUDS; none by
 * default). */
void sky_atmo_hemisphere_clouds(sky_atmo_hemisphere *h, float cover, float density);

/* The morning time-slider value (0..0.5) that puts the sun's apparent
 * centre at alt_deg for the observer (bisection; at the highest the sun
 * gets, noon). */
double sky_atmo_time_for_altitude(const sky_observer *o, double alt_deg);

/* CIEDE2000 colour difference of two CIELAB colours (Sharma, Wu & Dalal
 * 2005). */
double sky_atmo_de2000(const double lab1[3], const double lab2[3]);

#endif
