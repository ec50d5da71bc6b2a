/*
 * Airglow (SKY_AIRGLOW): the light the upper atmosphere gives off at night
 * (the oxygen green line at 97 km, sodium at 92 km, OH and a continuum),
 * most of a moonless sky's brightness at a dark site. A thin emitting
 * shell at AIRGLOW_HEIGHT_KM: a line of sight crosses it more obliquely
 * toward the horizon, which brightens it by the van Rhijn factor
 * 1 / sqrt(1 - (R / (R + h))^2 sin^2 z) (about 6 at the horizon), and the
 * air below dims it (atmosphere.glsl's sky_night_extinction). Dome role
 * NIGHT: it is part of the night variant of the dome's program
 * (airglow.glsl), drawn when it shows at the exposure.
 *
 * Level: Benn & Ellison (1998, La Palma Technical Note 115) measured a
 * dark zenith of V = 21.9 mag/arcsec^2 at solar minimum, 0.4 brighter at
 * maximum. Less the zodiacal light at high ecliptic latitude (about 60 S10,
 * Leinert et al. 1998) and the integrated light of the stars a render
 * does not draw (atmosphere.c's floor, 25 S10), that leaves the airglow
 * 22.54 mag/arcsec^2 at the zenith at minimum; it follows the 11-year
 * cycle up to 1.6 times that at maximum. That is the zenith as seen
 * through a dark site's air (V extinction 0.15 mag per air mass, as at La
 * Palma): above the air it is 10^(0.4 * 0.15) times brighter, and the
 * frame's own air dims it again. Its colour is the dark sky's measured
 * B - V of 0.8 (Benn & Ellison), through the stars' B - V map.
 */
#include "layer.h"

#include <math.h>

#define AIRGLOW_ZENITH_MAG 22.54    /* V mag/arcsec^2 at the zenith, solar minimum */
#define SITE_EXTINCTION_MAG 0.15    /* the air under which that was measured */
#define AIRGLOW_CYCLE_GAIN 0.6      /* at maximum: 1.6 times */
#define AIRGLOW_HEIGHT_KM 90.0
#define AIRGLOW_BV 0.8
#define SOLAR_CYCLE_YEARS 11.0
#define SOLAR_MINIMUM_YEAR 2019.9   /* the start of cycle 25 (and 2008.9 of 24) */
#define EARTH_MEAN_RADIUS_KM 6371.0

typedef struct airglow_state {
    float light[4]; /* rgb: zenith kcd/m^2 above the air; a: (R / (R + h))^2 */
} airglow_state;

static const sky_uniform_desc airglow_uniforms[] = {
    SKY_USL("u_airglow", SKY_U_F4, airglow_state, light, SKY_RGB),
};
static const sky_snippet airglow_snippet = {"SKY_HAS_AIRGLOW", "airglow.glsl", airglow_uniforms,
                                            SKY_UNIFORM_COUNT(airglow_uniforms), NULL, "sky_airglow", NULL};

/* 0 at solar minimum .. 1 at maximum: cfg's, or the date's place in a
 * cycle of 11 years from the minimum of 2019.9. */
static double solar_activity(const sky_core *s)
{
    if (s->cfg.solar_activity_manual) return sky_clampd(s->cfg.solar_activity, 0.0, 1.0);
    double year = 2000.0 + s->astro.years_since_j2000;
    double phase = (year - SOLAR_MINIMUM_YEAR) / SOLAR_CYCLE_YEARS;
    return 0.5 - 0.5 * cos(2.0 * SKY_PI * (phase - floor(phase)));
}

/* Its zenith from the date and cfg alone: for the atmosphere's summary,
 * before this layer's frame. */
static void airglow_zenith(const sky_core *s, const void *state, double rgb[3])
{
    (void)state;
    double level = sky_mag_arcsec2_to_kcd(AIRGLOW_ZENITH_MAG - SITE_EXTINCTION_MAG) *
                   (1.0 + AIRGLOW_CYCLE_GAIN * solar_activity(s));
    float colour[3];
    sky_star_color(AIRGLOW_BV, colour);
    for (int i = 0; i < 3; i++) rgb[i] = level * colour[i];
}

/* (R / (R + h))^2 for the observer's height */
static double shell_ratio2(const sky_core *s)
{
    double r = EARTH_MEAN_RADIUS_KM + sky_clampd(s->observer.altitude_m / 1000.0, -0.5, AIRGLOW_HEIGHT_KM - 1.0);
    double c = r / (EARTH_MEAN_RADIUS_KM + AIRGLOW_HEIGHT_KM);
    return c * c;
}

/* From direction d, as airglow.glsl has it (after this layer's frame). */
static void airglow_at(const sky_core *s, const void *state, const double d[3], double rgb[3])
{
    (void)s;
    const airglow_state *st = state;
    double y = sky_clampd(d[1], 0.0, 1.0);
    double van_rhijn = d[1] > 0.0 ? 1.0 / sqrt(fmax(1.0 - st->light[3] * (1.0 - y * y), 1e-6)) : 0.0;
    for (int i = 0; i < 3; i++) rgb[i] = st->light[i] * van_rhijn;
}

static int airglow_create(sky_core *s, void *state, char *err, size_t err_len)
{
    if (sky_snippet_bind(s, &airglow_snippet, state) == 0) return 0;
    sky_format(err, err_len, "out of memory");
    return -1;
}

static void airglow_frame(sky_core *s, void *state)
{
    airglow_state *st = state;
    double z[3];
    airglow_zenith(s, state, z);
    for (int i = 0; i < 3; i++) st->light[i] = (float)z[i];
    st->light[3] = (float)shell_ratio2(s);
}

/* In the dome's night variant while it would add a quarter of an 8-bit
 * step at the exposure (at its zenith, its faintest) */
static int airglow_visible(const sky_core *s, const void *state)
{
    const airglow_state *st = state;
    double y = 0.2126 * st->light[0] + 0.7152 * st->light[1] + 0.0722 * st->light[2];
    return y * s->frame.exposure >= 1.0 / 1024.0;
}

const sky_layer_class sky_airglow_layer = {
    .name = "airglow",
    .slot = SKY_LAYER_AIRGLOW,
    .feature = SKY_AIRGLOW,
    .state_size = sizeof(airglow_state),
    .dome_role = SKY_DOME_NIGHT,
    .dome_snippet = &airglow_snippet,
    .create = airglow_create,
    .frame = airglow_frame,
    .visible = airglow_visible,
    .glow_zenith = airglow_zenith,
    .glow_at = airglow_at,
};
