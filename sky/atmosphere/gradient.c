/*
 * The gradient atmosphere: Roden & Parberry's day sky (a blue gradient by
 * elevation) scaled to physical luminance by the sun's altitude. The
 * cheapest path and the only one needing no lookup table.
 */
#include "../sky_internal.h"

#include <math.h>

static const sky_uniform_desc gradient_uniforms[] = {
    SKY_UT("u_gradient_tex", SKY_TEX_GRADIENT),
    SKY_UF("u_sky_luminance", SKY_U_F1, sky_luminance),
    SKY_UF("u_night_luminance", SKY_U_F1, night_luminance),
    SKY_UF("u_sun_transmittance", SKY_U_F3, sun_transmittance),
};
const sky_snippet sky_gradient_snippet = {"SKY_HAS_GRADIENT", "gradient.glsl", gradient_uniforms,
                                          (int)(sizeof gradient_uniforms / sizeof gradient_uniforms[0])};

int sky_gradient_create(sky *s, char *err, size_t err_len)
{
    return sky_texture_load(s, SKY_TEX_GRADIENT, SKY_LAYER_ATMOSPHERE, "gradient.png", 256, 1, 0, err, err_len);
}

/* Luminance scale of the day sky (kcd/m^2) for a sun at altitude h. Above
 * the horizon it grows like sin(h)^0.6 to about 9 kcd/m^2; below it falls by
 * a decade every 3 degrees, which matches the measured twilight sky: about
 * 3 cd/m^2 at -6 (civil), 0.03 at -12 (nautical) and 3e-4 cd/m^2 at -18
 * degrees. Continuous at h = 0. */
static double day_sky_luminance(double altitude)
{
    double h_deg = altitude * 180.0 / SKY_PI;
    if (h_deg >= 0.0) return 0.3 + 9.0 * pow(sin(altitude), 0.6);
    return 0.3 * pow(10.0, sky_clampd(h_deg, -90.0, 0.0) / 3.0);
}

void sky_gradient_frame(sky *s)
{
    sky_frame *f = &s->frame;
    f->sky_luminance = (float)day_sky_luminance(f->sun_altitude);
    /* A dark, moonless sky: about 0.2 mcd/m^2 (21.6 mag/arcsec^2). */
    f->night_luminance = 2.0e-7f;
}
