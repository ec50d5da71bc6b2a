/*
 * The planets Mercury to Saturn (SKY_PLANETS): points drawn exactly as the
 * catalogue stars are (stars.vert/.frag: Mueller eq. 9-12's size, PSF,
 * glare, extinction and scintillation), from their apparent places
 * (astro.c: VSOP87D, Meeus ch. 33) and their magnitudes (Mallama & Hilton
 * 2018), coloured by their measured B-V. A planet's disc averages the
 * twinkle away: the shader's scintillation is scaled by
 * 1 / (1 + (diameter / 5")^2), so Jupiter keeps 1.5 % of a star's and
 * Mercury at 7" a third.
 *
 * The VSOP87 series (967 terms) are evaluated into a state of position
 * and velocity per planet that serves SKY_PLANET_STATE_DAYS either side
 * of its instant; a frame refreshes at most one state that has grown
 * older than half of that, or every state beyond it (a jump in time).
 * The geocentric place from a state (light time, nutation, aberration,
 * magnitude) is kept for GEOCENTRIC_DAYS, in which Mercury, the fastest
 * across the sky, moves under 3"; every frame only turns it into the
 * observer's horizon.
 */
#include "layer.h"
#include "points.h"

#include <math.h>
#include <string.h>

#define PLANET_FLOATS SKY_POINT_FLOATS
#define DISC_TWINKLE_ARCSEC 5.0
#define GEOCENTRIC_DAYS 0.0005 /* 43 s */

typedef struct planets_state {
    sky_program program;
    GLuint buffer;
    float point_max;
    double scintillation;
    int have_states;
    sky_planet_state states[SKY_ASTRO_PLANETS];
    sky_astro_planet places[SKY_ASTRO_PLANETS];
    double places_jd_tt;      /* the instant of the places' geocentric part */
    float vertices[SKY_ASTRO_PLANETS * PLANET_FLOATS];
    int dirty; /* vertices changed since the last upload */
    sky_point_frame points;   /* stars.vert's uniforms for the planets     */
} planets_state;

static const sky_uniform_desc planet_uniforms[] = {SKY_POINT_UNIFORMS(planets_state, points)};
static const sky_snippet planets_snippet = {NULL, NULL, planet_uniforms, SKY_UNIFORM_COUNT(planet_uniforms),
                                            NULL, NULL, NULL};

static const size_t planet_bytes = sizeof(float) * SKY_ASTRO_PLANETS * PLANET_FLOATS;

/* The states the frame's instant needs: every one past its window, else
 * the oldest past half of it (so a clock that runs keeps the work to one
 * planet's series a frame). */
static void refresh_states(planets_state *st, double jd_tt)
{
    int oldest = -1;
    double oldest_age = 0.5 * SKY_PLANET_STATE_DAYS;
    for (int p = 0; p < SKY_ASTRO_PLANETS; p++) {
        double age = st->have_states ? fabs(jd_tt - st->states[p].jd_tt) : INFINITY;
        if (!(age <= SKY_PLANET_STATE_DAYS))
            sky_planet_state_at(p, jd_tt, &st->states[p]);
        else if (age > oldest_age) {
            oldest = p;
            oldest_age = age;
        }
    }
    if (oldest >= 0) sky_planet_state_at(oldest, jd_tt, &st->states[oldest]);
    st->have_states = 1;
}

static int planets_create(sky_core *s, void *state, char *err, size_t err_len)
{
    planets_state *st = state;
    st->point_max = sky_gl_point_size_max(s);
    st->buffer = sky_buffer_create(s, GL_ARRAY_BUFFER, NULL, planet_bytes, GL_DYNAMIC_DRAW);
    if (!st->buffer) {
        sky_format(err, err_len, "glGenBuffers failed for the planets");
        return -1;
    }
    st->dirty = 1;
    st->places_jd_tt = -INFINITY;
    for (int p = 0; p < SKY_ASTRO_PLANETS; p++) {
        float *v = st->vertices + p * PLANET_FLOATS;
        v[0] = (float)(100000 + p); /* a seed no catalogue star has */
        sky_star_color(sky_astro_planet_bv(p), v + 5);
    }
    if (sky_snippet_bind(s, &planets_snippet, state)) {
        sky_format(err, err_len, "out of memory");
        return -1;
    }
    const sky_snippet *own[1] = {&planets_snippet};
    return sky_program_build_over_dome(s, s->dome_snippets, &st->program, "stars.vert", "stars.frag", own, 1, err,
                                       err_len);
}

static void planets_destroy(sky_core *s, void *state)
{
    planets_state *st = state;
    sky_program_destroy(s, &st->program);
    sky_buffers_destroy(s, &st->buffer, &planet_bytes, 1);
}

static void planets_advance(sky_core *s, void *state, double dt)
{
    planets_state *st = state;
    (void)s;
    st->scintillation = sky_scintillation_advance(st->scintillation, dt);
}

static void planets_reset(void *state) { ((planets_state *)state)->scintillation = 0.0; }

static void planets_frame(sky_core *s, void *state)
{
    planets_state *st = state;
    double jd_tt = s->astro.jd_tt;
    int geocentric = !(fabs(jd_tt - st->places_jd_tt) <= GEOCENTRIC_DAYS);
    if (geocentric) {
        refresh_states(st, jd_tt);
        st->places_jd_tt = jd_tt;
    }
    for (int p = 0; p < SKY_ASTRO_PLANETS; p++) {
        sky_astro_planet *pl = &st->places[p];
        if (geocentric)
            sky_astro_planet_place(&s->astro, p, &st->states[p], pl);
        else
            sky_astro_topocentric(&s->astro, &pl->body);
        float *v = st->vertices + p * PLANET_FLOATS;
        double disc = pl->diameter / (DISC_TWINKLE_ARCSEC * SKY_PI / 648000.0);
        v[1] = (float)(1.0 - 1.0 / (1.0 + disc * disc));
        /* unrefracted: stars.vert refracts each point by its own altitude */
        for (int i = 0; i < 3; i++) v[2 + i] = (float)pl->body.dir_geometric[i];
        v[8] = (float)pl->vmag;
    }
    st->dirty = 1;
    /* the places are apparent in the horizon frame already */
    memset(st->points.rot, 0, sizeof st->points.rot);
    st->points.rot[0] = st->points.rot[5] = st->points.rot[10] = st->points.rot[15] = 1.0f;
    st->points.aberration[0] = st->points.aberration[1] = st->points.aberration[2] = 0.0f;
}

static void planets_view(sky_core *s, void *state)
{
    planets_state *st = state;
    if (st->dirty) {
        sky_buffer_update(s, GL_ARRAY_BUFFER, st->buffer, st->vertices, planet_bytes, GL_DYNAMIC_DRAW);
        st->dirty = 0;
    }
    sky_point_view(s, st->point_max, st->scintillation, &st->points);
}

/* Drawn when the brightest planet above the horizon is within the naked
 * eye's limit and would add at least a quarter of an 8-bit step at the
 * exposure (the stars' rule). */
static int planets_visible(const sky_core *s, const void *state)
{
    const planets_state *st = state;
    const sky_frame *f = &s->frame;
    double brightest = 99.0;
    for (int p = 0; p < SKY_ASTRO_PLANETS; p++)
        if (st->places[p].body.alt > -0.01) brightest = fmin(brightest, st->places[p].vmag);
    return st->points.flux_scale * pow(2.512, -brightest) * f->exposure >= 1.0 / 1024.0 &&
           brightest < st->points.pressure[1] + 0.25;
}

/* No draw when no planet can show in this view: a draw of five points
 * costs a browser's WebGL a fixed price whatever they cover
 * (docs/validation.md). */
static int planets_draw(sky_core *s, void *state)
{
    planets_state *st = state;
    int in_view = 0;
    for (int p = 0; !in_view && p < SKY_ASTRO_PLANETS; p++)
        in_view = sky_point_in_view(s, &st->points, st->places[p].body.dir_geometric, st->places[p].vmag);
    if (!in_view) return 0;
    sky_points_draw(s, &st->program, st->buffer, 0, SKY_ASTRO_PLANETS);
    return 1;
}

static size_t planets_buffer_bytes(const sky_core *s, const void *state)
{
    (void)s;
    return ((const planets_state *)state)->buffer ? planet_bytes : 0;
}

const sky_astro_planet *sky_planets_places(const void *state) { return ((const planets_state *)state)->places; }

/* Added over the dome like the stars: dimmed by the atmosphere, hidden by
 * the clouds and the moon. */
const sky_layer_class sky_planets_layer = {
    .name = "planets",
    .slot = SKY_LAYER_PLANETS,
    .feature = SKY_PLANETS,
    .state_size = sizeof(planets_state),
    .blend = SKY_BLEND_ADD,
    .create = planets_create,
    .destroy = planets_destroy,
    .advance = planets_advance,
    .reset_clock = planets_reset,
    .frame = planets_frame,
    .view = planets_view,
    .visible = planets_visible,
    .draw = planets_draw,
    .buffer_bytes = planets_buffer_bytes,
};
