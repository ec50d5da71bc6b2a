/*
 * The camera room: the host's view and projection (or the all-sky
 * fisheye) turned into the frame's view_proj, pixel_angle and aspect, and
 * the horizon frame turned into the host's world.
 */
#ifndef SKY_CAMERA_H
#define SKY_CAMERA_H

#include "core.h"

/* Validates the camera and fills view_proj (horizon directions to clip)
 * and pixel_angle for the viewport. Returns 0, or -1 with a message. */
int sky_camera_set(sky_core *s, const float view[16], const float proj[16], const GLint viewport[4], char *err,
                   size_t err_len);
/* The inverse of that view_proj for a host's camera: clip coordinates to
 * a point on the view ray in the horizon frame (the eye at the origin).
 * 0, or -1 for a non-finite, degenerate or singular camera. */
int sky_camera_clip_to_horizon(const sky_core *s, const float view[16], const float proj[16], float out[16]);
/* What the view shows, for leaving out on the CPU what it does not: the
 * horizon and, with a perspective camera, the frustum's four side planes
 * through the eye (unit inward normals in the horizon frame, from
 * frame.view_proj's rows: w + x, w - x, w + y, w - y). A direction behind
 * the camera is outside all four. */
typedef struct sky_view_bounds {
    double planes[4][3];
    int sides; /* 4, or 0 for the all-sky image */
} sky_view_bounds;
sky_view_bounds sky_camera_bounds(const sky_frame *f);
/* The least of the sines of the horizon direction d's angles from the
 * horizon and the side planes: negative outside. */
double sky_camera_inside_by(const sky_view_bounds *b, const double d[3]);
/* The all-sky image in the viewport: aspect and pixel_angle (the caller
 * clears the viewport). */
void sky_camera_fisheye(sky_core *s, const GLint viewport[4]);
/* A horizon-frame direction in the host's world (horizon_to_world). */
void sky_camera_to_world(const sky_core *s, const float h[3], float w[3]);
/* Checks cfg.horizon_to_world: all zero (identity) or orthonormal
 * columns. Fills out (identity for zero); 0, or -1 if not a rotation. */
int sky_camera_horizon_to_world(const float m[9], float out[9]);

#endif /* SKY_CAMERA_H */
