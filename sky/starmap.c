/*
 * Mueller's star map (sec. 4.4): a low-resolution all-sky texture of the
 * stars fainter than the catalogue draws and of the Milky Way
 * (textures/starmap.png, built by tools/catgen.c), evaluated in the dome's
 * night variant behind the atmosphere. Shader: starmap.glsl.
 */
#include "layer.h"

#include <math.h>

/* Luminance of the map's brightest texel (the Sagittarius star clouds) at
 * m_a = 4 and a 60-degree, 720-pixel view: about six times the dark sky's
 * 0.2 mcd/m^2, so the band is hinted, as Mueller asks, and no more. */
#define STARMAP_PEAK 1.2e-6
#define STARMAP_REF_PIXEL_ANGLE (2.0 * 0.57735026919 / 720.0)

static const sky_uniform_desc starmap_uniforms[] = {
    SKY_UT("u_starmap_tex", SKY_TEX_STARMAP),
    SKY_UF("u_starmap_rot", SKY_U_M4, starmap_rot),
    SKY_UF("u_starmap_scale", SKY_U_F1, starmap_scale),
};
static const sky_snippet starmap_snippet = {"SKY_HAS_STARMAP", "starmap.glsl", starmap_uniforms,
                                         SKY_UNIFORM_COUNT(starmap_uniforms), NULL};

static int starmap_create(sky_core *s, void *state, char *err, size_t err_len)
{
    (void)state;
    return sky_texture_load(s, SKY_TEX_STARMAP, SKY_LAYER_STARMAP, "starmap.png", 512, 256, 1, err, err_len);
}

/* The map is in J2000: the shader takes horizon directions back through
 * the inverse of the sky's rotation. */
static void starmap_frame(sky_core *s, void *state)
{
    (void)state;
    sky_j2000_to_horizon_mat4(&s->astro, 1, s->frame.starmap_rot);
}

/* After the camera: the brightness depends on the pixel size. */
static void starmap_view(sky_core *s, void *state)
{
    (void)state;
    sky_frame *f = &s->frame;
    float m_a = s->cfg.star_control_magnitude > 0.0f ? sky_clampf(s->cfg.star_control_magnitude, 1.0f, 10.0f) : 4.0f;
    double fov = f->pixel_angle > 0.0f ? sqrt(STARMAP_REF_PIXEL_ANGLE / f->pixel_angle) : 1.0;
    double scale = STARMAP_PEAK * pow(2.512, m_a - 4.0) * fov * s->astro.star_visibility * f->star_local_gain;
    /* nothing a quarter of an 8-bit step could show at the automatic
     * exposure: off (for HDR output too, as for the stars) */
    f->starmap_scale = scale * f->exposure < 1.0 / 1024.0 ? 0.0f : (float)scale;
}

static int starmap_visible(const sky_core *s, const void *state)
{
    (void)state;
    return s->frame.starmap_scale > 0.0f;
}

const sky_layer_class sky_starmap_layer = {
    .slot = SKY_LAYER_STARMAP,
    .feature = SKY_STARMAP,
    .dome_role = SKY_DOME_NIGHT,
    .dome_snippet = &starmap_snippet,
    .create = starmap_create,
    .frame = starmap_frame,
    .view = starmap_view,
    .visible = starmap_visible,
};
