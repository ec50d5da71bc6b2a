/*
 * The exposure room: after the atmosphere, before the layers. The
 * automatic exposure from the scene's own brightness, the night vision
 * shift of the tone map, the stars' local gain during a solar eclipse,
 * and the naked eye's limiting magnitude against the sky.
 */
#ifndef SKY_EXPOSURE_H
#define SKY_EXPOSURE_H

#include "core.h"

void sky_exposure_frame(sky_core *s);
/* The display's partial adaptation: how many stops (<= 0) darker than full
 * adaptation a scene adapted to adapt_kcd shows, for sky_config's
 * exposure_range (exposure.c). */
double sky_display_stops(double adapt_kcd, double range_stops);
/* Schaefer (1990, PASP 102, 212): the V magnitude of the faintest point
 * the naked eye sees against a sky of luminance b (kcd/m^2). */
double sky_naked_eye_limit(double b_kcd);

#endif /* SKY_EXPOSURE_H */
