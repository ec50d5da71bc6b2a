/*
 * The sky's radiance as spherical harmonics of degree 0..2, for the
 * host's ambient light (irradiance.c; sky_get_irradiance_sh in sky.h).
 */
#ifndef SKY_IRRADIANCE_H
#define SKY_IRRADIANCE_H

#include "core.h"

/* degrees 0..2 (9) and 4 (9 more): degree 3 and every odd degree above 1
 * carry nothing to a Lambertian surface */
#define SKY_SH_COUNT 20

/* The real basis Y_lm at unit direction w (sky.h gives the order). */
void sky_sh_basis(const double w[3], double y[SKY_SH_COUNT]);
/* The atmosphere's radiance (sky_atmosphere_radiance) under the clouds'
 * mean (sky_clouds_mean_at) over the whole sphere projected on the basis
 * in the world frame, kcd/m^2. */
void sky_irradiance_project(const sky_core *s, double sh[SKY_SH_COUNT][3]);
/* The projection kept for as long as what it depends on stays: the
 * frame's sun, the moon on the gradient, night floor, eclipse, ground and
 * horizon, the gradient's and the blend's scales, the observer, the world
 * frame, Hillaire's table in use and the clouds. */
enum { SKY_ATMOSPHERE_KEY = 44, SKY_IRRADIANCE_KEY = SKY_ATMOSPHERE_KEY + 9 };
/* What the atmosphere's light around the observer depends on, as numbers
 * that change when it does (the aerial perspective table's key; the SH's
 * adds the clouds'). */
void sky_atmosphere_key(const sky_core *s, double key[SKY_ATMOSPHERE_KEY]);
typedef struct sky_irradiance_cache {
    int valid;
    double key[SKY_IRRADIANCE_KEY];
    double sh[SKY_SH_COUNT][3];
} sky_irradiance_cache;
const double (*sky_irradiance_cached(const sky_core *s, sky_irradiance_cache *cache))[3];
/* Irradiance (klx) on a surface of unit normal n from projected radiance. */
void sky_irradiance_eval(const double sh[SKY_SH_COUNT][3], const double n[3], const double up[3], double out[3]);
/* degrees 6 and 8 about the horizon's up (t = up . direction) into y[18..19] */
void sky_sh_zonal(double t, double y[SKY_SH_COUNT]);

#endif
