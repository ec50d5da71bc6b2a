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
 * The sun's depth is not A_s u from every point, though: from each point
 * of the view ray it is that point's own slant column toward the sun
 * (Chapman's function there, or the grazing column of a sun under the
 * point's horizon), taken at three nodes of the ray and linear in u
 * between them, so each segment's extinction still integrates in closed
 * form. The points whose ray toward the sun meets the planet are in its
 * shadow and scatter nothing: the integral stops at the shadow's edge, so
 * the sky darkens through twilight into night (the issue "Real skies":
 * the old form let the top of the atmosphere always see the sun, its
 * night set by an optical-depth cap). Multiple scattering is one
 * isotropic phase term in the same integral (multiple_scattering below).
 *
 * Limits, by design: one column's u for all species; multiple scattering
 * isotropic and taken from a one-layer estimate; no light in the shadow
 * beyond it. Everything stays finite and non-negative: slant depths are
 * capped at 1e4 (a transmittance of exactly 0 in float).
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
    SKY_UF("u_rl_geometry", SKY_U_F4, rl_geometry),
    SKY_UF("u_rl_multiple", SKY_U_F3, rl_multiple),
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

/* Multiple scattering as one isotropic phase term added to each species'
 * phase function, so that it rides on the same closed-form integral as
 * single scattering (the sun's transmittance to each point, the view's
 * extinction). It follows Hillaire 2020 (sec. 5.5): light of the second
 * and higher orders is taken as isotropic about a point, its second order
 * the single-scattered radiance arriving there averaged over the sphere,
 * the higher orders a geometric series 1 / (1 - f_ms). Here that average
 * is in closed form for one layer seen from its bottom:
 *  - from the ground below, Lambertian of albedo rho lit by the sun at
 *    cosine mu_s: radiance rho mu_s E / pi over half the sphere, so an
 *    isotropic phase of rho mu_s / (2 pi) per unit of sunlight;
 *  - from the sky above, single scattering of column tau_s (isotropic on
 *    average): (1 / 4 pi) (1 / 4 pi) 2 pi int_0^1 (1 - e^(-tau_s / mu)) dmu,
 *    the integral 1 - E_2(tau_s) ~ tau_s (ln(1 / tau_s) + 0.42) for the
 *    thin columns of a clear sky (within 5 % up to tau_s 0.3; capped at 1);
 *  - f_ms, the share of that light scattered again, ~ the same hemisphere
 *    average of the sky plus the ground's albedo times the air's half.
 * RL_MS_GAIN is the one fitted number: it brings the day sky's mean
 * luminance onto the CPU reference's (sky-bench --only-atmosphere). */
#define RL_MS_GAIN 1.0
static void multiple_scattering(const sky_atmosphere_params *a, double mu_s, sky_frame *f)
{
    for (int i = 0; i < 3; i++) {
        double tau_s = f->tau_rayleigh[i] + f->tau_mie_sca[i];
        double above = tau_s > 0.0 ? fmin(tau_s * (log(1.0 / tau_s) + 0.42), 1.0) : 0.0;
        double rho = sky_clampd(a->ground_albedo[i], 0.0, 1.0);
        double second = rho * fmax(mu_s, 0.0) / (2.0 * SKY_PI) + above / (8.0 * SKY_PI);
        double f_ms = sky_clampd(0.5 * above + 0.5 * rho * above, 0.0, 0.9);
        f->rl_multiple[i] = (float)(RL_MS_GAIN * second / (1.0 - f_ms));
    }
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
    f->rl_geometry[0] = (float)r;
    f->rl_geometry[1] = (float)a->planet_radius_km;
    f->rl_geometry[2] = (float)a->rayleigh_scale_height_km;
    f->rl_geometry[3] = (float)a->mie_scale_height_km;
    multiple_scattering(a, mu_s, f);
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

/* Optical depth toward the sun (cosine mu) from a point at radius r for
 * one exponential species of scale height H whose vertical depth above
 * the observer (radius r0) is tau. Above the horizon: the point's own
 * column times Chapman's function. Below it the ray runs down to its
 * tangent radius r_t and up again: the column of the tangent point's
 * grazing ray both ways, 2 sqrt(pi r_t / 2H) tau e^((r0 - r_t) / H), less
 * the part above the point on the far side (the same decomposition as
 * sky_chapman, written about the tangent point so that e^growth and the
 * point's thin column never meet as inf times 0). r0 - r_t comes in from
 * the caller in a cancellation-free form; the caller only asks about
 * points that the planet does not shadow (r_t >= R). */
static double sun_column(double tau, double H, double r, double mu, double dr0, double r0_minus_rt, double rt)
{
    double point = exp(fmin(dr0 / H, 0.0));
    if (mu >= 0.0) return tau * point * sky_chapman(r / H, mu);
    double grazing = 2.0 * sqrt(0.5 * SKY_PI * rt / H) * exp(fmin(r0_minus_rt / H, 80.0));
    return tau * fmax(grazing - point * sky_chapman(r / H, -mu), 0.0);
}

/* The lit interval's nodes along the view ray, as fractions of u at the
 * shadow's edge. Three nodes and the top (u = 0, no air, no depth): the
 * sun's depth is linear in u between them (exactly so for one species
 * under a high sun; the grazing depth of a sun under the horizon is
 * nearly so too, its tangent height rising with the point's height), so
 * each segment's extinction integrates in closed form. */
#define RL_NODES 3
static const double rl_node[RL_NODES] = {1.0, 0.45, 0.15};

void sky_rayleigh_eval(const sky_frame *f, const double d[3], double rgb[3])
{
    double mu = fmax(d[1], 0.0);
    double m_rayleigh = sky_chapman(f->chapman_x[0], mu), m_mie = sky_chapman(f->chapman_x[1], mu);
    double m_ozone = 1.0 / sqrt(fmax(1.0 - f->chapman_x[2] * (1.0 - mu * mu), 1e-4));
    double c = d[0] * f->sun_dir[0] + d[1] * f->sun_dir[1] + d[2] * f->sun_dir[2];
    double sy = f->sun_dir[1];
    double r0 = f->rl_geometry[0], R = f->rl_geometry[1], HR = f->rl_geometry[2], HM = f->rl_geometry[3];
    double rayleigh_phase = 3.0 / (16.0 * SKY_PI) * (1.0 + c * c);
    double mie_phase = f->mie_phase[0] * (1.0 + c * c) / pow(fmax(f->mie_phase[1] - f->mie_phase[2] * c, 1e-4), 1.5);

    /* The Earth's shadow: the points whose ray toward the sun meets the
     * planet fill the cylinder of radius R behind it (P.s < 0 and
     * |P|^2 - (P.s)^2 < R^2, planet-centred). Along the view ray, P = O +
     * t d, that set is convex and, once the observer is in it, an
     * interval [0, t_lit): |P|^2 - (P.s)^2 - R^2 = A t^2 + 2 B t + C with
     * A = 1 - c^2, B = r0 (mu - s_y c), C = (r0 - R)(r0 + R) - (r0 s_y)^2,
     * whose larger root is -C / (B + sqrt(B^2 - A C)) (no cancellation:
     * C < 0 there), and the plane P.s = 0 is left at t = -r0 s_y / c. An
     * observer in sunlight looking up never enters the shadow (it lies
     * below the tangent plane of the terminator). */
    double t_lit = 0.0;
    double C = (r0 - R) * (r0 + R) - (r0 * sy) * (r0 * sy);
    if (sy < 0.0 && C < 0.0) {
        double A = fmax(1.0 - c * c, 0.0), B = r0 * (mu - sy * c);
        t_lit = -C / fmax(B + sqrt(fmax(B * B - A * C, 0.0)), 1e-6);
        if (c > 0.0) t_lit = fmin(t_lit, -r0 * sy / c);
    }
    /* height above the observer at t: (r^2 - r0^2) / (r + r0) */
    double q = t_lit * (2.0 * r0 * mu + t_lit);
    double u_lit = exp(-(q / (sqrt(r0 * r0 + q) + r0)) / HR);

    /* the sun's depth at each node: u -> height z -> distance t along the
     * ray ((r0 + z)^2 = r0^2 + 2 r0 mu t + t^2, its root in the stable
     * form) -> the sun's cosine there, a = P.s / r */
    double u[RL_NODES + 1], S[RL_NODES + 1][3];
    for (int k = 0; k < RL_NODES; k++) {
        u[k] = u_lit * rl_node[k];
        double z = -HR * log(fmax(u[k], 1e-30));
        double w = z * (2.0 * r0 + z);
        double t = w / (r0 * mu + sqrt(r0 * r0 * mu * mu + w));
        double r = r0 + z, a = r0 * sy + t * c, mu_s = sky_clampd(a / r, -1.0, 1.0);
        /* r0 - r_t = (r0^2 - r^2 + a^2) / (r0 + r_t), with r_t^2 = r^2 - a^2 */
        double rt = sqrt(fmax(w + r0 * r0 - a * a, 0.0));
        double r0_minus_rt = (a * a - w) / (r0 + rt);
        double col_r = sun_column(1.0, HR, r, mu_s, -z, r0_minus_rt, rt);
        double col_m = sun_column(1.0, HM, r, mu_s, -z, r0_minus_rt, rt);
        /* ozone: a thin shell at R_oz^2 = r0^2 / chapman_x[2], crossed at
         * local cosine sqrt(1 - (r_t / R_oz)^2): once from below it, twice
         * from above it when the ray dips under it, never otherwise */
        double oz2 = r0 * r0 / f->chapman_x[2];
        double crossings = r * r <= oz2 ? 1.0 : (mu_s < 0.0 && rt * rt < oz2 ? 2.0 : 0.0);
        double col_o = crossings / sqrt(fmax(1.0 - rt * rt / oz2, 1e-4));
        for (int i = 0; i < 3; i++)
            S[k][i] = fmin(f->tau_rayleigh[i] * col_r + f->tau_mie_ext[i] * col_m + f->tau_ozone[i] * col_o,
                           SLANT_DEPTH_MAX);
    }
    u[RL_NODES] = 0.0;
    for (int i = 0; i < 3; i++) S[RL_NODES][i] = 0.0;

    for (int i = 0; i < 3; i++) {
        double view_depth = f->tau_rayleigh[i] * m_rayleigh + f->tau_mie_ext[i] * m_mie + f->tau_ozone[i] * m_ozone;
        /* the integrand e^-(A_v (1 - u) + S(u)), S linear between nodes */
        double lit = 0.0;
        for (int k = 0; k < RL_NODES; k++) {
            double ea = view_depth * (1.0 - u[k + 1]) + S[k + 1][i], eb = view_depth * (1.0 - u[k]) + S[k][i];
            lit += (u[k] - u[k + 1]) * exp_difference(ea, eb);
        }
        double ms = f->rl_multiple[i];
        double scattered = f->tau_rayleigh[i] * m_rayleigh * (rayleigh_phase + ms) +
                           f->tau_mie_sca[i] * m_mie * (mie_phase + ms);
        rgb[i] = f->sun_irradiance[i] * scattered * lit;
    }
}
