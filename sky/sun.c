/*
 * The sun: how much of its light comes through the atmosphere, and the
 * camera-facing quad that draws its limb-darkened disc (Roden & Parberry
 * sec. 2; Schneegans et al. eq. 1). Where it is comes from astro.c.
 */
#include "sky_internal.h"

#include <math.h>
#include <string.h>

/* Disc-centre luminance of the sun above the atmosphere, about 2.0e9 cd/m^2
 * (mean disc luminance 1.6e9 cd/m^2 divided by the mean of the u = 0.6
 * limb-darkening profile, 0.8). In kcd/m^2. */
#define SKY_SUN_LUMINANCE 2.0e6
/* The quad reaches 16 radii: the glare is windowed to zero there. */
#define SKY_SUN_QUAD_RADII 16.0
/* The corona's brightness relative to the sun's mean disc is Baumbach's
 * (1937) 1e-6 (0.0532 r^-2.5 + 1.425 r^-7 + 2.565 r^-17), r in solar radii
 * (4e-6 at the limb). sun.frag evaluates the bracket; this is the factor
 * before it: 1e-6 times the mean disc, 0.8 of the centre's luminance. In
 * kcd/m^2. */
#define SKY_CORONA_SCALE (1e-6 * 0.8 * SKY_SUN_LUMINANCE)

static const sky_uniform_desc sun_uniforms[] = {
    SKY_UF("u_sun_radius", SKY_U_F1, sun_radius),
    SKY_UF("u_sun_luminance", SKY_U_F1, sun_luminance),
    SKY_UF("u_sun_transmittance", SKY_U_F3, sun_transmittance),
    SKY_UF("u_sun_true_dir", SKY_U_F3, sun_true_dir),
    SKY_UF("u_eclipse_sun", SKY_U_F4, eclipse_sun),
    SKY_UF("u_eclipse_moon_dir", SKY_U_F3, eclipse_moon_dir),
};
/* Uniform rows only: sun.frag is the program's main, not a snippet. */
const sky_snippet sky_sun_snippet = {NULL, NULL, sun_uniforms, (int)(sizeof sun_uniforms / sizeof sun_uniforms[0])};

void sky_sun_transmittance(double altitude, float out[3])
{
    /* Zenith optical depths at 680, 550, 440 nm: Rayleigh (Bruneton's
     * coefficients times an 8 km scale height) plus aerosol of optical
     * depth 0.1 at 550 nm with Angstrom exponent 1.3. */
    static const double tau[3] = {0.046 + 0.076, 0.108 + 0.100, 0.265 + 0.134};
    /* Kasten & Young (1989) air mass, fitted down to the horizon. Below it
     * the fit is meaningless (its air mass peaks near -2 degrees and falls
     * again towards its pole at -6.08, so the beam would brighten as the
     * sun sinks); a ray there meets the ground, and what still reaches the eye is the
     * rim of a setting disc, seen along the horizon: hold the horizon's
     * value. How much of the disc is left is sky_disc_above_horizon's. */
    double h_deg = sky_clampd(altitude * 180.0 / SKY_PI, 0.0, 90.0);
    double airmass = 1.0 / (sin(h_deg * SKY_PI / 180.0) + 0.50572 * pow(h_deg + 6.07995, -1.6364));
    for (int i = 0; i < 3; i++) out[i] = (float)exp(-tau[i] * airmass);
}

double sky_disc_above_horizon(double altitude, double radius)
{
    /* a disc whose centre is d radii above a straight horizon shows
     * 1 - (acos d - d sqrt(1 - d^2)) / pi of its area (circular segment) */
    if (!(radius > 0.0)) return altitude >= 0.0 ? 1.0 : 0.0;
    double d = sky_clampd(altitude / radius, -1.0, 1.0);
    return 1.0 - (acos(d) - d * sqrt(fmax(1.0 - d * d, 0.0))) / SKY_PI;
}

int sky_disc_grid_create(sky *s, sky_disc_grid *g, const char *what, char *err, size_t err_len)
{
    /* two triangles per cell, rows of SKY_DISC_GRID + 1 vertices */
    unsigned short idx[SKY_DISC_GRID_INDICES];
    int k = 0;
    for (int j = 0; j < SKY_DISC_GRID; j++)
        for (int i = 0; i < SKY_DISC_GRID; i++) {
            unsigned short a = (unsigned short)(j * (SKY_DISC_GRID + 1) + i), b = (unsigned short)(a + 1);
            unsigned short c = (unsigned short)(a + SKY_DISC_GRID + 1), d = (unsigned short)(c + 1);
            idx[k++] = a, idx[k++] = b, idx[k++] = c;
            idx[k++] = b, idx[k++] = d, idx[k++] = c;
        }
    static const float zero[SKY_DISC_GRID_VERTICES * 5];
    g->vertices = sky_buffer_create(s, GL_ARRAY_BUFFER, zero, sizeof zero, GL_DYNAMIC_DRAW);
    g->indices = sky_buffer_create(s, GL_ELEMENT_ARRAY_BUFFER, idx, sizeof idx, GL_STATIC_DRAW);
    if (!g->vertices || !g->indices) {
        sky_format(err, err_len, "glGenBuffers failed for the %s", what);
        return -1;
    }
    return 0;
}

void sky_disc_grid_update(sky *s, const sky_disc_grid *g, const double centre[3], const double x[3],
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
    const sky_gl *gl = &s->gl;
    gl->glBindBuffer(GL_ARRAY_BUFFER, g->vertices);
    gl->glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)sizeof v, v, GL_DYNAMIC_DRAW);
}

int sky_sun_create(sky *s, char *err, size_t err_len) { return sky_disc_grid_create(s, &s->sun_grid, "sun", err, err_len); }

void sky_sun_frame(sky *s)
{
    sky_frame *f = &s->frame;
    const sky_astro *a = &s->astro;
    f->sun_radius = (float)a->sun_topo_semidiameter;
    f->sun_luminance = (float)SKY_SUN_LUMINANCE;
    /* the disc is drawn where refraction puts each of its points
     * (sun.frag): it needs the centre's true direction */
    for (int i = 0; i < 3; i++) f->sun_true_dir[i] = (float)a->sun.dir_geometric[i];
    /* A solar eclipse: sun.frag hides what lies behind the moon's true
     * disc. Both discs take their true sizes, the one scale at which the
     * contacts fall at the right times (moon.c draws the moon at it near
     * the sun). The glare keeps the uncovered light's share, and the
     * corona shows once the sun's last 10 % go. */
    for (int i = 0; i < 3; i++) f->eclipse_moon_dir[i] = (float)a->moon.dir_geometric[i];
    f->eclipse_sun[0] = (float)a->moon_topo_semidiameter;
    f->eclipse_sun[1] = (float)a->solar_flux_fraction;
    f->eclipse_sun[2] = (float)(SKY_CORONA_SCALE * sky_smoothstep(0.9, 0.999, a->solar_obscuration));
    f->eclipse_sun[3] = 0.0f;
}

int sky_sun_visible(const sky *s)
{
    /* The whole quad, glare included, below the horizon: nothing to draw. */
    return (s->features & SKY_SUN) && s->sun_grid.vertices &&
           s->frame.sun_altitude > -(float)SKY_SUN_QUAD_RADII * s->frame.sun_radius;
}

void sky_sun_update_quad(sky *s)
{
    const sky_astro *a = &s->astro;
    double d[3] = {a->sun.dir[0], a->sun.dir[1], a->sun.dir[2]};
    /* Tangent basis around the sun: any vector not parallel to d. */
    double up[3] = {0.0, 1.0, 0.0};
    if (fabs(d[1]) > 0.9) up[0] = 1.0, up[1] = 0.0;
    double t[3] = {up[1] * d[2] - up[2] * d[1], up[2] * d[0] - up[0] * d[2], up[0] * d[1] - up[1] * d[0]};
    double tl = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int i = 0; i < 3; i++) t[i] /= tl;
    double b[3] = {d[1] * t[2] - d[2] * t[1], d[2] * t[0] - d[0] * t[2], d[0] * t[1] - d[1] * t[0]};
    sky_disc_grid_update(s, &s->sun_grid, d, t, b, tan(SKY_SUN_QUAD_RADII * s->frame.sun_radius), 1.0);
}
