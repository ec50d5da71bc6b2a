/*
 * The sky dome (Roden & Parberry sec. 2): a sphere of directions centred on
 * the viewer, its rings packed toward the horizon where the sky changes
 * fastest. Each vertex carries what varies slowly across the sky and never
 * with time: the day-gradient colour and the galaxy brightness. Evaluating
 * them per vertex instead of per pixel saves two texture fetches a pixel,
 * which on a software rasteriser is most of a full-screen pass each; it is
 * also what an OpenGL 2.0 GPU wants (no texture lookups in vertex shaders:
 * the values are computed here, on the CPU, once).
 */
#include "camera.h"
#include "layer.h"
#include "atmosphere/atmosphere.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Upper hemisphere: ring k has elevation sine (k / RINGS_UP)^2, the same
 * square-root spacing the gradient texture uses, so the horizon band gets
 * most rings. Below the horizon a few rings of haze down to the nadir. */
#define DOME_RINGS_UP 24
#define DOME_SEGMENTS 64
static const double dome_rings_down_deg[] = {-1.0, -3.0, -7.0, -15.0, -35.0, -65.0};
#define DOME_RINGS_DOWN ((int)(sizeof dome_rings_down_deg / sizeof dome_rings_down_deg[0]))
/* vertices: rings (up + down) x segments, plus zenith and nadir poles */
#define DOME_VERTICES ((DOME_RINGS_UP + DOME_RINGS_DOWN) * DOME_SEGMENTS + 2)
#define DOME_FLOATS 7 /* direction xyz, gradient rgb, galaxy */

/* The LDR dome's image: by default 1/4 of the viewport on each axis (1/16
 * of its pixels; sky_config.dome_divisor). The dome's light (the
 * atmosphere, the galaxy glow, the star map and Roden & Parberry's clouds)
 * changes slowly across the screen, and a fetch is most of what a pixel
 * costs on a software rasteriser: evaluated on a sixteenth of the pixels
 * and drawn over the viewport with one filtered fetch (and the dither),
 * the dome costs about what one textured full-screen quad does. What is
 * sharp is drawn at full resolution over it: the sun, the moon and the
 * stars, each hidden by the clouds' alpha read from the image at its
 * pixel. HDR output and contexts without framebuffer objects draw the
 * dome at every pixel.
 *
 * The day's clouds over the gradient sky (the per-vertex path) are drawn
 * at 1/3 (DOME_DAY_DIVISOR): their detail is what a sky shows at 1:1, and
 * the frame affords it, at about 1.8 times the quad against 1.55 at 1/4.
 * At 1/2 it would cost 2.2 to 2.8 (over the 2.5 the presets must stay
 * within, on a busy machine), at every pixel 3.7 to 4.1 (docs/SHARPNESS.md
 * has the measurements). The per-pixel atmospheres and the night (the star
 * map, the galaxy glow) at 1/3 would cost up to 2.7: theirs stay at 1/4. */
#define DOME_DIVISOR 4
#define DOME_DAY_DIVISOR 3

typedef struct dome_state {
    GLuint vertices, indices;    /* direction, gradient colour, galaxy      */
    size_t vertex_bytes, index_bytes;
    /* On a physical path with a moon the vertices' colour is its moonlit
     * sky per unit of the moon's light (atmosphere.c), rewritten when that
     * changes: the vertices kept, and the generation they hold. */
    float *vertex_data;
    unsigned moonlit_generation;
    int index_count, upper_first; /* indices: all, and where the upper hemisphere starts */
    /* The triangles in view (select_triangles): a browser's rasterizer
     * spends about as much on setting up and clipping the 3840 triangles
     * as on the image's pixels; a view of 60 degrees sees a quarter. */
    float *dirs;                 /* each vertex's direction                 */
    unsigned short *mesh;        /* every triangle, in the order above      */
    unsigned short *list;        /* those in view: the index buffer's       */
    unsigned char *outside;      /* per vertex: the side planes it is out of */
    int list_upper_first, list_count;
    /* The dome program holds only the snippets of enabled layers. With
     * night layers there are two variants, with and without them: a
     * uniform branch is not free on every GPU (llvmpipe pays for both
     * sides), and a day frame should do no star work at all. */
    sky_program day;             /* atmosphere + front (clouds)             */
    sky_program night;           /* the same with the night backdrop        */
    sky_program night_clear;     /* the night backdrop without the front    */
    sky_program ground;          /* below the horizon: atmosphere only      */
    /* The day's two without the tone map's scotopic blue shift, for while
     * it is off (the eye adapted above 4 cd/m^2: exposure.c): the same
     * pixels, and on llvmpipe the shift's mix costs about 0.4 of the
     * baseline quad in a frame drawn at every pixel. The night's keep it:
     * at night it is on. */
    sky_program day_photopic, ground_photopic;
    /* with the optics' light over the front layers (a rainbow, a halo),
     * for the frames where one shows */
    sky_program day_optics, day_optics_photopic, night_optics;
    /* with the occasional night glows (the aurora), for the frames where
     * one shows */
    sky_program night_occasional, night_clear_occasional;
    /* the image (dome_divisor > 0): its framebuffer, the quad that draws
     * it over the viewport, and the program that does */
    GLuint fbo, quad;
    sky_program composite, composite_fisheye;
    int used[2];                 /* this draw: the image's corner in use    */
} dome_state;

static void ring_vertex(float *v, double elevation_sine, int seg)
{
    double az = 2.0 * SKY_PI * seg / DOME_SEGMENTS;
    double c = sqrt(sky_clampd(1.0 - elevation_sine * elevation_sine, 0.0, 1.0));
    v[0] = (float)(c * sin(az));  /* east  */
    v[1] = (float)elevation_sine; /* up    */
    v[2] = (float)(-c * cos(az)); /* south: az 0 is north (-z) */
}

static int create_mesh(sky_core *s, dome_state *st, char *err, size_t err_len)
{
    unsigned char *gradient = NULL, *galaxy = NULL;
    if (sky_asset_load_rgba(s, "gradient.png", 256, 1, &gradient, err, err_len)) return -1;
    memcpy(s->gradient_texels, gradient, sizeof s->gradient_texels);
    if ((s->features & SKY_FLICKER_STARS) && sky_asset_load_rgba(s, "galaxy.png", 128, 128, &galaxy, err, err_len)) {
        sky_png_free(gradient);
        return -1;
    }
    float *v = malloc(sizeof(float) * DOME_FLOATS * DOME_VERTICES);
    /* triangles: 2 per quad between rings, plus the two pole fans */
    enum { RINGS = DOME_RINGS_UP + DOME_RINGS_DOWN };
    size_t index_count = (size_t)((RINGS - 1) * DOME_SEGMENTS * 6 + 2 * DOME_SEGMENTS * 3);
    unsigned short *idx = malloc(sizeof(unsigned short) * index_count);
    if (!v || !idx) {
        free(v);
        free(idx);
        sky_png_free(gradient);
        sky_png_free(galaxy);
        sky_format(err, err_len, "out of memory for the dome mesh");
        return -1;
    }
    /* rings from the nadir side up: down rings reversed, then up rings */
    int n = 0;
    for (int r = 0; r < RINGS; r++) {
        double e = r < DOME_RINGS_DOWN ? sin(dome_rings_down_deg[DOME_RINGS_DOWN - 1 - r] * SKY_PI / 180.0)
                                       : pow((double)(r - DOME_RINGS_DOWN) / DOME_RINGS_UP, 2.0);
        for (int sgm = 0; sgm < DOME_SEGMENTS; sgm++, n++) ring_vertex(v + n * DOME_FLOATS, e, sgm);
    }
    int nadir = n++, zenith = n++;
    float *pn = v + nadir * DOME_FLOATS, *pz = v + zenith * DOME_FLOATS;
    pn[0] = pn[2] = pz[0] = pz[2] = 0.0f;
    pn[1] = -1.0f;
    pz[1] = 1.0f;
    int physical = sky_atmosphere_is_physical(s->atmosphere);
    for (int i = 0; i < n; i++) {
        float *p = v + i * DOME_FLOATS;
        if (physical)
            p[3] = p[4] = p[5] = 0.0f; /* (the moonlit sky, from the first night on) */
        else
            sky_gradient_vertex(gradient, p, p + 3);
        p[6] = galaxy ? sky_flicker_galaxy_vertex(galaxy, p) : 0.0f;
    }
    /* order: nadir fan, ring quads from the bottom up, zenith fan, so the
     * upper hemisphere is one contiguous range (all a fisheye draws) */
    size_t k = 0;
    for (int sgm = 0; sgm < DOME_SEGMENTS; sgm++) {
        idx[k++] = (unsigned short)nadir;
        idx[k++] = (unsigned short)((sgm + 1) % DOME_SEGMENTS);
        idx[k++] = (unsigned short)sgm;
    }
    for (int r = 0; r + 1 < RINGS; r++) {
        if (r == DOME_RINGS_DOWN) st->upper_first = (int)k;
        for (int sgm = 0; sgm < DOME_SEGMENTS; sgm++) {
            unsigned short a = (unsigned short)(r * DOME_SEGMENTS + sgm);
            unsigned short b = (unsigned short)(r * DOME_SEGMENTS + (sgm + 1) % DOME_SEGMENTS);
            unsigned short c = (unsigned short)(a + DOME_SEGMENTS), d = (unsigned short)(b + DOME_SEGMENTS);
            idx[k++] = a, idx[k++] = b, idx[k++] = c;
            idx[k++] = b, idx[k++] = d, idx[k++] = c;
        }
    }
    for (int sgm = 0; sgm < DOME_SEGMENTS; sgm++) {
        int top = (RINGS - 1) * DOME_SEGMENTS;
        idx[k++] = (unsigned short)(top + sgm);
        idx[k++] = (unsigned short)(top + (sgm + 1) % DOME_SEGMENTS);
        idx[k++] = (unsigned short)zenith;
    }
    st->vertex_bytes = sizeof(float) * DOME_FLOATS * (size_t)n;
    st->index_bytes = sizeof(unsigned short) * k;
    int moonlit = physical && (s->features & SKY_MOON);
    st->vertices =
        sky_buffer_create(s, GL_ARRAY_BUFFER, v, st->vertex_bytes, moonlit ? GL_DYNAMIC_DRAW : GL_STATIC_DRAW);
    st->indices = sky_buffer_create(s, GL_ELEMENT_ARRAY_BUFFER, idx, st->index_bytes, GL_DYNAMIC_DRAW);
    st->index_count = (int)k;
    st->dirs = malloc(sizeof(float) * 3 * (size_t)n);
    st->list = malloc(st->index_bytes);
    st->outside = malloc((size_t)n);
    if (st->dirs && st->list && st->outside)
        for (int i = 0; i < n; i++) memcpy(st->dirs + 3 * i, v + i * DOME_FLOATS, sizeof(float) * 3);
    st->mesh = idx;
    if (moonlit)
        st->vertex_data = v;
    else
        free(v);
    sky_png_free(gradient);
    sky_png_free(galaxy);
    if (!st->dirs || !st->list || !st->outside) {
        sky_format(err, err_len, "out of memory for the dome mesh");
        return -1;
    }
    if (!st->vertices || !st->indices) {
        sky_format(err, err_len, "glGenBuffers failed for the dome mesh");
        return -1;
    }
    return 0;
}

/* The index buffer for this view: the triangles with a vertex inside each
 * side plane of the frustum (a triangle of directions drawn at infinity
 * covers the cone of its three, so one whose vertices are all outside the
 * same plane through the eye shows nowhere), the lower hemisphere's first.
 * The all-sky image takes them all. */
static void select_triangles(sky_core *s, dome_state *st)
{
    sky_view_bounds b = sky_camera_bounds(&s->frame);
    for (int i = 0; i < DOME_VERTICES; i++) {
        const double d[3] = {st->dirs[3 * i], st->dirs[3 * i + 1], st->dirs[3 * i + 2]};
        unsigned char out = 0;
        for (int p = 0; p < b.sides; p++)
            if (b.planes[p][0] * d[0] + b.planes[p][1] * d[1] + b.planes[p][2] * d[2] < 0.0) out |= (unsigned char)(1u << p);
        st->outside[i] = out;
    }
    int n = 0;
    for (int t = 0; t < st->index_count; t += 3) {
        if (t == st->upper_first) st->list_upper_first = n;
        const unsigned short *tri = st->mesh + t;
        if (st->outside[tri[0]] & st->outside[tri[1]] & st->outside[tri[2]]) continue;
        st->list[n++] = tri[0], st->list[n++] = tri[1], st->list[n++] = tri[2];
    }
    st->list_count = n;
    sky_buffer_update(s, GL_ELEMENT_ARRAY_BUFFER, st->indices, st->list, sizeof *st->list * (size_t)(n > 0 ? n : 3),
                      GL_DYNAMIC_DRAW);
}

/* Binds the dome's buffers and draws its upper (1) or lower (0) hemisphere. */
static void draw_hemisphere(sky_core *s, const dome_state *st, int upper)
{
    static const sky_gl_layout layout = {DOME_FLOATS * sizeof(float),
                                         {{0, 0, 0, 0},
                                          {3, GL_FLOAT, GL_FALSE, 0},
                                          {4, GL_FLOAT, GL_FALSE, 3 * sizeof(float)}}};
    sky_gl_vertices_bind(s, st->vertices, st->indices, &layout);
    int first = upper ? st->list_upper_first : 0;
    int count = upper ? st->list_count - st->list_upper_first : st->list_upper_first;
    if (count <= 0) return;
    sky_gl_draw_elements(s, GL_TRIANGLES, first, count);
}

/* Drawn into the image, the dome writes the clouds' alpha beside the
 * colour. */
static const sky_snippet into_image_snippet = {"SKY_DOME_INTO_IMAGE", NULL, NULL, 0, NULL, NULL, NULL};
/* display.glsl's tone map without the scotopic shift */
static const sky_snippet photopic_snippet = {"SKY_PHOTOPIC", NULL, NULL, 0, NULL, NULL, NULL};

static int build(sky_core *s, sky_program *p, const sky_snippet *const *snippets, int n, int photopic, char *err,
                 size_t err_len)
{
    const sky_snippet **list = malloc(sizeof *list * (size_t)(n + 2));
    if (!list) {
        sky_format(err, err_len, "out of memory");
        return -1;
    }
    for (int i = 0; i < n; i++) list[i] = snippets[i];
    if (s->dome_divisor) list[n++] = &into_image_snippet;
    if (photopic) list[n++] = &photopic_snippet;
    int rc = sky_program_build(s, p, "dome.vert", "dome.frag", list, n, err, err_len);
    free(list);
    return rc;
}

/* A day program with the shift and without it. */
static int build_day(sky_core *s, sky_program *shifted, sky_program *photopic, const sky_snippet *const *snippets,
                     int n, char *err, size_t err_len)
{
    return build(s, shifted, snippets, n, 0, err, err_len) || build(s, photopic, snippets, n, 1, err, err_len);
}

int sky_dome_divisor_for(const sky_core *s)
{
    int divisor = s->cfg.dome_divisor ? s->cfg.dome_divisor : DOME_DIVISOR;
    return s->cfg.output == SKY_OUTPUT_LDR && s->caps.render_to_rgba8 && divisor > 1 ? divisor : 0;
}

int sky_dome_day_divisor_for(const sky_core *s)
{
    int chosen = s->cfg.dome_divisor != 0 || s->atmosphere != SKY_ATMOSPHERE_GRADIENT;
    return s->dome_divisor && !chosen ? DOME_DAY_DIVISOR : s->dome_divisor;
}

/* (The image's uniforms and the corner of a power-of-two image:
 * over_dome.c, which the layers drawn over the dome share.) */
static const sky_snippet fisheye_circle_snippet = {"SKY_FISHEYE_CIRCLE", NULL, NULL, 0, NULL, NULL, NULL};

/* The image for a viewport: 1/divisor of it on each axis, rounded up
 * (used), in a texture of that size, or without NPOT textures of the
 * powers of two that hold it (its corner used: the same picture on every
 * GPU, at up to four times the memory). The all-sky image is for looking
 * at, not for a frame rate, and a cube map's faces are small and must meet
 * without the reduced image's steps at their edges: theirs have every
 * pixel. */
static void image_size(const sky_core *s, int divisor, int used[2], int size[2])
{
    for (int i = 0; i < 2; i++) {
        int n = (s->viewport[2 + i] + divisor - 1) / divisor, p = 1;
        used[i] = n < 1 ? 1 : n;
        while (p < used[i]) p *= 2;
        size[i] = s->caps.npot ? used[i] : p;
    }
}

static int create_image_path(sky_core *s, dome_state *st, char *err, size_t err_len)
{
    const sky_snippet *own[3] = {&sky_dome_image_snippet, &sky_dome_corner_snippet, &fisheye_circle_snippet};
    int n = s->caps.npot ? 1 : 2; /* (own[1] only without NPOT) */
    if (s->caps.npot) own[1] = &fisheye_circle_snippet;
    if (sky_program_build(s, &st->composite, "composite.vert", "composite.frag", own, n, err, err_len) ||
        sky_program_build(s, &st->composite_fisheye, "composite.vert", "composite.frag", own, n + 1, err, err_len))
        return -1;
    static const float corners[8] = {-1, -1, 1, -1, -1, 1, 1, 1};
    st->quad = sky_buffer_create(s, GL_ARRAY_BUFFER, corners, sizeof corners, GL_STATIC_DRAW);
    /* a first image, to check the framebuffer with; resized by fit_image */
    if (!st->quad || sky_texture_create_image(s, SKY_TEX_DOME, SKY_LAYER_ATMOSPHERE, 4, 4, err, err_len)) {
        if (!st->quad) sky_format(err, err_len, "glGenBuffers failed for the dome's quad");
        return -1;
    }
    st->fbo = sky_gl_target_create(s, SKY_TEX_DOME, err, err_len);
    return st->fbo ? 0 : -1;
}

/* Appends count snippets to list's first n; the new length. */
static int append(const sky_snippet **list, int n, const sky_snippet *const *add, int count)
{
    for (int i = 0; i < count; i++) list[n++] = add[i];
    return n;
}

/* The dome's variants: the day's (with and without the scotopic shift),
 * the ground's, the night's and the night's without the front layers,
 * composed in list (room for all the snippets). */
static int build_dome_programs(sky_core *s, dome_state *st, const sky_dome_snippets *d, const sky_snippet **list,
                               char *err, size_t err_len)
{
    int atmosphere = sky_atmosphere_snippets(s->atmosphere, s->cfg.blend_partner, s->profile != SKY_GL_CORE33, list), n = atmosphere;
    n = append(list, n, d->front, d->front_count);
    if (build_day(s, &st->day, &st->day_photopic, list, n, err, err_len)) return -1;
    /* Below the horizon there are no clouds and no stars: the lower
     * hemisphere gets the atmosphere alone (the host's terrain usually
     * covers it; what shows in a gap is the horizon haze). */
    if (d->front_count && build_day(s, &st->ground, &st->ground_photopic, list, atmosphere, err, err_len)) return -1;
    if (!d->night_count) return 0;
    n = append(list, n, d->night, d->night_count);
    if (build(s, &st->night, list, n, 0, err, err_len)) return -1;
    /* and the night without the front layers, when none shows (by day the
     * atmosphere-only program serves): the night layers moved down over
     * the front ones */
    if (!d->front_count) return 0;
    return build(s, &st->night_clear, list, append(list, atmosphere, d->night, d->night_count), 0, err, err_len);
}

/* The optics' variants (a rainbow, a halo: their light lies over the
 * front layers, which they need): the day's and the night's with them,
 * for the frames where one shows; none without an optics layer. */
static int build_optics_programs(sky_core *s, dome_state *st, const sky_dome_snippets *d, const sky_snippet **list,
                                 char *err, size_t err_len)
{
    if (!d->optics_count || !d->front_count) return 0;
    int n = sky_atmosphere_snippets(s->atmosphere, s->cfg.blend_partner, s->profile != SKY_GL_CORE33, list);
    n = append(list, n, d->front, d->front_count);
    n = append(list, n, d->optics, d->optics_count);
    if (build_day(s, &st->day_optics, &st->day_optics_photopic, list, n, err, err_len)) return -1;
    if (!d->night_count) return 0;
    n = append(list, n, d->night, d->night_count);
    return build(s, &st->night_optics, list, n, 0, err, err_len);
}

/* The occasional night glows' variants (the aurora: most nights show
 * none, and compiled into the night's program it costs even where it
 * is dark): the night's with them, with and without the front layers,
 * for the frames where one shows. */
static int build_occasional_programs(sky_core *s, dome_state *st, const sky_dome_snippets *d,
                                     const sky_snippet **list, char *err, size_t err_len)
{
    if (!d->occasional_count) return 0;
    int atmosphere = sky_atmosphere_snippets(s->atmosphere, s->cfg.blend_partner, s->profile != SKY_GL_CORE33, list);
    int n = atmosphere;
    n = append(list, n, d->night, d->night_count);
    n = append(list, n, d->occasional, d->occasional_count);
    if (d->front_count && build(s, &st->night_clear_occasional, list, n, 0, err, err_len)) return -1;
    /* the front layers before the night's */
    n = atmosphere;
    n = append(list, n, d->front, d->front_count);
    n = append(list, n, d->night, d->night_count);
    n = append(list, n, d->occasional, d->occasional_count);
    return build(s, &st->night_occasional, list, n, 0, err, err_len);
}

static int dome_create(sky_core *s, void *state, char *err, size_t err_len)
{
    dome_state *st = state;
    const sky_dome_snippets *d = s->dome_snippets;
    if (create_mesh(s, st, err, err_len)) return -1;
    if (s->dome_divisor && create_image_path(s, st, err, err_len)) return -1;
    /* the atmosphere's, the front layers', the night layers' (and build's
     * own): as many as the enabled layers bring */
    const sky_snippet **list = malloc(sizeof *list * (size_t)(SKY_ATMOSPHERE_SNIPPETS + d->front_count +
                                                                  d->night_count + d->optics_count +
                                                                  d->occasional_count));
    if (!list) {
        sky_format(err, err_len, "out of memory");
        return -1;
    }
    int rc = build_dome_programs(s, st, d, list, err, err_len) || build_optics_programs(s, st, d, list, err, err_len) ||
             build_occasional_programs(s, st, d, list, err, err_len);
    free(list);
    return rc;
}

static void dome_destroy(sky_core *s, void *state)
{
    dome_state *st = state;
    sky_program_destroy(s, &st->day);
    sky_program_destroy(s, &st->night);
    sky_program_destroy(s, &st->night_clear);
    sky_program_destroy(s, &st->ground);
    sky_program_destroy(s, &st->day_photopic);
    sky_program_destroy(s, &st->ground_photopic);
    sky_program_destroy(s, &st->day_optics);
    sky_program_destroy(s, &st->day_optics_photopic);
    sky_program_destroy(s, &st->night_optics);
    sky_program_destroy(s, &st->night_occasional);
    sky_program_destroy(s, &st->night_clear_occasional);
    sky_program_destroy(s, &st->composite);
    sky_program_destroy(s, &st->composite_fisheye);
    const GLuint buffers[3] = {st->vertices, st->indices, st->quad};
    const size_t bytes[3] = {st->vertex_bytes, st->index_bytes, 8 * sizeof(float)};
    sky_buffers_destroy(s, buffers, bytes, 3);
    free(st->dirs);
    free(st->mesh);
    free(st->vertex_data);
    free(st->list);
    free(st->outside);
    sky_gl_target_destroy(s, st->fbo);
}

/* The image follows the viewport's size and this draw's divisor. */
static void fit_image(sky_core *s, dome_state *st, int divisor)
{
    int used[2], size[2];
    image_size(s, divisor, used, size);
    const sky_texture *t = &s->textures[SKY_TEX_DOME];
    /* should it fail (out of memory), the old texture stays, its corner
     * stretched over the viewport */
    if ((t->width != size[0] || t->height != size[1]) && sky_texture_resize_image(s, SKY_TEX_DOME, size[0], size[1])) {
        used[0] = used[0] < t->width ? used[0] : t->width;
        used[1] = used[1] < t->height ? used[1] : t->height;
    }
    sky_frame *f = &s->frame;
    for (int i = 0; i < 2; i++) {
        st->used[i] = used[i];
        f->dome_texel[i] = 1.0f / (float)(i ? t->height : t->width);
        f->dome_scale[i] = (float)used[i] * f->dome_texel[i];
    }
}

static int dome_visible(const sky_core *s, const void *state)
{
    (void)s;
    return ((const dome_state *)state)->vertices != 0;
}

/* The physical paths' moonlit sky into the vertices, when it changed (a
 * step of the moon: atmosphere.c). */
static void moonlit_vertices(sky_core *s, dome_state *st)
{
    if (!st->vertex_data || st->moonlit_generation == s->frame.moonlit_generation) return;
    st->moonlit_generation = s->frame.moonlit_generation;
    size_t n = st->vertex_bytes / (sizeof(float) * DOME_FLOATS);
    for (size_t i = 0; i < n; i++) {
        float *p = st->vertex_data + i * DOME_FLOATS;
        double d[3] = {p[0], p[1], p[2]}, rgb[3];
        sky_atmosphere_moonlit_unit(s, d, rgb);
        for (int c = 0; c < 3; c++) p[3 + c] = (float)rgb[c];
    }
    sky_buffer_update(s, GL_ARRAY_BUFFER, st->vertices, st->vertex_data, st->vertex_bytes, GL_DYNAMIC_DRAW);
}

/* The dome: the atmosphere, with the night backdrop behind it and the
 * front layers (clouds) over it, in one pass over the screen. Which
 * variant: the night one while a backdrop layer shows, the one without
 * front code while none of those shows (Roden-Parberry's clouds vanish
 * at cover 0). */
static int dome_draw(sky_core *s, void *state)
{
    dome_state *st = state;
    const sky_frame *f = &s->frame;
    int night = st->night.id && s->dome_night_shows;
    int clear = s->dome_snippets->front_count && !s->dome_front_shows;
    int photopic = !(f->night_shift > 0.0f);
    const sky_program *ground = photopic ? &st->ground_photopic : &st->ground;
    const sky_program *upper = night ? (clear ? &st->night_clear : &st->night)
                                     : clear ? ground : photopic ? &st->day_photopic : &st->day;
    /* an optics layer shows: its variant, over the front layers it needs */
    if (s->dome_optics_shows && !clear && st->day_optics.id)
        upper = night ? (st->night_optics.id ? &st->night_optics : upper)
                      : photopic ? &st->day_optics_photopic : &st->day_optics;
    /* an occasional night glow shows (the aurora): the night's variant
     * with it (before a night's optics, which would need yet another) */
    if (s->dome_occasional_shows && st->night_occasional.id) {
        night = 1;
        upper = clear && st->night_clear_occasional.id ? &st->night_clear_occasional : &st->night_occasional;
    }
    sky_atmosphere_upload(s); /* a sky-view table rebuilt since the last draw */
    moonlit_vertices(s, st);
    select_triangles(s, st);
    sky_gl_target target;
    int into_image = st->fbo != 0;
    /* the image's divisor for this draw: every pixel for the all-sky image
     * and the cube map's faces (image_size says why), the day's where the
     * clouds show over a day program */
    int divisor = f->fisheye >= 0.5f || s->capturing ? 1 : s->dome_front_shows && !night ? s->dome_day_divisor
                                                                                         : s->dome_divisor;
    sky_clouds_image_step(s, into_image ? divisor : 1);
    if (into_image) {
        fit_image(s, st, divisor);
        sky_gl_target_begin(s, st->fbo, SKY_TEX_DOME, st->used[0], st->used[1], &target);
        if (f->fisheye >= 0.5f) { /* the margin around the all-sky circle */
            const GLint all[4] = {0, 0, st->used[0], st->used[1]};
            sky_gl_clear_viewport(s, all);
        }
    }
    sky_program_apply(s, upper);
    draw_hemisphere(s, st, 1);
    int draws = 1;
    /* the lower hemisphere: its own cheap program when the upper one
     * carries more than the atmosphere, unless a weather's haze or deck
     * (in the clouds' code) lies over the ground too; none in the all-sky
     * image */
    if (f->fisheye < 0.5f) {
        if (ground->id && !(f->haze[0] > 0.0f) && !(f->deck > 0.0f)) {
            sky_program_apply(s, ground);
            draws++;
        }
        draw_hemisphere(s, st, 0);
    }
    if (!into_image) return draws;
    sky_gl_target_end(s, &target);
    /* the image over the viewport: one filtered fetch and the dither */
    static const sky_gl_layout quad = {2 * sizeof(float), {{2, GL_FLOAT, GL_FALSE, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}}};
    sky_program_apply(s, f->fisheye >= 0.5f ? &st->composite_fisheye : &st->composite);
    sky_gl_vertices_bind(s, st->quad, 0, &quad);
    sky_gl_draw_arrays(s, GL_TRIANGLE_STRIP, 0, 4);
    return draws + 1;
}

static size_t dome_buffer_bytes(const sky_core *s, const void *state)
{
    (void)s;
    const dome_state *st = state;
    return (st->vertices ? st->vertex_bytes : 0) + (st->indices ? st->index_bytes : 0) +
           (st->quad ? 8 * sizeof(float) : 0);
}

const sky_layer_class sky_dome_layer = {
    .name = "atmosphere",
    .slot = SKY_LAYER_ATMOSPHERE,
    .state_size = sizeof(dome_state),
    .blend = SKY_BLEND_NONE,
    .create = dome_create,
    .destroy = dome_destroy,
    .visible = dome_visible,
    .draw = dome_draw,
    .buffer_bytes = dome_buffer_bytes,
};
