/*
 * Mueller's star map (sec. 4.4): a low-resolution all-sky texture of the
 * stars fainter than the catalogue draws and of the Milky Way
 * (textures/starmap.png, built by tools/catgen.c), evaluated in the dome's
 * night variant behind the atmosphere. Shader: starmap.glsl.
 */
#include "layer.h"

#include <math.h>
#include <stdlib.h>

/* Luminance of the map's brightest texel (the Sagittarius star clouds) at
 * m_a = 4 and a 60-degree, 720-pixel view: about six times the dark sky's
 * 0.2 mcd/m^2, so the band is hinted, as Mueller asks, and no more. */
#define STARMAP_PEAK 1.2e-6
#define STARMAP_REF_PIXEL_ANGLE (2.0 * 0.57735026919 / 720.0)

typedef struct starmap_state {
    float rot[16]; /* J2000 -> horizon                                      */
    float scale;   /* kcd/m^2 of a full texel in this view; 0: off          */
} starmap_state;

static const sky_uniform_desc starmap_uniforms[] = {
    SKY_UT("u_starmap_tex", SKY_TEX_STARMAP),
    SKY_US("u_starmap_rot", SKY_U_M4, starmap_state, rot),
    SKY_USL("u_starmap_scale", SKY_U_F1, starmap_state, scale, 1u),
};
static const sky_snippet starmap_snippet = {"SKY_HAS_STARMAP", "starmap.glsl", starmap_uniforms,
                                         SKY_UNIFORM_COUNT(starmap_uniforms), NULL, NULL, NULL};

/* The map ships as an equirectangular image (u = right ascension / 2 pi,
 * v = 0.5 - declination / pi); the GPU gets it as a cube map, so a pixel
 * finds its texel with one lookup by direction instead of an atan, an
 * asin and a wrap. 128 texels across a face is the image's own 0.7
 * degree at the faces' centres. */
#define STARMAP_W 512
#define STARMAP_H 256
#define STARMAP_FACE 128

/* The image at J2000 direction e, bilinear, wrapping in right ascension. */
static void sample_equirect(const unsigned char *img, const double e[3], unsigned char out[4])
{
    double ra = atan2(e[1], e[0]), dec = asin(sky_clampd(e[2], -1.0, 1.0));
    double u = ra / (2.0 * SKY_PI), v = 0.5 - dec / SKY_PI;
    u -= floor(u);
    double x = u * STARMAP_W - 0.5, y = sky_clampd(v * STARMAP_H - 0.5, 0.0, STARMAP_H - 1.0);
    int x0 = (int)floor(x), y0 = (int)y, y1 = y0 + 1 < STARMAP_H ? y0 + 1 : y0;
    double fx = x - x0, fy = y - y0;
    int xa = (x0 % STARMAP_W + STARMAP_W) % STARMAP_W, xb = (xa + 1) % STARMAP_W;
    for (int c = 0; c < 4; c++) {
        double top = img[4 * (y0 * STARMAP_W + xa) + c] * (1 - fx) + img[4 * (y0 * STARMAP_W + xb) + c] * fx;
        double bottom = img[4 * (y1 * STARMAP_W + xa) + c] * (1 - fx) + img[4 * (y1 * STARMAP_W + xb) + c] * fx;
        out[c] = (unsigned char)lround(top * (1 - fy) + bottom * fy);
    }
}

static int starmap_create(sky_core *s, void *state, char *err, size_t err_len)
{
    (void)state;
    unsigned char *img = NULL;
    if (sky_asset_load_rgba(s, "starmap.png", STARMAP_W, STARMAP_H, &img, err, err_len)) return -1;
    unsigned char *faces = malloc(6u * STARMAP_FACE * STARMAP_FACE * 4u);
    if (!faces) {
        sky_png_free(img);
        sky_format(err, err_len, "out of memory for the star map");
        return -1;
    }
    /* each face's texel (i, j) at GL's (s, t) in -1..1 looks along these
     * directions (the cube-map face selection of the GL specification) */
    for (int f = 0; f < 6; f++)
        for (int j = 0; j < STARMAP_FACE; j++)
            for (int i = 0; i < STARMAP_FACE; i++) {
                double sc = 2.0 * (i + 0.5) / STARMAP_FACE - 1.0, tc = 2.0 * (j + 0.5) / STARMAP_FACE - 1.0;
                const double dirs[6][3] = {{1, -tc, -sc}, {-1, -tc, sc}, {sc, 1, tc},
                                           {sc, -1, -tc}, {sc, -tc, 1}, {-sc, -tc, -1}};
                double n = sqrt(dirs[f][0] * dirs[f][0] + dirs[f][1] * dirs[f][1] + dirs[f][2] * dirs[f][2]);
                double e[3] = {dirs[f][0] / n, dirs[f][1] / n, dirs[f][2] / n};
                sample_equirect(img, e, faces + 4u * (((size_t)f * STARMAP_FACE + (size_t)j) * STARMAP_FACE + (size_t)i));
            }
    sky_png_free(img);
    int rc = sky_texture_create_cube(s, SKY_TEX_STARMAP, SKY_LAYER_STARMAP, faces, STARMAP_FACE, 0, err, err_len);
    free(faces);
    return rc;
}

/* The map is in J2000: the shader takes horizon directions back through
 * the inverse of the sky's rotation. */
static void starmap_frame(sky_core *s, void *state)
{
    starmap_state *st = state;
    sky_j2000_to_horizon_mat4(&s->astro, 1, st->rot);
}

/* After the camera: the brightness depends on the pixel size. */
static void starmap_view(sky_core *s, void *state)
{
    starmap_state *st = state;
    const sky_frame *f = &s->frame;
    float m_a = s->cfg.star_control_magnitude > 0.0f ? sky_clampf(s->cfg.star_control_magnitude, 1.0f, 10.0f) : 4.0f;
    double fov = f->pixel_angle > 0.0f ? sqrt(STARMAP_REF_PIXEL_ANGLE / f->pixel_angle) : 1.0;
    /* it fades with the naked eye's limit, from the limit a dark site's
     * catalogue reaches (6.5) to that of Bortle's classes 7-8 (4.75),
     * where the Milky Way is gone: it is the faint stars and the glow of
     * the Milky Way, which a brighter sky drowns first */
    double seen = sky_smoothstep(4.75, 6.5, f->naked_eye_limit);
    double scale = STARMAP_PEAK * pow(2.512, m_a - 4.0) * fov * seen * f->star_local_gain;
    /* nothing a quarter of an 8-bit step could show at the automatic
     * exposure: off (for HDR output too, as for the stars) */
    st->scale = scale * f->exposure < 1.0 / 1024.0 ? 0.0f : (float)scale;
}

static int starmap_visible(const sky_core *s, const void *state)
{
    (void)s;
    return ((const starmap_state *)state)->scale > 0.0f;
}

const sky_layer_class sky_starmap_layer = {
    .name = "starmap",
    .slot = SKY_LAYER_STARMAP,
    .feature = SKY_STARMAP,
    .state_size = sizeof(starmap_state),
    .dome_role = SKY_DOME_NIGHT,
    .dome_snippet = &starmap_snippet,
    .create = starmap_create,
    .frame = starmap_frame,
    .view = starmap_view,
    .visible = starmap_visible,
};
