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
#include "sky_internal.h"

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

static void ring_vertex(float *v, double elevation_sine, int seg)
{
    double az = 2.0 * SKY_PI * seg / DOME_SEGMENTS;
    double c = sqrt(sky_clampd(1.0 - elevation_sine * elevation_sine, 0.0, 1.0));
    v[0] = (float)(c * sin(az));  /* east  */
    v[1] = (float)elevation_sine; /* up    */
    v[2] = (float)(-c * cos(az)); /* south: az 0 is north (-z) */
}

int sky_dome_create(sky *s, char *err, size_t err_len)
{
    unsigned char *gradient = NULL, *galaxy = NULL;
    if (sky_asset_load_rgba(s, "gradient.png", 256, 1, &gradient, err, err_len)) return -1;
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
    for (int i = 0; i < n; i++) {
        float *p = v + i * DOME_FLOATS;
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
        if (r == DOME_RINGS_DOWN) s->dome_upper_first = (int)k;
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
    s->dome_vertices = sky_buffer_create(s, GL_ARRAY_BUFFER, v, sizeof(float) * DOME_FLOATS * (size_t)n,
                                         GL_STATIC_DRAW);
    s->dome_indices = sky_buffer_create(s, GL_ELEMENT_ARRAY_BUFFER, idx, sizeof(unsigned short) * k, GL_STATIC_DRAW);
    s->dome_index_count = (int)k;
    free(v);
    free(idx);
    sky_png_free(gradient);
    sky_png_free(galaxy);
    if (!s->dome_vertices || !s->dome_indices) {
        sky_format(err, err_len, "glGenBuffers failed for the dome mesh");
        return -1;
    }
    return 0;
}

void sky_dome_draw(sky *s, int upper)
{
    const sky_gl *gl = &s->gl;
    gl->glBindBuffer(GL_ARRAY_BUFFER, s->dome_vertices);
    gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, s->dome_indices);
    gl->glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, DOME_FLOATS * sizeof(float), (const void *)0);
    gl->glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, DOME_FLOATS * sizeof(float),
                              (const void *)(3 * sizeof(float)));
    gl->glDisableVertexAttribArray(0);
    gl->glEnableVertexAttribArray(1);
    gl->glEnableVertexAttribArray(2);
    int first = upper ? s->dome_upper_first : 0;
    int count = upper ? s->dome_index_count - s->dome_upper_first : s->dome_upper_first;
    gl->glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_SHORT, (const void *)(first * sizeof(unsigned short)));
}
