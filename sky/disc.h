/*
 * A disc on the sky (the sun's, the moon's): how much of it stands above
 * the horizon, and the tessellated quad that draws it.
 *
 * The quad is a grid of SKY_DISC_GRID^2 cells: the vertex shaders undo
 * the refraction at each vertex (common.glsl's sky_unrefract), which is
 * smooth enough over a cell (0.53 degree for the sun, 0.33 for the moon at
 * its default scale) for linear interpolation to keep the disc's shape:
 * w^2/8 times the refraction's curvature is at most 13 arcseconds at the
 * horizon (1.3 % of the sun's radius), 5 for the moon. Where the whole
 * quad stands 10 degrees up or higher, 2 x 2 cells of the same grid keep
 * the error under 8 arcseconds for the sun's quad (cells of 4.3 degrees;
 * Bennett's refraction against its chord), under the fine grid's worst: a
 * software rasteriser pays for each of the 512 small triangles (the
 * sun's fine grid cost a tenth of a full-screen quad on llvmpipe). The
 * fragment shaders only normalise. The vertices (grid position,
 * direction) are rewritten each frame; the indices are fixed.
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
#define SKY_DISC_COARSE_GRID 2
#define SKY_DISC_COARSE_INDICES (SKY_DISC_COARSE_GRID * SKY_DISC_COARSE_GRID * 6)
#define SKY_DISC_COARSE_ABOVE_DEG 10.0
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
/* Binds the grid (a_pos, a_dir) and draws it with the current program:
 * the coarse cells when the quad's lowest corner stands at least
 * SKY_DISC_COARSE_ABOVE_DEG up. centre_altitude (apparent) and
 * half_angle (the quad's centre to its edge) in radians. */
void sky_disc_grid_draw(sky_core *s, const sky_disc_grid *g, double centre_altitude, double half_angle);

#endif /* SKY_DISC_H */
