/*
 * The exposure room: after the atmosphere, before the layers. The
 * automatic exposure from the scene's own brightness, the night vision
 * shift of the tone map, and the stars' local gain during a solar eclipse.
 */
#ifndef SKY_EXPOSURE_H
#define SKY_EXPOSURE_H

#include "core.h"

void sky_exposure_frame(sky_core *s);

#endif /* SKY_EXPOSURE_H */
