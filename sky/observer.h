/*
 * The astronomy room's face toward the rest of the library: the observer
 * (checked, with the time slider's time of day when it asks for one) and
 * its astronomy (astro.c) in the public sky_astronomy form. Pure C, no GL.
 */
#ifndef SKY_OBSERVER_H
#define SKY_OBSERVER_H

#include "core.h"

sky_observer sky_default_observer(void);
int sky_observer_check(const sky_observer *o, char *err, size_t err_len);
/* Astronomy for the observer, with the time slider's time of day when the
 * observer asks for it; cache may be NULL (astro.h: the result is the same). */
int sky_observer_astro(const sky_observer *o, double time_of_day, sky_astro_cache *cache, sky_astro *a, char *err,
                       size_t err_len);
void sky_astronomy_from_astro(const sky_astro *a, sky_astronomy *out);
/* The planets into out->planets: from places already computed, or
 * computed now for a's instant (the full series, some 30 us). */
void sky_planets_out(const sky_astro_planet places[SKY_ASTRO_PLANETS], sky_astronomy *out);
void sky_planets_fill(const sky_astro *a, sky_astronomy *out);

#endif /* SKY_OBSERVER_H */
