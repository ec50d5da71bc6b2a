/*
 * Roden & Parberry's night sky (sec. 4): the 256x256 flicker-star texture
 * tiled over the dome and the 128x128 galaxy texture stretched over it. The
 * shader is flicker.glsl; this file owns the textures and the flicker clock.
 */
#include "sky_internal.h"

/* Fastest flicker, at G = 255, in cycles per second. */
#define SKY_FLICKER_RATE_MAX 2.0
/* kcd/m^2 of a star texel of intensity 1 on a fully dark night: about ten
 * times the moonless sky, so stars read clearly after exposure. */
#define SKY_FLICKER_STAR_LUMINANCE 2.5e-5

static const sky_uniform_desc flicker_uniforms[] = {
    SKY_UT("u_flicker_tex", SKY_TEX_FLICKER),
    SKY_UT("u_galaxy_tex", SKY_TEX_GALAXY),
    SKY_UF("u_flicker_phase", SKY_U_F1, flicker_phase),
    SKY_UF("u_star_luminance", SKY_U_F1, star_luminance),
};
const sky_snippet sky_flicker_snippet = {"SKY_HAS_FLICKER", "flicker.glsl", flicker_uniforms,
                                         (int)(sizeof flicker_uniforms / sizeof flicker_uniforms[0])};

int sky_flicker_create(sky *s, char *err, size_t err_len)
{
    if (sky_texture_load(s, SKY_TEX_FLICKER, SKY_LAYER_FLICKER, "flicker.png", 256, 256, 1, err, err_len)) return -1;
    return sky_texture_load(s, SKY_TEX_GALAXY, SKY_LAYER_FLICKER, "galaxy.png", 128, 128, 0, err, err_len);
}

void sky_flicker_advance(sky *s, double dt)
{
    /* A star with rate byte k flickers at k/255 * RATE_MAX Hz. The clock
     * tau = RATE_MAX * t / 255 wrapped into [0, 1) advances every star by a
     * whole number of cycles at each wrap, so the wrap is invisible and the
     * float phase k * tau never grows. */
    s->flicker_phase = sky_wrap(s->flicker_phase + SKY_FLICKER_RATE_MAX * dt / 255.0, 1.0);
}

void sky_flicker_frame(sky *s)
{
    sky_frame *f = &s->frame;
    f->flicker_phase = (float)(255.0 * s->flicker_phase);
    f->star_luminance = (float)SKY_FLICKER_STAR_LUMINANCE * f->night;
}
