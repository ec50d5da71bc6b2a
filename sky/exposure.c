/*
 * The exposure room (exposure.h): what the tone map and the layers' LDR
 * gains take from the scene's brightness, once the atmosphere has set it.
 */
#include "exposure.h"

#include <math.h>

double sky_naked_eye_limit(double b_kcd)
{
    /* the threshold illuminance I = c1 (1 + sqrt(c2 B))^2 in foot-candles
     * for a sky of B nanolamberts (1 nL = 3.183e-6 cd/m^2), with the rods'
     * constants below 1500 nL and the cones' above; V = -16.57 - 2.5 log I
     * (Schaefer's conversion: V = 0 is 2.54e-6 lux) */
    double b = fmax(b_kcd, 0.0) * 1000.0 / 3.183e-6;
    double c1 = b < 1500.0 ? pow(10.0, -9.8) : pow(10.0, -8.35), c2 = b < 1500.0 ? pow(10.0, -1.9) : pow(10.0, -5.9);
    double root = 1.0 + sqrt(c2 * b);
    return -16.57 - 2.5 * log10(c1 * root * root);
}

/* Partial adaptation (issue "Dusk and night"): the eye adapts fully to
 * daylight at least FULL_ADAPTATION bright (the gradient sky's with the
 * sun some 20 degrees up; every path's noon is brighter); daylight s =
 * log2(daylight / FULL_ADAPTATION) < 0 stops below it shows d(s) = -range
 * (1 - exp(SLOPE s / range)) stops darker than full adaptation would show
 * it: 0.3 of each stop lost at first, never more than range in all. The
 * curve is smooth and falls everywhere below FULL_ADAPTATION, so the
 * display never jumps; engines' automatic exposures bound their range the
 * same way (a minimum and a maximum EV). sky_exposure_frame weights it by
 * the square root of daylight's share of what the eye adapts to: the
 * night's own light (the moon, the glows, the stars) is adapted to fully,
 * as before, so a night stays as legible as it was while twilight, lit by
 * the sun from below the horizon, reads as the day's end. With the
 * defaults the sky shows 0.50 of noon's brightness at sunset, 0.23 at -6
 * degrees and 0.16 at -12 on the gradient path (docs/DUSK.md). */
#define FULL_ADAPTATION_KCD 5.0
#define ADAPTATION_SLOPE 0.3
#define DEFAULT_RANGE_STOPS 3.0
/* the night's own light is adapted to partly (sky_exposure_frame): 0.40
 * keeps a full moon's sky, scattered by the paths' own models (darker away
 * from the moon than the uniform floor that stood for it before, at 0.35),
 * a day-for-night blue one can see (docs/DUSK.md) */
#define NIGHT_PARTIAL 0.40

double sky_display_stops(double adapt_kcd, double range_stops)
{
    double s = log2(fmax(adapt_kcd, 1e-30) / FULL_ADAPTATION_KCD);
    return s >= 0.0 ? 0.0 : -range_stops * (1.0 - exp(ADAPTATION_SLOPE * s / range_stops));
}

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
    double withheld = 1.0 / sqrt(sky_clampd(f->eclipse_sky_mean, 1e-6, 1.0)), daylight = f->sky_luminance * withheld;
    /* Automatic exposure from the scene's own brightness: the day sky's
     * scale maps to the filmic curve's shoulder (display.glsl); at night a
     * floor 120 times a natural dark sky's zenith keeps the sky dark and
     * the stars bright. The eye adapts no further than to that dark sky
     * (21.9 mag/arcsec^2, Benn & Ellison 1998): a scene that leaves the
     * airglow out is darker, not exposed up to the same grey. A brighter
     * night (the moon, light pollution) raises the floor by its brightness
     * over the dark sky's to the power 1 - NIGHT_PARTIAL only, so a
     * moonlit sky shows brighter than a moonless one, as the eye sees it,
     * where full adaptation showed both alike. */
    double dark = sky_mag_arcsec2_to_kcd(21.9), night = fmax(f->night_luminance, dark);
    double adapt = daylight + 120.0 * dark * pow(night / dark, 1.0 - NIGHT_PARTIAL);
    /* the display follows daylight down only partly (above; weighted by
     * daylight's share of the adaptation); the stars, the planets and the
     * star map keep the brightness full adaptation gives them against a
     * dark sky (a dark-adapted eye sees them so) */
    double range = s->cfg.exposure_range > 0.0f ? s->cfg.exposure_range : DEFAULT_RANGE_STOPS;
    double shown = sky_display_stops(daylight, range) * sqrt(daylight / adapt);
    /* HDR output is the sky's light as it is: its exposure (the layers'
     * visibility thresholds) stays full adaptation's, and the display's
     * is kept for a host's sky_display (sky_display_bind) */
    int ldr = s->cfg.output != SKY_OUTPUT_HDR;
    f->star_local_gain = ldr ? (float)(withheld * exp2(-shown)) : 1.0f;
    f->display_exposure = (float)(pow(2.0, s->exposure_bias + shown) / adapt);
    f->exposure = ldr ? f->display_exposure : (float)(pow(2.0, s->exposure_bias) / adapt);
    /* A fragment stage without highp holds only mediump's +-2^14 (GLSL ES
     * 1.00), and the sky's light spans far more (the sun's disc near 2e6
     * kcd/m^2, a moonless sky near 1e-7): in LDR it reaches the shaders
     * already times the exposure, where a display value of 1 is white
     * (sky_program_apply). HDR output is kcd/m^2 itself: there the range
     * is the host's choice of context. */
    int prescale = !s->caps.fragment_highp && s->cfg.output != SKY_OUTPUT_HDR;
    f->light_scale = prescale ? f->exposure : 1.0f;
    f->shader_exposure = prescale ? 1.0f : f->exposure;
    /* The sun's irradiance times that exposure is far past 2^14 in a
     * twilight, where the air's light per unit of it is far below 2^-14: a
     * power of two is taken out of it, and put back where the two meet (in
     * the highp vertex stage, rayleigh.glsl; in the exponent of a
     * decoding, hillaire.glsl). */
    double sun = fmax(f->sun_irradiance[0], fmax(f->sun_irradiance[1], f->sun_irradiance[2])) * f->light_scale;
    int gain = prescale && sun > 1.0 ? (int)ceil(log2(sun)) : 0;
    f->sun_gain_log2 = (float)gain;
    for (int i = 0; i < 3; i++) f->sun_irradiance_sent[i] = (float)ldexp(f->sun_irradiance[i] * f->light_scale, -gain);
    /* Night vision (display.glsl's sky_scotopic_shift, after Jensen et
     * al. 2000): the rods' share 1 - s at the luminance the eye adapts
     * to, the sky's own (daylight and the night's light, cd/m^2): none
     * above 4 cd/m^2 (the sun 5 degrees down on the gradient path), all
     * below 0.01 (a moonlit or moonless night). */
    double eye_cd = 1000.0 * (daylight + f->night_luminance);
    f->night_shift = (float)(1.0 - sky_smoothstep(-2.0, 0.6, log10(fmax(eye_cd, 1e-12))));
    f->display_cd = (float)(1000.0 / fmax(f->display_exposure, 1e-30));

}
