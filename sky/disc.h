/*
 * A disc on the sky (the sun's, the moon's): how much of it stands above
 * the horizon, and the tessellated quad that draws it.
 *
 * The quad is a grid of SKY_DISC_GRID^2 cells: the vertex shaders undo
 * the refraction at each vertex (common.glsl's sky_unrefract), which is
 * smooth enough over a cell (0.53 degree for the sun, 0.33 for the moon at
 * its default scale) for linear interpolation to keep the disc's shape:
 * w^2/8 times the refraction's curvature is at most 13 arcseconds at the
 * horizon (1.3 % of the sun's radius), 5 for the moon. The fragment
 * shaders only normalise. The vertices (grid position, direction) are
 * rewritten each frame; the indices are fixed.
 */
#ifndef SKY_DISC_H
#define SKY_DISC_H

#include "gl/gl.h"

/* The fraction of a disc of the given angular radius (radians) whose
 * centre is at altitude that stands above the horizon: 0..1, continuous. */
double sky_disc_above_horizon(double altitude, double radius);

#define SKY_DISC_GRID 16
#define SKY_DISC_GRID_VERTICES ((SKY_DISC_GRID + 1) * (SKY_DISC_GRID + 1))
#define SKY_DISC_GRID_INDICES (SKY_DISC_GRID * SKY_DISC_GRID * 6)
typedef struct sky_disc_grid {
    GLuint vertices, indices;
} sky_disc_grid;
/* The grid's buffers; 0, or -1 with a message naming `what`. */
int sky_disc_grid_create(sky_core *s, sky_disc_grid *g, const char *what, char *err, size_t err_len);
void sky_disc_grid_destroy(sky_core *s, sky_disc_grid *g);
/* GPU bytes of a created grid (0 for none). */
size_t sky_disc_grid_bytes(const sky_disc_grid *g);
/* Rewrites the grid over the square centre +- half (tangent-plane units)
 * along the unit axes x and y; a_pos runs over +-pos_half. */
void sky_disc_grid_update(sky_core *s, const sky_disc_grid *g, const double centre[3], const double x[3],
                          const double y[3], double half, double pos_half);
/* Binds the grid (a_pos, a_dir) and draws it with the current program. */
void sky_disc_grid_draw(sky_core *s, const sky_disc_grid *g);

#endif /* SKY_DISC_H */
