/*
 * What the sets of points share (points.c): the catalogue stars and the
 * planets are drawn by stars.vert/.frag from the same vertex layout and
 * uniform rows, sized and lit alike.
 */
#ifndef SKY_POINTS_H
#define SKY_POINTS_H

#include "core.h"
#include "gl/gl.h"

/* stars.vert's uniform rows for a set of points: the sky_point_frame
 * `member` of the layer's state_type (stars, planets: each its own). */
#define SKY_POINT_UNIFORMS(state_type, member)                                                              \
    SKY_US("u_star_rot", SKY_U_M4, state_type, member.rot),                                                 \
        SKY_US("u_star_aberration", SKY_U_F3, state_type, member.aberration),                               \
        SKY_US("u_star_size", SKY_U_F4, state_type, member.size),                                           \
        SKY_US("u_star_pressure", SKY_U_F3, state_type, member.pressure),                                   \
        SKY_USL("u_star_flux_scale", SKY_U_F1, state_type, member.flux_scale, 1u),                          \
        SKY_US("u_star_extinction", SKY_U_F3, state_type, member.extinction),                               \
        SKY_US("u_star_shell", SKY_U_F3, state_type, member.shell), SKY_US("u_star_seed", SKY_U_F1, state_type, member.seed), \
        SKY_US("u_star_occulter", SKY_U_F4, state_type, member.occulter)
/* For the view being drawn, what every set of points shares: the
 * sizes of Mueller eq. 9 (q, glare c_k, largest radius in pixels, control
 * magnitude), the refraction's pressure factor and the faintest V drawn,
 * the peak luminance of a V = 0 point on its PSF (eq. 10, kcd/m^2), the
 * zenith optical depths and the shell of eq. 11, and the moon's disc that
 * hides them, and the seed of the set's scintillation clock (its phase,
 * sky_scintillation_advance). Leaves rot and aberration, the set's own. */
void sky_point_view(sky_core *s, float point_max, double scintillation, sky_point_frame *p);
/* A point's vertex for stars.vert: a_pos (scintillation seed, the share of
 * the twinkle a disc averages away), a_dir (3), a_color (rgb, V). */
#define SKY_POINT_FLOATS 9
/* A set of points' scintillation clock, a phase wrapped in 0..1,
 * moved on by dt seconds. */
double sky_scintillation_advance(double phase, double dt);
/* Whether a point of magnitude vmag at the horizon direction d
 * (before refraction) can show in this view: above the horizon and within
 * the frustum's sides, with refraction, aberration and its point's radius
 * (p's sizes) for margin. */
int sky_point_in_view(const sky_core *s, const sky_point_frame *p, const double d[3], double vmag);
/* Draws count points of that layout from buffer with program. */
void sky_points_draw(sky_core *s, const sky_program *program, GLuint buffer, GLuint elements, int count);
/* The faintest V a point source is drawn at: the naked eye's
 * limit against the zenith's sky (Schaefer 1990), as the finished frame
 * has it (sky.c keeps it in frame.naked_eye_limit after every layer's
 * frame). Whatever the view's field: Mueller's PSF already gives a zoomed
 * view's points more contrast, as binoculars do, but not the points the
 * eye would not see. */
double sky_point_limit(const sky_core *s);
/* The margin in radians around a point of magnitude vmag: what moves it
 * from its catalogue place on the way to the screen, and its radius. */
double sky_point_margin(const sky_frame *f, const sky_point_frame *p, double vmag);

#endif /* SKY_POINTS_H */
