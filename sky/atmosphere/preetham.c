/*
 * The Preetham atmosphere: Preetham, Shirley & Smits, "A practical
 * analytic model for daylight" (SIGGRAPH 1999). The Perez et al. (1993)
 * distribution F(theta, gamma) (eq. 3) for the luminance Y and the
 * chromaticities x and y, each normalised by its zenith value (eq. 4),
 * with the coefficients and zenith values fitted to turbidity
 * (appendix A.2). All per frame on the CPU; the shader only evaluates F.
 *
 * Outside its fit: the model was fitted for turbidity 2..10 with the sun
 * above the horizon. Turbidity is CLAMPED into 2..10 (below 2 the zenith
 * darkening factor 1 + A e^B approaches zero; above 10 the zenith
 * luminance at a horizon sun turns negative). For a sun below the horizon
 * the distribution keeps the horizon sun's shape (theta_s held at 90
 * degrees, so Y_z stays positive) and the luminance FADES by a decade
 * every 3 degrees of depression, the measured twilight decline the
 * gradient path uses too: continuous at 0 degrees, positive everywhere.
 */
#include "atmosphere.h"

#include <math.h>

static const sky_uniform_desc preetham_uniforms[] = {
    SKY_UF("u_perez_a", SKY_U_F3, perez[0]), SKY_UF("u_perez_b", SKY_U_F3, perez[1]),
    SKY_UF("u_perez_c", SKY_U_F3, perez[2]), SKY_UF("u_perez_d", SKY_U_F3, perez[3]),
    SKY_UF("u_perez_e", SKY_U_F3, perez[4]), SKY_UF("u_perez_zenith", SKY_U_F3, perez_zenith),
};
const sky_snippet sky_preetham_snippet = {"SKY_HAS_PREETHAM", "preetham.glsl", preetham_uniforms,
                                          SKY_UNIFORM_COUNT(preetham_uniforms), NULL};

#define PREETHAM_TURBIDITY_MIN 2.0
#define PREETHAM_TURBIDITY_MAX 10.0

/* Appendix A.2: each Perez coefficient is slope * T + offset, for Y, x, y. */
static const double perez_fit[3][5][2] = {
    {{0.1787, -1.4630}, {-0.3554, 0.4275}, {-0.0227, 5.3251}, {0.1206, -2.5771}, {-0.0670, 0.3703}},
    {{-0.0193, -0.2592}, {-0.0665, 0.0008}, {-0.0004, 0.2125}, {-0.0641, -0.8989}, {-0.0033, 0.0452}},
    {{-0.0167, -0.2608}, {-0.0950, 0.0092}, {-0.0079, 0.2102}, {-0.0441, -1.6537}, {-0.0109, 0.0529}},
};
/* Zenith chromaticity: [T^2 T 1] M [theta^3 theta^2 theta 1]^T. */
static const double zenith_x[3][4] = {
    {0.00166, -0.00375, 0.00209, 0.0}, {-0.02903, 0.06377, -0.03202, 0.00394}, {0.11693, -0.21196, 0.06052, 0.25886}};
static const double zenith_y[3][4] = {
    {0.00275, -0.00610, 0.00317, 0.0}, {-0.04214, 0.08970, -0.04153, 0.00516}, {0.15346, -0.26756, 0.06670, 0.26688}};

static double zenith_chromaticity(const double m[3][4], double T, double theta)
{
    double t[3] = {T * T, T, 1.0}, th[4] = {theta * theta * theta, theta * theta, theta, 1.0}, acc = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) acc += t[i] * m[i][j] * th[j];
    return acc;
}

double sky_preetham_turbidity(float requested)
{
    double t = requested == 0.0f ? 2.5 : requested;
    return sky_clampd(t, PREETHAM_TURBIDITY_MIN, PREETHAM_TURBIDITY_MAX);
}

void sky_preetham_frame(sky_core *s)
{
    sky_frame *f = &s->frame;
    double T = sky_preetham_turbidity(s->cfg.turbidity);
    double altitude = f->sun_altitude;
    double theta_s = 0.5 * SKY_PI - sky_clampd(altitude, 0.0, 0.5 * SKY_PI);
    double coef[3][5];
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 5; k++) {
            coef[c][k] = perez_fit[c][k][0] * T + perez_fit[c][k][1];
            f->perez[k][c] = (float)coef[c][k];
        }
    /* eq. A.2 zenith luminance, kcd/m^2; chi < pi/2 for every T >= 0 */
    double chi = (4.0 / 9.0 - T / 120.0) * (SKY_PI - 2.0 * theta_s);
    double zenith[3] = {(4.0453 * T - 4.9710) * tan(chi) - 0.2155 * T + 2.4192,
                        zenith_chromaticity(zenith_x, T, theta_s), zenith_chromaticity(zenith_y, T, theta_s)};
    double fade = altitude >= 0.0 ? 1.0 : pow(10.0, sky_clampd(altitude * 180.0 / SKY_PI, -90.0, 0.0) / 3.0);
    zenith[0] *= fade;
    for (int c = 0; c < 3; c++) {
        /* F(0, theta_s): the zenith itself, gamma = theta_s */
        double F0 = (1.0 + coef[c][0] * exp(coef[c][1])) *
                    (1.0 + coef[c][2] * exp(coef[c][3] * theta_s) + coef[c][4] * cos(theta_s) * cos(theta_s));
        f->perez_zenith[c] = (float)(zenith[c] / F0);
    }
}

void sky_preetham_eval(const sky_frame *f, const double d[3], double rgb[3])
{
    double cos_theta = fmax(d[1], 1e-3);
    double cos_gamma = sky_clampd(d[0] * f->sun_dir[0] + d[1] * f->sun_dir[1] + d[2] * f->sun_dir[2], -1.0, 1.0);
    double gamma = acos(cos_gamma), Yxy[3];
    for (int c = 0; c < 3; c++)
        Yxy[c] = f->perez_zenith[c] * (1.0 + f->perez[0][c] * exp(f->perez[1][c] / cos_theta)) *
                 (1.0 + f->perez[2][c] * exp(f->perez[3][c] * gamma) + f->perez[4][c] * cos_gamma * cos_gamma);
    double y = fmax(Yxy[2], 1e-4);
    double XYZ[3] = {Yxy[1] / y * Yxy[0], Yxy[0], (1.0 - Yxy[1] - Yxy[2]) / y * Yxy[0]};
    sky_xyz_to_linear_srgb(XYZ, rgb);
    for (int i = 0; i < 3; i++) rgb[i] = fmax(rgb[i], 0.0);
}
