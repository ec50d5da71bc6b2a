/*
 * What every set of points shares (the catalogue stars, the planets): the
 * size and light of a point after Mueller et al. 2012 (eq. 9, 10), the
 * air's extinction and the moon's disc hiding them, the scintillation
 * clock, whether a point can show in the view, the naked eye's limit
 * against the finished sky, and the draw through stars.vert.
 */
#include "camera.h"
#include "exposure.h"
#include "layer.h"
#include "points.h"
#include "atmosphere/atmosphere.h"

#include <math.h>

/* Illuminance of a V = 0 point (light_units.h), in klx so that luminance comes
 * out in kcd/m^2. */
#define POINT_E0_KLX SKY_V0_ILLUMINANCE_KLX
/* Mueller's minimum billboard radius, sqrt(2) pixels (eq. 9). */
#define POINT_Q_PX 1.41421356
/* Glare radius coefficient c_k in pixels: Sirius at m_a = 4 gets ~17 px. */
#define POINT_GLARE_CK_PX 1.5
/* Integral of T(l) = 2l^3 - 3l^2 + 1 over the unit disc: 2 pi (2/5 - 3/4 +
 * 1/2) = 0.3 pi. Dividing by it makes a point's light add up to its
 * illuminance, whatever its pixel size. */
#define POINT_PSF_INTEGRAL (0.3 * SKY_PI)
/* The scintillation clock (stars.frag): RATE new random values a second,
 * counted modulo PERIOD so the float uniform keeps its fraction after
 * years of running. */
#define SCINTILLATION_RATE 10.0
#define SCINTILLATION_PERIOD 997.0
/* what moves a point from its catalogue place on the way to the screen:
 * refraction (under 0.6 degrees) and aberration (20"), in radians, with
 * margin */
#define POINT_MOTION_MARGIN (1.0 * SKY_PI / 180.0)

double sky_scintillation_advance(double phase, double dt)
{
    return sky_phase_advance(phase, SCINTILLATION_RATE / SCINTILLATION_PERIOD, dt);
}

double sky_point_limit(const sky_core *s)
{
    /* the sky at the zenith as the paths' CPU twin has it (after every
     * layer's frame: eclipse, light pollution and night glows included) */
    const double up[3] = {0.0, 1.0, 0.0};
    double z[3];
    sky_atmosphere_radiance(s, up, z);
    return sky_naked_eye_limit(0.2126 * z[0] + 0.7152 * z[1] + 0.0722 * z[2]);
}

void sky_point_view(sky_core *s, float point_max, double scintillation, sky_point_frame *p)
{
    const sky_frame *f = &s->frame;
    const sky_astro *a = &s->astro;
    float m_a = s->cfg.star_control_magnitude > 0.0f ? sky_clampf(s->cfg.star_control_magnitude, 1.0f, 10.0f) : 4.0f;
    p->size.q = (float)POINT_Q_PX;
    p->size.glare_ck = (float)POINT_GLARE_CK_PX;
    p->size.max_radius = 0.5f * point_max - 1.0f;
    p->size.control_magnitude = m_a;
    p->pressure[0] = (float)a->pressure_factor;
    p->pressure[1] = f->naked_eye_limit;
    p->pressure[2] = 0.0f;
    /* eq. 10 in physical units: peak luminance of a V = 0 point on a PSF
     * of radius q pixels (pixel_angle radians each). No day-night fade:
     * a point's light is added to the sky as it is, and what the naked eye
     * would not see against the sky is left out (pressure[1]). */
    double r = POINT_Q_PX * f->pixel_angle;
    double peak = POINT_E0_KLX * pow(2.512, m_a - 4.0) / (POINT_PSF_INTEGRAL * r * r);
    p->flux_scale = (float)(peak * f->star_local_gain);
    /* the air above the observer, as the atmosphere stage has it */
    for (int i = 0; i < 3; i++) {
        p->extinction[i] = f->night_depth[i];
        p->shell[i] = f->night_shell[i];
    }
    /* The moon hides what is behind its disc, whatever the sky's
     * brightness (the disc itself only adds light by day, moon.c, so it
     * cannot hide them): the test is in true directions, at the disc's
     * drawn size. */
    p->occulter[0] = p->occulter[1] = p->occulter[2] = 0.0f;
    p->occulter[3] = 2.0f;
    if (s->features & SKY_MOON) {
        for (int i = 0; i < 3; i++) p->occulter[i] = (float)a->moon.dir_geometric[i];
        p->occulter[3] = (float)cos(sky_moon_drawn_scale(s) * a->moon_topo_semidiameter);
    }
    /* the scintillation clock, in random values */
    p->seed = (float)(SCINTILLATION_PERIOD * scintillation);
}

void sky_points_draw(sky_core *s, const sky_program *program, GLuint buffer, GLuint elements, int count)
{
    static const sky_gl_layout layout = {SKY_POINT_FLOATS * sizeof(float),
                                         {{2, GL_FLOAT, GL_FALSE, 0},
                                          {3, GL_FLOAT, GL_FALSE, 2 * sizeof(float)},
                                          {4, GL_FLOAT, GL_FALSE, 5 * sizeof(float)}}};
    sky_program_apply(s, program);
    sky_gl_vertices_bind(s, buffer, elements, &layout);
    sky_gl_program_point_size(s, 1);
    if (elements)
        sky_gl_draw_elements(s, GL_POINTS, 0, count);
    else
        sky_gl_draw_arrays(s, GL_POINTS, 0, count);
    sky_gl_program_point_size(s, 0);
}

/* The radius in pixels of a star's point (stars.vert's k, Mueller eq. 9):
 * q, or for a star brighter than the control magnitude its glare's
 * c_k sqrt(I_G); at most the largest point. */
static double point_radius(const sky_point_frame *p, double vmag)
{
    double glare = pow(2.512, p->size.control_magnitude - vmag - 0.167) - 1.0;
    return fmin(fmax(p->size.q, p->size.glare_ck * sqrt(fmax(glare, 0.0))), p->size.max_radius);
}

double sky_point_margin(const sky_frame *f, const sky_point_frame *p, double vmag)
{
    return POINT_MOTION_MARGIN + (point_radius(p, vmag) + 1.0) * f->pixel_angle;
}

int sky_point_in_view(const sky_core *s, const sky_point_frame *p, const double d[3], double vmag)
{
    sky_view_bounds b = sky_camera_bounds(&s->frame);
    return sky_camera_inside_by(&b, d) >= -sky_point_margin(&s->frame, p, vmag);
}
