/*
 * The analytic Rayleigh + Mie atmosphere: single scattering in closed
 * form, no ray march.
 *
 * For one exponential species seen from the ground, let u = exp(-z/H) be
 * the fraction of the vertical column above height z. A point at u sees
 * the eye through optical depth A_v (1 - u) and the sun through A_s u,
 * where A_v and A_s are the full slant depths from the observer toward
 * the view and the sun (vertical depth times a Chapman air mass). The
 * in-scattered radiance integrates in u exactly:
 *     L = E P tau_v int_0^1 exp(-A_v (1 - u) - A_s u) du
 *       = E P tau_v (e^-A_s - e^-A_v) / (A_v - A_s)
 * (tau_v: the species' scattering depth along the view). With several
 * species (Rayleigh H 8 km, Mie 1.2 km, ozone) the same u stands for all
 * of them: exact for one species, an approximation for the mixture that
 * sky-bench measures against the reference. The difference quotient is
 * evaluated without cancellation (e^-min times (1 - e^-x)/x).
 *
 * Limits, by design: no multiple scattering and no ground bounce, and a
 * sun below the horizon reaches the sky only through the ground's slant
 * column, so twilight falls too fast (the blend path hands twilight to
 * Hillaire's LUTs). Everything stays finite and non-negative: slant depths
 * are capped at 1e4 (a transmittance of exactly 0 in float).
 */
#include "atmosphere.h"

#include <math.h>

static const sky_uniform_desc extinction_uniforms[] = {
    SKY_UF("u_tau_rayleigh", SKY_U_F3, tau_rayleigh),
    SKY_UF("u_tau_mie_sca", SKY_U_F3, tau_mie_sca),
    SKY_UF("u_tau_mie_ext", SKY_U_F3, tau_mie_ext),
    SKY_UF("u_tau_ozone", SKY_U_F3, tau_ozone),
    SKY_UF("u_chapman_x", SKY_U_F3, chapman_x),
    SKY_UF("u_sun_irradiance", SKY_U_F3, sun_irradiance),
};
const sky_snippet sky_extinction_snippet = {"SKY_HAS_EXTINCTION", "extinction.glsl", extinction_uniforms,
                                            SKY_UNIFORM_COUNT(extinction_uniforms), NULL};
static const sky_uniform_desc rayleigh_uniforms[] = {
    SKY_UF("u_sun_depth", SKY_U_F3, sun_depth),
    SKY_UF("u_mie_phase", SKY_U_F3, mie_phase),
};
const sky_snippet sky_rayleigh_snippet = {"SKY_HAS_RAYLEIGH", "rayleigh.glsl", rayleigh_uniforms,
                                          SKY_UNIFORM_COUNT(rayleigh_uniforms), NULL};

#define SLANT_DEPTH_MAX 1e4

double sky_chapman(double X, double mu)
{
    if (mu >= 0.0) {
        /* sqrt(pi X / 2) erfcx(mu sqrt(X / 2)); erfcx(y) ~ 2 / (sqrt(pi)
         * (y + sqrt(y^2 + a))) with a blended between Abramowitz &
         * Stegun 7.1.13's bounds 4/pi (exact at y = 0) and 2 (exact as
         * y -> inf): within 0.6 % of the exact integral for X 300..5300 */
        double y = mu * sqrt(0.5 * X);
        double a = 4.0 / SKY_PI + (2.0 - 4.0 / SKY_PI) * y / (y + 1.0);
        return sqrt(2.0 * X) / (y + sqrt(y * y + a));
    }
    /* Below the horizon the ray runs down to its tangent point, at
     * X sin(chi), and up again: 2 Ch(X sin chi, 90 deg) e^(X (1 - sin chi))
     * less the part above the observer on the far side, Ch(X, -mu). Past
     * e^50 the beam is black either way: the column is held there. */
    double sin_chi = sqrt(fmax(1.0 - mu * mu, 0.0));
    double growth = X * (1.0 - sin_chi);
    if (growth > 50.0) return 2.0 * sqrt(0.5 * SKY_PI * X) * exp(50.0); /* held: non-decreasing, finite */
    double grazing = sqrt(0.5 * SKY_PI * X * sin_chi) * exp(growth);
    return fmax(2.0 * grazing - sky_chapman(X, -mu), 0.0);
}

/* Column of the ozone tent above height h (km), in km of peak density. */
static double ozone_column_above(double h, double peak, double half)
{
    if (h <= peak - half) return half;
    if (h <= peak) return half - (h - (peak - half)) * (h - (peak - half)) / (2.0 * half);
    if (h <= peak + half) return (peak + half - h) * (peak + half - h) / (2.0 * half);
    return 0.0;
}

void sky_rayleigh_frame(sky_core *s)
{
    sky_frame *f = &s->frame;
    const sky_atmosphere_params *a = &s->atm_rgb;
    /* the observer inside the shell: an observer above it sees it from
     * just under the top (a closed form for the outside is Hillaire's) */
    double h = sky_clampd(s->observer.altitude_m / 1000.0, -0.5, a->top_radius_km - a->planet_radius_km - 0.01);
    double r = a->planet_radius_km + h;
    double rayleigh_column = a->rayleigh_scale_height_km * exp(-h / a->rayleigh_scale_height_km);
    double mie_column = a->mie_scale_height_km * exp(-h / a->mie_scale_height_km);
    double ozone_column = ozone_column_above(h, a->ozone_peak_km, a->ozone_half_width_km);
    double ozone_radius = a->planet_radius_km + fmax(a->ozone_peak_km, h + 0.01);
    f->chapman_x[0] = (float)(r / a->rayleigh_scale_height_km);
    f->chapman_x[1] = (float)(r / a->mie_scale_height_km);
    f->chapman_x[2] = (float)((r / ozone_radius) * (r / ozone_radius));
    double mu_s = f->sun_dir[1];
    double m_rayleigh = sky_chapman(f->chapman_x[0], mu_s), m_mie = sky_chapman(f->chapman_x[1], mu_s);
    /* the ozone shell: 1 / its local cosine where the ray crosses it, once
     * for any mu from an observer below the shell (a ray sunk below the
     * horizon meets it on the far side of its tangent point, at the same
     * cosine) */
    double m_ozone = 1.0 / sqrt(fmax(1.0 - f->chapman_x[2] * (1.0 - mu_s * mu_s), 1e-4));
    for (int i = 0; i < 3; i++) {
        f->tau_rayleigh[i] = (float)(a->rayleigh_scattering[i] * rayleigh_column);
        f->tau_mie_sca[i] = (float)(a->mie_scattering[i] * mie_column);
        f->tau_mie_ext[i] = (float)(a->mie_extinction[i] * mie_column);
        f->tau_ozone[i] = (float)(a->ozone_absorption[i] * ozone_column);
        double depth = f->tau_rayleigh[i] * m_rayleigh + f->tau_mie_ext[i] * m_mie + f->tau_ozone[i] * m_ozone;
        f->sun_depth[i] = (float)fmin(depth, SLANT_DEPTH_MAX);
        f->sun_irradiance[i] = (float)s->sun_irradiance_klx[i];
    }
    double g = a->mie_g;
    f->mie_phase[0] = (float)(3.0 / (8.0 * SKY_PI) * (1.0 - g * g) / (2.0 + g * g));
    f->mie_phase[1] = (float)(1.0 + g * g);
    f->mie_phase[2] = (float)(2.0 * g);
}

/* (e^-a - e^-b) / (b - a) without cancellation. */
static double exp_difference(double a, double b)
{
    double x = fabs(b - a);
    double g = x < 1e-3 ? 1.0 - 0.5 * x : -expm1(-x) / x;
    return exp(-fmin(a, b)) * g;
}

void sky_rayleigh_eval(const sky_frame *f, const double d[3], double rgb[3])
{
    double mu = fmax(d[1], 0.0);
    double m_rayleigh = sky_chapman(f->chapman_x[0], mu), m_mie = sky_chapman(f->chapman_x[1], mu);
    double m_ozone = 1.0 / sqrt(fmax(1.0 - f->chapman_x[2] * (1.0 - mu * mu), 1e-4));
    double c = d[0] * f->sun_dir[0] + d[1] * f->sun_dir[1] + d[2] * f->sun_dir[2];
    double rayleigh_phase = 3.0 / (16.0 * SKY_PI) * (1.0 + c * c);
    double mie_phase = f->mie_phase[0] * (1.0 + c * c) / pow(fmax(f->mie_phase[1] - f->mie_phase[2] * c, 1e-4), 1.5);
    for (int i = 0; i < 3; i++) {
        double view_depth = f->tau_rayleigh[i] * m_rayleigh + f->tau_mie_ext[i] * m_mie + f->tau_ozone[i] * m_ozone;
        double scattered = f->tau_rayleigh[i] * m_rayleigh * rayleigh_phase + f->tau_mie_sca[i] * m_mie * mie_phase;
        rgb[i] = f->sun_irradiance[i] * scattered * exp_difference(view_depth, f->sun_depth[i]);
    }
}
