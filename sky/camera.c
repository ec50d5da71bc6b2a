/*
 * The camera room (camera.h): the host's view and projection, or the
 * all-sky fisheye, as the frame's view_proj, pixel_angle and aspect; and
 * the horizon frame in the host's world.
 */
#include "camera.h"

#include <math.h>

/* Inverts a 4x4 column-major matrix in double. Returns 0 if singular. */
static int invert4(const double m[16], double out[16])
{
    double inv[16];
    inv[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] + m[9] * m[7] * m[14] +
             m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    inv[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] - m[8] * m[7] * m[14] -
             m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    inv[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] + m[8] * m[7] * m[13] +
             m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    inv[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] - m[8] * m[6] * m[13] -
              m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    inv[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] - m[9] * m[3] * m[14] -
             m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    inv[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] + m[8] * m[3] * m[14] +
             m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    inv[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] - m[8] * m[3] * m[13] -
             m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    inv[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] + m[8] * m[2] * m[13] +
              m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    inv[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] + m[5] * m[3] * m[14] +
             m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
    inv[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] - m[4] * m[3] * m[14] -
             m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    inv[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] + m[4] * m[3] * m[13] +
              m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    inv[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] - m[4] * m[2] * m[13] -
              m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    inv[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] - m[5] * m[3] * m[10] -
             m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
    inv[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] + m[4] * m[3] * m[10] +
             m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
    inv[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] - m[4] * m[3] * m[9] -
              m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
    inv[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] + m[4] * m[2] * m[9] +
              m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
    double det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
    /* Singular relative to Hadamard's bound, the product of the columns'
     * lengths (|det| reaches it for orthogonal columns): free of the
     * matrix's scale, so an extreme aspect ratio, one huge and one small
     * column, is not mistaken for a singular projection. */
    double bound = 1.0;
    for (int c = 0; c < 4; c++) {
        double len2 = 0.0;
        for (int r = 0; r < 4; r++) len2 += m[c * 4 + r] * m[c * 4 + r];
        bound *= sqrt(len2);
    }
    if (!isfinite(det) || !(fabs(det) > 1e-12 * bound)) return 0;
    for (int i = 0; i < 16; i++) out[i] = inv[i] / det;
    return 1;
}

/* The rotation from the horizon frame to the camera: the view's 3x3 made
 * orthonormal (a scaled or slightly skewed view still means a direction),
 * times horizon_to_world. Returns 0 for a degenerate view. */
static int camera_rotation(const sky_core *s, const float view[16], double rot[9])
{
    double r[3][3]; /* rows of the view's rotation: camera axes in world */
    for (int row = 0; row < 3; row++)
        for (int c = 0; c < 3; c++) r[row][c] = view[c * 4 + row];
    /* Gram-Schmidt on forward (row 2), then up (row 1); right = up x fwd. */
    double *f = r[2], *u = r[1];
    double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!(fl > 1e-12)) return 0;
    for (int i = 0; i < 3; i++) f[i] /= fl;
    double d = u[0] * f[0] + u[1] * f[1] + u[2] * f[2];
    for (int i = 0; i < 3; i++) u[i] -= d * f[i];
    double ul = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (!(ul > 1e-9 * fl)) return 0;
    for (int i = 0; i < 3; i++) u[i] /= ul;
    double x[3] = {u[1] * f[2] - u[2] * f[1], u[2] * f[0] - u[0] * f[2], u[0] * f[1] - u[1] * f[0]};
    /* keep the view's handedness for the x axis */
    if (x[0] * r[0][0] + x[1] * r[0][1] + x[2] * r[0][2] < 0.0)
        for (int i = 0; i < 3; i++) x[i] = -x[i];
    double cam[3][3] = {{x[0], x[1], x[2]}, {u[0], u[1], u[2]}, {f[0], f[1], f[2]}};
    /* rot = cam * H (H maps horizon to world), stored row-major */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double acc = 0.0;
            for (int k = 0; k < 3; k++) acc += cam[i][k] * s->horizon_to_world[j * 3 + k];
            rot[i * 3 + j] = acc;
        }
    return 1;
}

static void set_viewport(sky_core *s, const GLint viewport[4])
{
    for (int i = 0; i < 4; i++) s->frame.viewport[i] = (float)viewport[i];
}

int sky_camera_set(sky_core *s, const float view[16], const float proj[16], const GLint viewport[4], char *err,
                   size_t err_len)
{
    for (int i = 0; i < 16; i++)
        if (!isfinite(view[i]) || !isfinite(proj[i])) {
            sky_format(err, err_len, "sky_draw: %s[%d] is not finite", !isfinite(view[i]) ? "view" : "proj", i);
            return -1;
        }
    double rot[9];
    if (!camera_rotation(s, view, rot)) {
        sky_format(err, err_len, "sky_draw: the view matrix has a degenerate rotation");
        return -1;
    }
    double p[16], pinv[16];
    for (int i = 0; i < 16; i++) p[i] = proj[i];
    if (!invert4(p, pinv)) {
        sky_format(err, err_len, "sky_draw: the projection is singular");
        return -1;
    }
    /* u_view_proj = proj * [rot 0; 0 1], column-major */
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double acc = 0.0;
            for (int k = 0; k < 4; k++) {
                double m = (k < 3 && col < 3) ? rot[k * 3 + col] : (k == 3 && col == 3 ? 1.0 : 0.0);
                acc += p[k * 4 + row] * m;
            }
            s->frame.view_proj[col * 4 + row] = (float)acc;
        }
    s->frame.fisheye = 0.0f;
    set_viewport(s, viewport);
    /* radians per pixel at the view centre: 2 tan(fov/2) / height */
    s->frame.pixel_angle = (float)(2.0 / (fabs(p[5]) * (viewport[3] > 0 ? viewport[3] : 1)));
    return 0;
}

int sky_camera_clip_to_horizon(const sky_core *s, const float view[16], const float proj[16], float out[16])
{
    for (int i = 0; i < 16; i++)
        if (!isfinite(view[i]) || !isfinite(proj[i])) return -1;
    double rot[9], m[16], inv[16];
    if (!camera_rotation(s, view, rot)) return -1;
    /* proj * [rot 0; 0 1], as sky_camera_set builds it, inverted */
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double acc = 0.0;
            for (int k = 0; k < 4; k++) {
                double r = (k < 3 && col < 3) ? rot[k * 3 + col] : (k == 3 && col == 3 ? 1.0 : 0.0);
                acc += (double)proj[k * 4 + row] * r;
            }
            m[col * 4 + row] = acc;
        }
    if (!invert4(m, inv)) return -1;
    for (int i = 0; i < 16; i++) out[i] = (float)inv[i];
    return 0;
}

void sky_camera_fisheye(sky_core *s, const GLint viewport[4])
{
    double w = viewport[2] > 0 ? viewport[2] : 1, h = viewport[3] > 0 ? viewport[3] : 1;
    s->frame.aspect[0] = (float)(w > h ? w / h : 1.0);
    s->frame.aspect[1] = (float)(h > w ? h / w : 1.0);
    s->frame.fisheye = 1.0f;
    set_viewport(s, viewport);
    s->frame.pixel_angle = (float)(SKY_PI / (w < h ? w : h)); /* 90 degrees on the circle's radius */
}

void sky_camera_to_world(const sky_core *s, const float h[3], float w[3])
{
    for (int i = 0; i < 3; i++)
        w[i] = s->horizon_to_world[0 * 3 + i] * h[0] + s->horizon_to_world[1 * 3 + i] * h[1] +
               s->horizon_to_world[2 * 3 + i] * h[2];
}

static int check_rotation(const float m[9])
{
    for (int i = 0; i < 9; i++)
        if (!isfinite(m[i])) return 0;
    /* columns orthonormal within float tolerance */
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double dot = 0.0;
            for (int i = 0; i < 3; i++) dot += (double)m[a * 3 + i] * m[b * 3 + i];
            if (fabs(dot - (a == b ? 1.0 : 0.0)) > 1e-3) return 0;
        }
    return 1;
}

int sky_camera_horizon_to_world(const float m[9], float out[9])
{
    int identity = 1;
    for (int i = 0; i < 9; i++)
        if (m[i] != 0.0f) identity = 0;
    if (!identity && !check_rotation(m)) return -1;
    for (int i = 0; i < 9; i++) out[i] = identity ? (i % 4 == 0 ? 1.0f : 0.0f) : m[i];
    return 0;
}

sky_view_bounds sky_camera_bounds(const sky_frame *f)
{
    sky_view_bounds b;
    b.sides = f->fisheye < 0.5f ? 4 : 0;
    const float *vp = f->view_proj;
    for (int p = 0; p < 4; p++) {
        int row = p >> 1;
        double sign = p & 1 ? -1.0 : 1.0, len = 0.0;
        for (int j = 0; j < 3; j++) {
            b.planes[p][j] = vp[j * 4 + 3] + sign * vp[j * 4 + row];
            len += b.planes[p][j] * b.planes[p][j];
        }
        len = sqrt(len);
        for (int j = 0; j < 3; j++) b.planes[p][j] = len > 0.0 ? b.planes[p][j] / len : 0.0;
    }
    return b;
}

double sky_camera_inside_by(const sky_view_bounds *b, const double d[3])
{
    double least = d[1];
    for (int p = 0; p < b->sides; p++)
        least = fmin(least, b->planes[p][0] * d[0] + b->planes[p][1] * d[1] + b->planes[p][2] * d[2]);
    return least;
}
