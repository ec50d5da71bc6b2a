/*
 * Catalogue stars after Mueller et al. 2012, sec. 4: every star of the
 * built-in catalogue (to V 6.5) as one point, coloured by its B-V, sized by
 * the field of view (eq. 9), with a physically normalised intensity PSF
 * (eq. 10), glare for stars brighter than the control magnitude,
 * extinction (eq. 11-12) and scintillation. Shaders: stars.vert/.frag.
 */
#include "camera.h"
#include "catalog.h"
#include "exposure.h"
#include "layer.h"
#include "points.h"
#include "atmosphere/atmosphere.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define STAR_FLOATS SKY_POINT_FLOATS /* a_pos (index, 0), a_dir (3), a_color (rgb, V) */

/* The buffer holds the stars in cells of about equal area, STAR_BANDS in
 * sin(dec) by STAR_COLUMNS in right ascension (about 8 stars each, 4 to
 * 12 degrees across), brightest first within each; a draw takes, through
 * an index list, only the stars above the horizon and in view, and of
 * those the ones the naked eye reaches (stars_select): 784 of the 8874 in
 * the starry preset's view, 132 in the moonlit one's. A rasterizer sets
 * up every point it is given, in view or not (SwiftShader about 0.5 us
 * each, whatever the shader: docs/validation.md). */
#define STAR_BANDS 24
#define STAR_COLUMNS 48
#define STAR_CELLS (STAR_BANDS * STAR_COLUMNS)
typedef struct star_cell {
    int first, count;  /* its stars in the buffer                        */
    float dir[3];      /* their mean direction, J2000                   */
    float radius;      /* the largest angle of one from it, radians    */
} star_cell;

typedef struct stars_state {
    sky_program program;
    sky_catalog catalog;
    GLuint buffer;
    double epoch;             /* years since J2000 of the uploaded positions */
    float point_max;          /* largest point size the context draws      */
    double scintillation;     /* the clock's phase, wrapped                */
    int brightest_first;      /* the catalogue is sorted so (catgen.c's is) */
    /* in cells (when the catalogue fits 16-bit indices): */
    star_cell cells[STAR_CELLS];
    float *vmag;              /* V of each star in the buffer's order       */
    float *dirs;              /* and its J2000 direction (3 floats)         */
    float vmag_least;         /* the brightest star's V                     */
    unsigned short *indices;  /* the draw's list                           */
    GLuint elements;          /* and its buffer                            */
    int whole;                /* tests: every star, without the cells      */
    sky_point_frame points;   /* stars.vert's uniforms for the catalogue   */
} stars_state;

static const sky_uniform_desc star_uniforms[] = {SKY_POINT_UNIFORMS(stars_state, points)};
static const sky_snippet stars_snippet = {NULL, NULL, star_uniforms, SKY_UNIFORM_COUNT(star_uniforms),
                                          NULL, NULL, NULL};

/* A star's place in the buffer: its cell, brightest first within it. */
typedef struct star_place {
    int cell, index;
    float vmag;
} star_place;

static int by_cell(const void *a, const void *b)
{
    const star_place *p = a, *q = b;
    if (p->cell != q->cell) return p->cell < q->cell ? -1 : 1;
    if (p->vmag != q->vmag) return p->vmag < q->vmag ? -1 : 1;
    return (p->index > q->index) - (p->index < q->index);
}

/* Fills the vertex buffer: J2000 directions moved by proper motion to the
 * given epoch (years since J2000), colours and magnitudes; in cells (and
 * the cells' table) when st->indices is there, else in the catalogue's
 * order. */
static int upload_stars(sky_core *s, stars_state *st, double years, char *err, size_t err_len)
{
    const sky_catalog *cat = &st->catalog;
    float *v = malloc(sizeof(float) * STAR_FLOATS * (size_t)cat->count);
    star_place *order = malloc(sizeof *order * (size_t)(cat->count > 0 ? cat->count : 1));
    if (!v || !order) {
        free(v);
        free(order);
        sky_format(err, err_len, "out of memory for %d stars", cat->count);
        return -1;
    }
    st->brightest_first = 1;
    const double mas = SKY_PI / 648000.0 * 1e-3;
    for (int i = 0; i < cat->count; i++) {
        const sky_star *star = &cat->stars[i];
        if (i > 0 && star->vmag < cat->stars[i - 1].vmag) st->brightest_first = 0;
        double cd = cos(star->dec);
        double ra = star->ra + (cd > 1e-9 ? star->pm_ra / cd : 0.0) * mas * years;
        double dec = star->dec + star->pm_dec * mas * years;
        float *p = v + i * STAR_FLOATS;
        p[0] = (float)i; /* the twinkle's seed: the catalogue's index */
        p[1] = 0.0f;
        p[2] = (float)(cos(dec) * cos(ra));
        p[3] = (float)(cos(dec) * sin(ra));
        p[4] = (float)sin(dec);
        sky_star_color(star->bv, p + 5);
        p[8] = star->vmag;
        double column = fmod(atan2(p[3], p[2]) / (2.0 * SKY_PI) + 1.0, 1.0) * STAR_COLUMNS;
        int band = (int)sky_clampd((p[4] + 1.0) * 0.5 * STAR_BANDS, 0.0, STAR_BANDS - 1);
        order[i] = (star_place){band * STAR_COLUMNS + (int)sky_clampd(column, 0.0, STAR_COLUMNS - 1), i, star->vmag};
    }
    size_t bytes = sizeof(float) * STAR_FLOATS * (size_t)cat->count;
    float *sorted = st->indices ? malloc(bytes) : NULL;
    if (sorted) {
        qsort(order, (size_t)cat->count, sizeof *order, by_cell);
        memset(st->cells, 0, sizeof st->cells);
        st->vmag_least = cat->count > 0 ? order[0].vmag : 0.0f;
        for (int k = 0; k < cat->count; k++) {
            memcpy(sorted + k * STAR_FLOATS, v + order[k].index * STAR_FLOATS, sizeof(float) * STAR_FLOATS);
            memcpy(st->dirs + 3 * k, sorted + k * STAR_FLOATS + 2, sizeof(float) * 3);
            st->vmag[k] = order[k].vmag;
            st->vmag_least = fminf(st->vmag_least, order[k].vmag);
            star_cell *c = &st->cells[order[k].cell];
            if (!c->count) c->first = k;
            c->count++;
            for (int j = 0; j < 3; j++) c->dir[j] += sorted[k * STAR_FLOATS + 2 + j];
        }
        for (int n = 0; n < STAR_CELLS; n++) {
            star_cell *c = &st->cells[n];
            double len = sqrt(c->dir[0] * c->dir[0] + c->dir[1] * c->dir[1] + c->dir[2] * c->dir[2]);
            double nearest = 1.0;
            for (int j = 0; j < 3; j++) c->dir[j] = len > 0.0 ? (float)(c->dir[j] / len) : 0.0f;
            for (int k = c->first; k < c->first + c->count; k++) {
                const float *d = sorted + k * STAR_FLOATS + 2;
                nearest = fmin(nearest, d[0] * c->dir[0] + d[1] * c->dir[1] + d[2] * c->dir[2]);
            }
            c->radius = (float)acos(sky_clampd(nearest, -1.0, 1.0));
        }
        free(v);
        v = sorted;
    }
    free(order);
    if (!st->buffer)
        st->buffer = sky_buffer_create(s, GL_ARRAY_BUFFER, v, bytes, GL_STATIC_DRAW);
    else
        sky_buffer_update(s, GL_ARRAY_BUFFER, st->buffer, v, bytes, GL_STATIC_DRAW);
    free(v);
    st->epoch = years;
    if (!st->buffer) {
        sky_format(err, err_len, "glGenBuffers failed for the stars");
        return -1;
    }
    return 0;
}

static size_t star_bytes(const sky_catalog *cat) { return sizeof(float) * STAR_FLOATS * (size_t)cat->count; }

static int stars_create(sky_core *s, void *state, char *err, size_t err_len)
{
    stars_state *st = state;
    if (sky_catalog_load(&st->catalog, err, err_len)) return -1;
    st->point_max = sky_gl_point_size_max(s);
    /* the cells need 16-bit indices (ES 2.0 has no others); a catalogue
     * past them is drawn whole, in its own order */
    int n = st->catalog.count;
    if (n > 0 && n <= 65536) {
        st->vmag = malloc(sizeof *st->vmag * (size_t)n);
        st->dirs = malloc(sizeof *st->dirs * 3 * (size_t)n);
        st->indices = malloc(sizeof *st->indices * (size_t)n);
        if (!st->vmag || !st->dirs || !st->indices) {
            sky_format(err, err_len, "out of memory for %d stars", n);
            return -1;
        }
        st->elements = sky_buffer_create(s, GL_ELEMENT_ARRAY_BUFFER, NULL, sizeof *st->indices * (size_t)n,
                                         GL_DYNAMIC_DRAW);
        if (!st->elements) {
            sky_format(err, err_len, "glGenBuffers failed for the stars' index list");
            return -1;
        }
    }
    if (upload_stars(s, st, s->astro.years_since_j2000, err, err_len)) return -1;
    if (sky_snippet_bind(s, &stars_snippet, state)) {
        sky_format(err, err_len, "out of memory");
        return -1;
    }
    const sky_snippet *own[1] = {&stars_snippet};
    return sky_program_build_over_dome(s, s->dome_snippets, &st->program, "stars.vert", "stars.frag", own, 1, err,
                                       err_len);
}

static void stars_destroy(sky_core *s, void *state)
{
    stars_state *st = state;
    sky_program_destroy(s, &st->program);
    const GLuint buffers[2] = {st->buffer, st->elements};
    const size_t bytes[2] = {star_bytes(&st->catalog), sizeof *st->indices * (size_t)st->catalog.count};
    sky_buffers_destroy(s, buffers, bytes, 2);
    free(st->vmag);
    free(st->dirs);
    free(st->indices);
    sky_catalog_free(&st->catalog);
}

static void stars_advance(sky_core *s, void *state, double dt)
{
    stars_state *st = state;
    (void)s;
    st->scintillation = sky_scintillation_advance(st->scintillation, dt);
}

static void stars_reset(void *state) { ((stars_state *)state)->scintillation = 0.0; }

/* The catalogue is in J2000: the sky's rotation takes it to the horizon. */
static void stars_frame(sky_core *s, void *state)
{
    stars_state *st = state;
    sky_j2000_to_horizon_mat4(&s->astro, 0, st->points.rot);
}

/* Per draw, from the observer's astronomy and the camera. */
static void stars_view(sky_core *s, void *state)
{
    stars_state *st = state;
    const sky_astro *a = &s->astro;
    /* proper motion moves Arcturus 0.1" a month: refresh past half a year */
    if (fabs(a->years_since_j2000 - st->epoch) > 0.5) upload_stars(s, st, a->years_since_j2000, NULL, 0);
    for (int i = 0; i < 3; i++)
        st->points.aberration[i] = (float)(a->horizon[i * 3] * a->aberration[0] +
                                           a->horizon[i * 3 + 1] * a->aberration[1] +
                                           a->horizon[i * 3 + 2] * a->aberration[2]);
    sky_point_view(s, st->point_max, st->scintillation, &st->points);
}

/* The brightest star (Sirius, V -1.46) is past the naked eye's limit, or
 * would add less than a quarter of an 8-bit step at the automatic
 * exposure: skip the draw (by day, that is always). The same rule holds
 * for HDR output, so a host doing its own tone mapping does no star work
 * at noon either. */
static int stars_visible(const sky_core *s, const void *state)
{
    const stars_state *st = state;
    if (!st->buffer) return 0;
    const sky_frame *f = &s->frame;
    return st->points.flux_scale * pow(2.512, 1.46) * f->exposure >= 1.0 / 1024.0 && -1.46 < st->points.pressure[1] + 0.25;
}

/* How many of n magnitudes (brightest first, stride bytes apart from
 * first) the naked eye reaches against this sky: stars.vert gives nothing
 * to a star a quarter magnitude fainter than the limit. */
static int in_reach(const float *first, size_t stride, int n, float limit)
{
    int lo = 0, hi = n; /* the first past the limit lies in [lo, hi] */
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (*(const float *)(const void *)((const char *)first + (size_t)mid * stride) < limit + 0.26f)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* The draw's index list (STAR_CELLS): the stars the eye reaches in the
 * cells that reach above the horizon and, with a perspective camera, into
 * the view (a cone of the cell's radius and the margin against each side
 * plane of the frustum); in a cell across a boundary, star by star. Each
 * star left out saves a point that the rasterizer would set up only to
 * clip (SwiftShader spends about half a microsecond on one). Returns
 * their number. */
static int stars_select(const sky_core *s, stars_state *st)
{
    const sky_frame *f = &s->frame;
    const float *rot = st->points.rot;
    const sky_point_frame *pf = &st->points;
    sky_view_bounds b = sky_camera_bounds(f);
    int n = 0;
    /* A point spreads over its radius in pixels: the catalogue's brightest
     * star's bounds every cell's for a first test, then the cell's own
     * (its brightest star's) for the rest. Angles stand in for their
     * sines: never smaller, so nothing in view is left out. */
    double widest = sky_point_margin(f, pf, st->vmag_least);
    for (int c = 0; c < STAR_CELLS; c++) {
        const star_cell *cell = &st->cells[c];
        if (!cell->count) continue;
        double d[3];
        for (int i = 0; i < 3; i++) d[i] = rot[i] * cell->dir[0] + rot[4 + i] * cell->dir[1] + rot[8 + i] * cell->dir[2];
        double inside = sky_camera_inside_by(&b, d);
        if (inside < -(cell->radius + widest)) continue;
        double margin = sky_point_margin(f, pf, st->vmag[cell->first]);
        if (inside < -(cell->radius + margin)) continue;
        int count = in_reach(st->vmag + cell->first, sizeof(float), cell->count, pf->pressure[1]);
        int whole = inside >= cell->radius; /* every star inside */
        for (int k = cell->first; k < cell->first + count; k++) {
            if (!whole) {
                const float *j = st->dirs + 3 * k;
                for (int i = 0; i < 3; i++) d[i] = rot[i] * j[0] + rot[4 + i] * j[1] + rot[8 + i] * j[2];
                if (sky_camera_inside_by(&b, d) < -margin) continue;
            }
            st->indices[n++] = (unsigned short)k;
        }
    }
    return n;
}

static int stars_draw(sky_core *s, void *state)
{
    stars_state *st = state;
    if (!st->elements || st->whole) {
        /* a catalogue brightest first ends its draw at the first star past
         * the limit; one in another order is drawn whole */
        int count = st->catalog.count;
        if (st->brightest_first && !st->elements && count > 0)
            count = in_reach(&st->catalog.stars[0].vmag, sizeof(sky_star), count, st->points.pressure[1]);
        sky_points_draw(s, &st->program, st->buffer, 0, count);
        return 1;
    }
    int n = stars_select(s, st);
    if (!n) return 0;
    sky_buffer_update(s, GL_ELEMENT_ARRAY_BUFFER, st->elements, st->indices, sizeof *st->indices * (size_t)n,
                      GL_DYNAMIC_DRAW);
    sky_points_draw(s, &st->program, st->buffer, st->elements, n);
    return 1;
}

static size_t stars_buffer_bytes(const sky_core *s, const void *state)
{
    (void)s;
    const stars_state *st = state;
    return (st->buffer ? star_bytes(&st->catalog) : 0) + (st->elements ? sizeof *st->indices * (size_t)st->catalog.count : 0);
}

double sky_stars_clock(const void *state) { return ((const stars_state *)state)->scintillation; }
sky_catalog *sky_stars_catalog(void *state) { return &((stars_state *)state)->catalog; }
void sky_stars_reload(void *state) { ((stars_state *)state)->epoch = -1e9; /* the next frame uploads */ }
void sky_stars_draw_whole(void *state, int whole) { ((stars_state *)state)->whole = whole; }

/* Catalogue stars, added over the dome: their light dimmed by the
 * atmosphere (extinction in the shader) and hidden by the clouds. */
const sky_layer_class sky_stars_layer = {
    .name = "stars",
    .slot = SKY_LAYER_STARS,
    .feature = SKY_STARS,
    .state_size = sizeof(stars_state),
    .blend = SKY_BLEND_ADD,
    .create = stars_create,
    .destroy = stars_destroy,
    .advance = stars_advance,
    .reset_clock = stars_reset,
    .frame = stars_frame,
    .view = stars_view,
    .visible = stars_visible,
    .draw = stars_draw,
    .buffer_bytes = stars_buffer_bytes,
};
