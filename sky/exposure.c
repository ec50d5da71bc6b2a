/*
 * The exposure room (exposure.h): what the tone map and the layers' LDR
 * gains take from the scene's brightness, once the atmosphere has set it.
 */
#include "exposure.h"

#include <math.h>

void sky_exposure_frame(sky_core *s)
{
    sky_frame *f = &s->frame;
    /* The few minutes of a total solar eclipse are too short for the eye
     * to adapt to its dimmed sky (the rods take tens of minutes): the
     * exposure follows the square root of the eclipse's dimming (the mean
     * that the atmosphere applied to sky_luminance), so totality looks
     * like deep twilight around a bright corona, not like day. The stars
     * (the catalogue, the star map and the flicker stars) are judged
     * against the sky around them, as the moon is (moon.c): in LDR they
     * keep the contrast a full adaptation would give them. */
    double withheld = 1.0 / sqrt(sky_clampd(f->eclipse_sky_mean, 1e-6, 1.0));
    f->star_local_gain = s->cfg.output == SKY_OUTPUT_HDR ? 1.0f : (float)withheld;
    /* Automatic exposure from the scene's own brightness: the day sky's
     * scale maps to the filmic curve's shoulder (common.glsl); at night a
     * floor 75 times the night sky (moonlit or not) keeps the sky dark blue
     * and the stars bright. */
    double adapt = f->sky_luminance * withheld + 75.0 * f->night_luminance;
    f->exposure = (float)(pow(2.0, s->exposure_bias) / adapt);
    /* Night vision: the adaptation luminance (what the exposure maps to
     * mid grey) from photopic, above 3 cd/m^2, to scotopic, below 0.01
     * cd/m^2, on a log scale; the shift is at most 60 % (the moon and
     * stars keep a little colour in the eye of a game player). */
    f->night_shift = (float)(0.6 * sky_smoothstep(log10(3e-3), log10(1e-5), log10(adapt)));
}
