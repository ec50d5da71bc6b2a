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
 * degrees, so Y_z stays positive) and its luminance is scaled so that the
 * sky's illuminance on a horizontal surface follows MEASURED twilight
 * (twilight_log10_klx below): 0.8 klx at sunset, 3.4 lx at -6 and 0.008 lx at
 * -12 degrees, then into the night floor (atmosphere.c). The fit's own
 * horizon sky is far brighter (10.7 klx at turbidity 2.5), so over the
 * sun's last few degrees above the horizon the scale eases from 1 (the
 * published model, untouched by day) down to the measured value, with the
 * twilight's slope at the horizon: continuous, and with a continuous
 * slope, through sunset, positive everywhere.
 */
#include "atmosphere.h"
#include "layer.h"
#include "moonlight.h"

#include <math.h>

static const sky_uniform_desc preetham_uniforms[] = {
    SKY_UF("u_perez_a", SKY_U_F3, perez[0]), SKY_UF("u_perez_b", SKY_U_F3, perez[1]),
    SKY_UF("u_perez_c", SKY_U_F3, perez[2]), SKY_UF("u_perez_d", SKY_U_F3, perez[3]),
    SKY_UF("u_perez_e", SKY_U_F3, perez[4]), SKY_UL("u_perez_zenith", SKY_U_F3, perez_zenith, 1u),
    SKY_UL("u_perez_moon_zenith", SKY_U_F3, perez_moon_zenith, 1u), SKY_UF("u_moon_tint", SKY_U_F3, moon_tint),
};
/* (in the vertex stage too: R-P's stars take its transmittance per point,
 * flicker.vert) */
const sky_snippet sky_preetham_snippet = {"SKY_HAS_PREETHAM", "preetham.glsl", preetham_uniforms,
                                          SKY_UNIFORM_COUNT(preetham_uniforms), "preetham.glsl", NULL, NULL};

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

/* The sky's illuminance on a horizontal surface in twilight, klx, for the
 * sun h_deg <= 0 degrees high: log10 E quadratic in h through three
 * measured clear-sky values: the IES clear sky's diffuse illuminance with
 * the sun on the horizon, 0.8 klx (IES RP-21, E = 0.8 + 15.5 sqrt(sin h)
 * klx), and Bond & Henderson's (1963) 3.4 lx at -6 (civil) and 0.008 lx at
 * -12 degrees (nautical). It falls a decade per 2.7 degrees at the horizon,
 * steepening to one per 2.1 at -12 (about 2.3 between -6 and -12, as the
 * measurements do); below about -15 it is under the night floor, which
 * takes over. Also returns d log10 E / dh at the horizon (decades per
 * degree), which the ease above the horizon continues. */
static double twilight_log10_klx(double h_deg, double *slope_at_horizon)
{
    const double L0 = log10(0.8), d6 = log10(3.4e-3) - L0, d12 = log10(8.0e-6) - L0;
    /* L = L0 + b h + c h^2 with L(-6) - L0 = d6, L(-12) - L0 = d12 */
    const double c = (d12 - 2.0 * d6) / 72.0, b = (36.0 * c - d6) / 6.0;
    if (slope_at_horizon) *slope_at_horizon = b;
    /* beyond -30 degrees the term is 1e-9 of the night floor: hold it there */
    double h = sky_clampd(h_deg, -30.0, 0.0);
    return L0 + b * h + c * h * h;
}

/* The illuminance (klx) on a horizontal surface of the distribution with
 * the sun on the horizon (theta_s = 90 degrees), for the Perez
 * coefficients of Y and Y_z / F(0, theta_s) (eq. 3, 4): E = int Y cos theta
 * domega. Gauss-Legendre in cos theta (8 nodes on 0..1) times 48 azimuths
 * over the half of the sky on one side of the sun's vertical (the other is
 * its mirror image). Within 0.3 % of a fine midpoint sum for T in 2..10. */
static double horizon_sun_illuminance(const double coef[5], double Y_over_F0)
{
    static const double x[8] = {0.0198550718, 0.1016667613, 0.2372337950, 0.4082826788,
                                0.5917173212, 0.7627662050, 0.8983332387, 0.9801449282};
    static const double w[8] = {0.0506142681, 0.1111905172, 0.1568533229, 0.1813418917,
                                0.1813418917, 0.1568533229, 0.1111905172, 0.0506142681};
    enum { AZIMUTHS = 48 };
    double e = 0.0;
    for (int k = 0; k < 8; k++) {
        double mu = x[k], sin_theta = sqrt(1.0 - mu * mu), ring = 0.0;
        for (int a = 0; a < AZIMUTHS; a++) {
            /* the sun at azimuth 0 on the horizon: cos gamma = sin theta cos phi */
            double phi = SKY_PI * (a + 0.5) / AZIMUTHS;
            double cos_gamma = sky_clampd(sin_theta * cos(phi), -1.0, 1.0), gamma = acos(cos_gamma);
            ring += (1.0 + coef[0] * exp(coef[1] / mu)) *
                    (1.0 + coef[2] * exp(coef[3] * gamma) + coef[4] * cos_gamma * cos_gamma);
        }
        e += w[k] * mu * ring * (2.0 * SKY_PI / AZIMUTHS);
    }
    return Y_over_F0 * e;
}

/* The scale of Preetham's luminance for a sun at altitude h (radians):
 * 1 by day; at and below the horizon the measured twilight over the fit's
 * own horizon-sun illuminance E0 (T's). In between, over the sun's last
 * h1 degrees, log10 of the scale is the parabola L (1 - h / h1)^2 from its
 * horizon value L = log10(0.8 klx / E0) to 0: it arrives flat, and with
 * h1 = 2 |L| / m it leaves the horizon with the twilight's own slope m, so
 * the time-lapse has no kink at sunset, and it is monotonic. h1 is 6
 * degrees at T 2.5 and a fraction of one at T 10, whose horizon sky is
 * already near 0.8 klx. A fit darker than measured is left alone (L held
 * <= 0): no brightening. */
static double twilight_scale(double altitude, double horizon_klx)
{
    double h_deg = altitude * 180.0 / SKY_PI, m;
    double L = fmin(twilight_log10_klx(0.0, &m) - log10(fmax(horizon_klx, 1e-30)), 0.0);
    if (h_deg <= 0.0) return pow(10.0, L + twilight_log10_klx(h_deg, NULL) - twilight_log10_klx(0.0, NULL));
    double h1 = 2.0 * -L / m;
    if (h_deg >= h1) return 1.0;
    double t = 1.0 - h_deg / h1;
    return pow(10.0, L * t * t);
}

/* Appendix A.2's coefficients for turbidity T, per (Y, x, y). */
static void perez_coefficients(double T, double coef[3][5])
{
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 5; k++) coef[c][k] = perez_fit[c][k][0] * T + perez_fit[c][k][1];
}

/* The zenith values (Y in kcd/m^2 for the sun's light, with the twilight
 * scale; x, y) over F(0, theta_s) for a light at this altitude. */
static void perez_zenith_at(sky_frame *f, const double coef[3][5], double T, double altitude, double out[3])
{
    altitude = isfinite(altitude) ? altitude : 0.0;
    double theta_s = 0.5 * SKY_PI - sky_clampd(altitude, 0.0, 0.5 * SKY_PI);
    /* eq. A.2 zenith luminance, kcd/m^2; chi < pi/2 for every T >= 0 */
    double chi = (4.0 / 9.0 - T / 120.0) * (SKY_PI - 2.0 * theta_s);
    double zenith[3] = {(4.0453 * T - 4.9710) * tan(chi) - 0.2155 * T + 2.4192,
                        zenith_chromaticity(zenith_x, T, theta_s), zenith_chromaticity(zenith_y, T, theta_s)};
    double F0[3];
    for (int c = 0; c < 3; c++)
        /* F(0, theta_s): the zenith itself, gamma = theta_s */
        F0[c] = (1.0 + coef[c][0] * exp(coef[c][1])) *
                (1.0 + coef[c][2] * exp(coef[c][3] * theta_s) + coef[c][4] * cos(theta_s) * cos(theta_s));
    /* The twilight scale needs the fit's horizon-sun illuminance: only
     * while the light is within a few degrees of the horizon or below it
     * (the ease above ends at h1 = 2 |log10(0.8 klx / E0)| / m: 6.9
     * degrees at T 2, the brightest horizon sky, 15 klx). It depends on
     * T alone, which a sky keeps: the 384-point quadrature (some 30 us)
     * runs once, not every frame. */
    double scale = 1.0;
    if (altitude < 10.0 * SKY_PI / 180.0) {
        if (f->perez_horizon_t != T) {
            /* eq. A.2 at theta_s = 90 degrees: chi = 0, tan chi = 0 */
            double Yz0 = -0.2155 * T + 2.4192;
            double F00 = (1.0 + coef[0][0] * exp(coef[0][1])) * (1.0 + coef[0][2] * exp(coef[0][3] * 0.5 * SKY_PI));
            f->perez_horizon_klx = horizon_sun_illuminance(coef[0], Yz0 / F00);
            f->perez_horizon_t = T;
        }
        scale = twilight_scale(altitude, f->perez_horizon_klx);
    }
    zenith[0] *= scale;
    for (int c = 0; c < 3; c++) out[c] = zenith[c] / F0[c];
}

void sky_preetham_frame(sky_core *s)
{
    sky_frame *f = &s->frame;
    double T = sky_preetham_turbidity(s->cfg.turbidity), coef[3][5], zenith[3];
    perez_coefficients(T, coef);
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 5; k++) f->perez[k][c] = (float)coef[c][k];
    /* (the cast: C before C23 makes no implicit double (*)[5] -> const double (*)[5]) */
    perez_zenith_at(f, (const double(*)[5])coef, T, f->sun_altitude, zenith);
    for (int c = 0; c < 3; c++) f->perez_zenith[c] = (float)zenith[c];
}

/* The moonlit sky (Jensen et al. 2001: the day sky's model lit by the
 * moon): the distribution for a light at the moon's place, its zenith
 * luminance scaled by the moon's light over the sun's above the air
 * (phase, distance), and the moon's redder colour per channel (u_moon_tint,
 * of unit luminance). Only while the sun is down: by day it is a
 * millionth of the sky, and the shader skips it (faded in over the sun's
 * last 5 degrees). Returns the zenith's luminance, kcd/m^2. */
double sky_preetham_moon(sky_core *s)
{
    sky_frame *f = &s->frame;
    for (int c = 0; c < 3; c++) f->perez_moon_zenith[c] = f->moon_tint[c] = 0.0f;
    double night = 1.0 - sky_smoothstep(0.0, 5.0, f->sun_altitude * 180.0 / SKY_PI);
    if (!(s->features & SKY_MOON) || night <= 0.0) return 0.0;
    double T = sky_preetham_turbidity(s->cfg.turbidity), coef[3][5], zenith[3], top[3], ratio[3];
    perez_coefficients(T, coef);
    perez_zenith_at(f, (const double(*)[5])coef, T, s->astro.moon.alt, zenith);
    sky_moon_light_above_air(s, top);
    for (int c = 0; c < 3; c++) ratio[c] = top[c] / s->sun_irradiance_klx[c];
    double r = 0.2126 * ratio[0] + 0.7152 * ratio[1] + 0.0722 * ratio[2];
    if (!(r > 0.0)) return 0.0;
    zenith[0] *= r * night;
    for (int c = 0; c < 3; c++) {
        f->perez_moon_zenith[c] = (float)zenith[c];
        f->moon_tint[c] = (float)(ratio[c] / r);
    }
    static const double up[3] = {0.0, 1.0, 0.0};
    double rgb[3];
    sky_preetham_moon_eval(f, up, rgb);
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

/* F(theta, gamma) for a light along l with the given zenith values, in
 * linear sRGB (eq. 3; xyY -> XYZ -> linear sRGB). */
static void perez_rgb(const sky_frame *f, const double d[3], const float l[3], const float zenith[3], double rgb[3])
{
    double cos_theta = fmax(d[1], 1e-3);
    double cos_gamma = sky_clampd(d[0] * l[0] + d[1] * l[1] + d[2] * l[2], -1.0, 1.0);
    double gamma = acos(cos_gamma), Yxy[3];
    for (int c = 0; c < 3; c++)
        Yxy[c] = zenith[c] * (1.0 + f->perez[0][c] * exp(f->perez[1][c] / cos_theta)) *
                 (1.0 + f->perez[2][c] * exp(f->perez[3][c] * gamma) + f->perez[4][c] * cos_gamma * cos_gamma);
    double y = fmax(Yxy[2], 1e-4);
    double XYZ[3] = {Yxy[1] / y * Yxy[0], Yxy[0], (1.0 - Yxy[1] - Yxy[2]) / y * Yxy[0]};
    sky_xyz_to_linear_srgb(XYZ, rgb);
    for (int i = 0; i < 3; i++) rgb[i] = fmax(rgb[i], 0.0);
}

void sky_preetham_eval(const sky_frame *f, const double d[3], double rgb[3])
{
    perez_rgb(f, d, f->sun_dir, f->perez_zenith, rgb);
}

void sky_preetham_moon_eval(const sky_frame *f, const double d[3], double rgb[3])
{
    for (int i = 0; i < 3; i++) rgb[i] = 0.0;
    if (!(f->perez_moon_zenith[0] > 0.0f)) return;
    perez_rgb(f, d, f->moon_dir, f->perez_moon_zenith, rgb);
    for (int i = 0; i < 3; i++) rgb[i] *= f->moon_tint[i];
}
