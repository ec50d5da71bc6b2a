/*
 * A disc on the sky (disc.h): its part above the horizon, and the
 * tessellated quad the sun and the moon are drawn on.
 */
#include "disc.h"

#include <math.h>

#define GRID_VERTEX_BYTES (SKY_DISC_GRID_VERTICES * 5 * sizeof(float))
#define GRID_INDEX_BYTES ((SKY_DISC_GRID_INDICES + SKY_DISC_COARSE_INDICES) * sizeof(unsigned short))

double sky_disc_above_horizon(double altitude, double radius)
{
    /* a disc whose centre is d radii above a straight horizon shows
     * 1 - (acos d - d sqrt(1 - d^2)) / pi of its area (circular segment) */
    if (!(radius > 0.0)) return altitude >= 0.0 ? 1.0 : 0.0;
    double d = sky_clampd(altitude / radius, -1.0, 1.0);
    return 1.0 - (acos(d) - d * sqrt(fmax(1.0 - d * d, 0.0))) / SKY_PI;
}

/* Two triangles per cell of `cells` per side, over the vertex rows of the
 * fine grid (SKY_DISC_GRID + 1 vertices each). */
static int grid_indices(unsigned short *idx, int cells)
{
    int k = 0, step = SKY_DISC_GRID / cells, row = SKY_DISC_GRID + 1;
    for (int j = 0; j < SKY_DISC_GRID; j += step)
        for (int i = 0; i < SKY_DISC_GRID; i += step) {
            unsigned short a = (unsigned short)(j * row + i), b = (unsigned short)(a + step);
            unsigned short c = (unsigned short)(a + step * row), d = (unsigned short)(c + step);
            idx[k++] = a, idx[k++] = b, idx[k++] = c;
            idx[k++] = b, idx[k++] = d, idx[k++] = c;
        }
    return k;
}

int sky_disc_grid_create(sky_core *s, sky_disc_grid *g, const char *what, char *err, size_t err_len)
{
    /* the fine grid's indices, then the coarse grid's */
    unsigned short idx[SKY_DISC_GRID_INDICES + SKY_DISC_COARSE_INDICES];
    int fine = grid_indices(idx, SKY_DISC_GRID);
    grid_indices(idx + fine, SKY_DISC_COARSE_GRID);
    static const float zero[SKY_DISC_GRID_VERTICES * 5];
    g->vertices = sky_buffer_create(s, GL_ARRAY_BUFFER, zero, sizeof zero, GL_DYNAMIC_DRAW);
    g->indices = sky_buffer_create(s, GL_ELEMENT_ARRAY_BUFFER, idx, sizeof idx, GL_STATIC_DRAW);
    if (!g->vertices || !g->indices) {
        sky_format(err, err_len, "glGenBuffers failed for the %s", what);
        return -1;
    }
    return 0;
}

void sky_disc_grid_update(sky_core *s, const sky_disc_grid *g, const double centre[3], const double x[3],
                          const double y[3], double half, double pos_half)
{
    float v[SKY_DISC_GRID_VERTICES * 5];
    for (int j = 0, n = 0; j <= SKY_DISC_GRID; j++)
        for (int i = 0; i <= SKY_DISC_GRID; i++, n++) {
            double u = 2.0 * i / SKY_DISC_GRID - 1.0, w = 2.0 * j / SKY_DISC_GRID - 1.0;
            v[n * 5 + 0] = (float)(u * pos_half);
            v[n * 5 + 1] = (float)(w * pos_half);
            for (int c = 0; c < 3; c++) v[n * 5 + 2 + c] = (float)(centre[c] + half * (u * x[c] + w * y[c]));
        }
    sky_buffer_update(s, GL_ARRAY_BUFFER, g->vertices, v, sizeof v, GL_DYNAMIC_DRAW);
}

void sky_disc_grid_draw(sky_core *s, const sky_disc_grid *g, double centre_altitude, double half_angle)
{
    int coarse = centre_altitude - half_angle * 1.41421356 >= SKY_DISC_COARSE_ABOVE_DEG * SKY_PI / 180.0;
    static const sky_gl_layout layout = {
        5 * sizeof(float), {{2, GL_FLOAT, GL_FALSE, 0}, {3, GL_FLOAT, GL_FALSE, 2 * sizeof(float)}, {0, 0, 0, 0}}};
    sky_gl_vertices_bind(s, g->vertices, g->indices, &layout);
    if (coarse)
        sky_gl_draw_elements(s, GL_TRIANGLES, SKY_DISC_GRID_INDICES, SKY_DISC_COARSE_INDICES);
    else
        sky_gl_draw_elements(s, GL_TRIANGLES, 0, SKY_DISC_GRID_INDICES);
}

size_t sky_disc_grid_bytes(const sky_disc_grid *g) { return g->vertices ? GRID_VERTEX_BYTES + GRID_INDEX_BYTES : 0; }

void sky_disc_grid_destroy(sky_core *s, sky_disc_grid *g)
{
    const GLuint buffers[2] = {g->vertices, g->indices};
    const size_t bytes[2] = {GRID_VERTEX_BYTES, GRID_INDEX_BYTES};
    sky_buffers_destroy(s, buffers, bytes, 2);
    g->vertices = g->indices = 0;
}
