/*
 * The sun: the camera-facing quad that draws its limb-darkened disc (Roden & Parberry
 * sec. 2; Schneegans et al. eq. 1). Where it is comes from astro.c.
 */
#include "layer.h"
#include "disc.h"
#include "solar_eclipse.h"

#include <math.h>

/* The sun's photometry, one scale for the drawn disc and the host's
 * sunlight (sky_get_lighting): the solar illuminance above the atmosphere
 * at 1 au, 128 klx (the IES's solar illuminance constant, 127.5 klx,
 * rounded; IES Lighting Handbook), spread over the disc's solid angle at
 * 1 au (radius 696000 km, astro.c). Mean disc luminance 1.88e9 cd/m^2
 * (1.6e9, the old figure, is a sea-level one: extinction is applied on
 * top). */
#define SKY_SUN_E0_KLX 128.0
#define SKY_SUN_RADIUS_KM 696000.0
#define SKY_AU_KM 149597870.7
/* The mean of the u = 0.6 limb-darkening profile (sun.frag) over the disc:
 * 1 - u / 3. */
#define SKY_SUN_LIMB_MEAN 0.8
/* The quad reaches 16 radii: the glare is windowed to zero there. */
#define SKY_SUN_QUAD_RADII 16.0

/* The solid angle of a cap of angular radius sd, 2 pi (1 - cos sd), in the
 * form that keeps its digits for the sun's small radius. */
static double cap_solid_angle(double sd)
{
    double h = sin(0.5 * sd);
    return 4.0 * SKY_PI * h * h;
}

/* Disc-centre luminance above the atmosphere, kcd/m^2: the mean over the
 * disc at 1 au (E0 over its solid angle) divided by the limb darkening's
 * mean. Luminance does not change with distance. */
static double sun_centre_luminance(void)
{
    return SKY_SUN_E0_KLX / (cap_solid_angle(atan(SKY_SUN_RADIUS_KM / SKY_AU_KM)) * SKY_SUN_LIMB_MEAN);
}

double sky_sun_illuminance_klx(const sky_core *s)
{
    /* what the disc drawn at the topocentric semidiameter sums to: 128 klx
     * times (1 au / r)^2, +-3.4 % over the year */
    return sun_centre_luminance() * SKY_SUN_LIMB_MEAN * cap_solid_angle(s->astro.sun_topo_semidiameter);
}

typedef struct sun_state {
    sky_program program;
    sky_disc_grid grid;  /* the sun's quad, tessellated                       */
    float radius;        /* angular radius of the drawn disc, radians         */
    float disc[3];       /* the disc's centre as drawn: its luminance x the
                            transmittance, kcd/m^2 (under mediump kept within
                            its 2^14, where the disc is white anyway)         */
    float glare[3];      /* the glare's peak, 5e-6 of the unclamped centre x
                            the transmittance                                 */
    float true_dir[3];   /* the sun's centre without refraction               */
} sun_state;

static const sky_uniform_desc sun_uniforms[] = {
    SKY_US("u_sun_radius", SKY_U_F1, sun_state, radius),
    SKY_USL("u_sun_disc", SKY_U_F3, sun_state, disc, SKY_RGB),
    SKY_USL("u_sun_glare", SKY_U_F3, sun_state, glare, SKY_RGB),
    SKY_UF("u_sun_transmittance", SKY_U_F3, sun_transmittance),
    SKY_US("u_sun_true_dir", SKY_U_F3, sun_state, true_dir),
};
/* Uniform rows only: sun.frag is the program's main, not a snippet. */
static const sky_snippet sun_snippet = {NULL, NULL, sun_uniforms, SKY_UNIFORM_COUNT(sun_uniforms), NULL, NULL, NULL};

static int sun_create(sky_core *s, void *state, char *err, size_t err_len)
{
    sun_state *st = state;
    if (sky_disc_grid_create(s, &st->grid, "sun", err, err_len)) return -1;
    if (sky_snippet_bind(s, &sun_snippet, state)) {
        sky_format(err, err_len, "out of memory");
        return -1;
    }
    const sky_snippet *own[2] = {&sun_snippet, &sky_solar_eclipse_sun_snippet};
    return sky_program_build_over_dome(s, s->dome_snippets, &st->program, "sun.vert", "sun.frag", own, 2, err,
                                       err_len);
}

static void sun_destroy(sky_core *s, void *state)
{
    sun_state *st = state;
    sky_program_destroy(s, &st->program);
    sky_disc_grid_destroy(s, &st->grid);
}

static void sun_frame(sky_core *s, void *state)
{
    sun_state *st = state;
    const sky_frame *f = &s->frame;
    const sky_astro *a = &s->astro;
    st->radius = (float)a->sun_topo_semidiameter;
    double centre = sun_centre_luminance();
    /* The light reaches the shader as drawn: luminance 1.6e6 kcd/m^2 is
     * past the 2^14 of a mediump fragment stage (GLSL ES 1.00 without
     * highp), and the glare's 5e-6 of it must not be taken from a clamped
     * value. */
    double most = s->caps.fragment_highp ? 3e38 : 16384.0;
    for (int i = 0; i < 3; i++) {
        double t = f->sun_transmittance[i];
        st->disc[i] = (float)fmin(centre * t, most);
        st->glare[i] = (float)(5e-6 * centre * t);
    }
    /* the disc is drawn where refraction puts each of its points
     * (sun.frag): it needs the centre's true direction */
    for (int i = 0; i < 3; i++) st->true_dir[i] = (float)a->sun.dir_geometric[i];
    sky_solar_eclipse_sun(s, centre); /* the moon in front */
}

static int sun_visible(const sky_core *s, const void *state)
{
    const sun_state *st = state;
    /* The whole quad, glare included, below the horizon: nothing to draw. */
    return st->grid.vertices && s->frame.sun_altitude > -(float)SKY_SUN_QUAD_RADII * st->radius;
}

static int sun_draw(sky_core *s, void *state)
{
    sun_state *st = state;
    const sky_astro *a = &s->astro;
    double d[3] = {a->sun.dir[0], a->sun.dir[1], a->sun.dir[2]};
    /* Tangent basis around the sun: any vector not parallel to d. */
    double up[3] = {0.0, 1.0, 0.0};
    if (fabs(d[1]) > 0.9) up[0] = 1.0, up[1] = 0.0;
    double t[3] = {up[1] * d[2] - up[2] * d[1], up[2] * d[0] - up[0] * d[2], up[0] * d[1] - up[1] * d[0]};
    double tl = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int i = 0; i < 3; i++) t[i] /= tl;
    double b[3] = {d[1] * t[2] - d[2] * t[1], d[2] * t[0] - d[0] * t[2], d[0] * t[1] - d[1] * t[0]};
    double half = SKY_SUN_QUAD_RADII * st->radius;
    sky_disc_grid_update(s, &st->grid, d, t, b, tan(half), 1.0);
    sky_program_apply(s, &st->program);
    sky_disc_grid_draw(s, &st->grid, a->sun.alt, half);
    return 1;
}

static size_t sun_buffer_bytes(const sky_core *s, const void *state)
{
    (void)s;
    return sky_disc_grid_bytes(&((const sun_state *)state)->grid);
}

/* The sun quad, added over the dome (it hides behind the clouds by
 * evaluating them itself). */
const sky_layer_class sky_sun_layer = {
    .name = "sun",
    .slot = SKY_LAYER_SUN,
    .feature = SKY_SUN,
    .state_size = sizeof(sun_state),
    .blend = SKY_BLEND_ADD,
    .create = sun_create,
    .destroy = sun_destroy,
    .frame = sun_frame,
    .visible = sun_visible,
    .draw = sun_draw,
    .buffer_bytes = sun_buffer_bytes,
};
