/*
 * The analytic Rayleigh + Mie atmosphere: single scattering up to the
 * Earth's shadow and an isotropic multiple-scattering term, each segment
 * between a few nodes of the view ray in closed form; no ray march, no
 * table.
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
 * point's horizon), taken at nodes of the ray, and u is each species'
 * own share of the view's column beyond a node (Chapman's function
 * there too); between nodes the exponent is linear in u, so each
 * segment's extinction still integrates in closed form. The points whose ray toward the sun meets the planet are in its
 * shadow and scatter nothing: the integral stops at the shadow's edge, so
 * the sky darkens through twilight into night (the issue "Real skies":
 * the old form let the top of the atmosphere always see the sun, its
 * night set by an optical-depth cap). Multiple scattering is one
 * isotropic phase term in the same integral (multiple_scattering below).
 *
 * Limits, by design: multiple scattering isotropic, from a one-layer
 * estimate, and its light in the shadow a fit (rl_node_at); the nodes' few
 * segments (their error against a fine march is given below). Everything stays finite and non-negative: slant depths are
 * capped at 1e4 (a transmittance of exactly 0 in float).
 */
#include "atmosphere.h"

#include <math.h>
#include <string.h>

static const sky_uniform_desc extinction_uniforms[] = {
    SKY_UF("u_tau_rayleigh", SKY_U_F3, tau_rayleigh),
    SKY_UF("u_tau_mie_sca", SKY_U_F3, tau_mie_sca),
    SKY_UF("u_tau_mie_ext", SKY_U_F3, tau_mie_ext),
    SKY_UF("u_tau_ozone", SKY_U_F3, tau_ozone),
    SKY_UF("u_chapman_x", SKY_U_F3, chapman_x),
    SKY_UF("u_sun_irradiance", SKY_U_F3, sun_irradiance_sent),
    SKY_UF("u_sun_gain_log2", SKY_U_F1, sun_gain_log2),
};
/* both stages: the dome evaluates the analytic sky's integrals per vertex */
const sky_snippet sky_extinction_snippet = {"SKY_HAS_EXTINCTION", "extinction.glsl", extinction_uniforms,
                                            SKY_UNIFORM_COUNT(extinction_uniforms), "extinction.glsl", NULL, NULL};
static const sky_uniform_desc rayleigh_uniforms[] = {
    SKY_UF("u_mie_phase", SKY_U_F3, mie_phase),
    SKY_UF("u_rl_geometry", SKY_U_F4, rl_geometry),
    SKY_UF("u_rl_multiple", SKY_U_F3, rl_multiple),
    SKY_UF("u_rl_ozone", SKY_U_F3, rl_ozone),
    SKY_UF("u_rl_skylight", SKY_U_F3, rl_skylight),
};
const sky_snippet sky_rayleigh_snippet = {"SKY_HAS_RAYLEIGH", "rayleigh.glsl", rayleigh_uniforms,
                                          SKY_UNIFORM_COUNT(rayleigh_uniforms), "rayleigh.glsl", NULL, NULL};

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
 * No gain is fitted here: the estimate stands as derived (its error
 * against the CPU reference: docs/validation.md). */
static void multiple_scattering(const sky_atmosphere_params *a, double mu_s, sky_frame *f)
{
    for (int i = 0; i < 3; i++) {
        double tau_s = f->tau_rayleigh[i] + f->tau_mie_sca[i];
        double above = tau_s > 0.0 ? fmin(tau_s * (log(1.0 / tau_s) + 0.42), 1.0) : 0.0;
        double rho = sky_clampd(a->ground_albedo[i], 0.0, 1.0);
        double second = rho * fmax(mu_s, 0.0) / (2.0 * SKY_PI) + above / (8.0 * SKY_PI);
        double f_ms = sky_clampd(0.5 * above + 0.5 * rho * above, 0.0, 0.9);
        f->rl_multiple[i] = (float)(second / (1.0 - f_ms));
    }
}

static void skylight(const sky_core *s, sky_frame *f);

void sky_rayleigh_frame(sky_core *s) { sky_rayleigh_light_frame(s, &s->frame); }

void sky_rayleigh_light_frame(const sky_core *s, sky_frame *f)
{
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
    f->rl_ozone[0] = (float)a->ozone_peak_km;
    f->rl_ozone[1] = (float)a->ozone_half_width_km;
    f->rl_ozone[2] = ozone_column > 0.0 ? (float)(1.0 / ozone_column) : 0.0f;
    multiple_scattering(a, mu_s, f);
    double g = a->mie_g;
    f->mie_phase[0] = (float)(3.0 / (8.0 * SKY_PI) * (1.0 - g * g) / (2.0 + g * g));
    f->mie_phase[1] = (float)(1.0 + g * g);
    f->mie_phase[2] = (float)(2.0 * g);
    skylight(s, f);
}

/* The mean of e^-E over a segment whose exponent runs linearly from a
 * to b, (e^-a - e^-b) / (b - a), from the two exponentials (ta = e^-a,
 * tb = e^-b), which each node computes once for both of its segments;
 * within 1e-3 of each other, the larger one times 1 - x/2. */
static double seg_mean(double ta, double tb, double a, double b)
{
    double x = b - a;
    return fabs(x) < 1e-3 ? fmax(ta, tb) * (1.0 - 0.5 * fabs(x)) : (ta - tb) / x;
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

/* The nodes along the view ray. In the shadow, from the eye to its edge:
 * at 0, 3 and 12 Rayleigh scale heights of distance (or the edge if
 * nearer), where only multiple scattering lights the air; the view's own
 * extinction is what limits a low ray there, so the nodes follow
 * distance. Then the lit part: the edge, the points where the Rayleigh
 * column above is 0.45 and 0.15 of the edge's, and the top (no air, no
 * depth). With the eye in sunlight the shadow's segments have no length.
 * Each segment's extinction integrates in closed form, its exponent taken
 * linear in each species' own column (the difference quotient above):
 * exact for one species under a high sun, and the sun's grazing depth
 * under the horizon is nearly linear in the column too, its tangent
 * height rising with the point's height. (How closely three nodes each
 * side hold the sky against the same model on a fine march:
 * docs/validation.md.) */
#define RL_SHADOW_NODES 3
#define RL_LIT_NODES 3
#define RL_NODES (RL_SHADOW_NODES + RL_LIT_NODES + 1)
static const double rl_shadow_node[RL_SHADOW_NODES] = {0.0, 3.0, 12.0};
static const double rl_lit_node[RL_LIT_NODES] = {1.0, 0.45, 0.15};

/* One node: its u for each species (Rayleigh, Mie), the depth of the sun
 * for single scattering and the effective depth of the light that
 * multiple scattering brings there (see below), per channel. */
typedef struct rl_node {
    double u_r, u_m, sun[3], ms[3];
} rl_node;

/* The distance along the view ray (mu) to the height where the Rayleigh
 * column above is u of the observer's: (r0 + z)^2 = r0^2 + 2 r0 mu t +
 * t^2, its root in the stable form. */
static double distance_at(const sky_frame *f, double u, double mu)
{
    double r0 = f->rl_geometry[0], z = -f->rl_geometry[2] * log(fmax(u, 1e-30));
    double w = z * (2.0 * r0 + z);
    return w / fmax(r0 * mu + sqrt(r0 * r0 * mu * mu + w), 1e-9);
}

static void rl_node_at(const sky_frame *f, double t, double mu, double c, double m_r, double m_m, rl_node *n)
{
    double sy = f->sun_dir[1];
    double r0 = f->rl_geometry[0], R = f->rl_geometry[1], HR = f->rl_geometry[2], HM = f->rl_geometry[3];
    /* the point's height z above the eye ((r^2 - r0^2) / (r + r0)) and
     * the sun's cosine there, a = P.s / r */
    double w = t * (2.0 * r0 * mu + t);
    double r = sqrt(r0 * r0 + w), z = w / (r + r0);
    double a = r0 * sy + t * c;
    /* r_t^2 = r^2 - a^2, the radius where the sun's ray is tangent */
    double rt = sqrt(fmax(w + r0 * r0 - a * a, 0.0));
    /* A point in the shadow (a < 0, r_t < R) is raised along its vertical
     * to the shadow's edge, r' = r R / r_t, where the sun's ray grazes the
     * ground: multiple scattering reaches it from the lit air above,
     * thinned by e per Rayleigh scale height of the climb (the lit column
     * above it falls so). A lit point stays where it is. */
    double raise = (a < 0.0 && rt < R) ? r * (R / fmax(rt, 1e-3 * R) - 1.0) : 0.0;
    double re = r + raise, ze = z + raise, ae = a * re / r, rte = raise > 0.0 ? R : rt;
    double mu_s = sky_clampd(ae / re, -1.0, 1.0);
    /* r0 - r_t = (r0^2 - r_t^2) / (r0 + r_t), with r0^2 - r_t^2 = a^2 - w
     * for the point itself (no cancellation); the raised point's is R */
    double r0_minus_rt = raise > 0.0 ? r0 - R : (a * a - w) / (r0 + rt);
    double col_r = sun_column(1.0, HR, re, mu_s, -ze, r0_minus_rt, rte);
    double col_m = sun_column(1.0, HM, re, mu_s, -ze, r0_minus_rt, rte);
    /* ozone, a thin tent: the part of its column above the point (as a
     * fraction of the observer's), crossed at the local cosine where the
     * ray meets the layer's peak radius, sqrt(1 - (r_t / R_oz)^2) (the
     * point's own cosine once it is above the peak); a ray dipping toward
     * its tangent point also crosses twice the part between the tangent
     * height and the point, and that part at the peak radius's cosine
     * even from a point above the peak (where the dip meets the layer;
     * the point's own cosine, twice as steep for a point 20 km above the
     * peak, let the lit air above the shadow keep too much of its green:
     * the zenith's G at sun -6 deg 0.87 -> 0.70 mcd/m^2, the reference
     * ~0.3; grazing, 1 / sqrt(1e-3) at most). Smooth in the point's height, so that no
     * node steps as it crosses the layer. */
    double oz_r = R + f->rl_ozone[0], h_t = fmin(rte, re) - R;
    double oz_above = ozone_column_above(ze + r0 - R, f->rl_ozone[0], f->rl_ozone[1]);
    double oz_dip = mu_s < 0.0 ? ozone_column_above(h_t, f->rl_ozone[0], f->rl_ozone[1]) - oz_above : 0.0;
    double k_up = rte / fmax(oz_r, re), k_dip = fmin(rte / oz_r, 1.0);
    double col_o = (oz_above / sqrt(fmax(1.0 - k_up * k_up, 1e-3)) + 2.0 * oz_dip / sqrt(fmax(1.0 - k_dip * k_dip, 1e-3))) *
                   f->rl_ozone[2];
    /* the share of the view's column beyond the point, per species: the
     * point's own column along the ray (Chapman's function at its cosine
     * (r0 mu + t) / r) over the observer's. A flat layer's u, but exact on
     * a curved one: along a low ray the column builds up linearly in t
     * while the height, and u, change only as t^2. */
    double mu_v = sky_clampd((r0 * mu + t) / r, 0.0, 1.0);
    n->u_r = exp(-z / HR) * sky_chapman(r / HR, mu_v) / m_r;
    n->u_m = exp(-z / HM) * sky_chapman(r / HM, mu_v) / m_m;
    for (int i = 0; i < 3; i++)
        n->sun[i] = fmin(f->tau_rayleigh[i] * col_r + f->tau_mie_ext[i] * col_m + f->tau_ozone[i] * col_o,
                         SLANT_DEPTH_MAX);
    /* Deep in the shadow the light comes down from the lit air, which
     * scatters blue as the day sky does; the grazing reddening is the
     * edge's, not the shadow's: there every channel takes the green
     * channel's depth, blended in with the climb, 1 - e^-climb/H_R
     * (nothing at the edge, so no seam). */
    double neutral = -expm1(-raise / HR);
    double low = exp(-z / HR); /* the skylight's floor fades with height (below) */
    for (int i = 0; i < 3; i++) {
        double s = n->sun[i] + (n->sun[1] - n->sun[i]) * neutral;
        /* Multiple scattering at a point comes from the sunlit air around
         * it. Where the sun's own depth s there is small that is its
         * transmittance e^-s; where it is large (a low sun, the shadow's
         * edge), from the air higher up, whose grazing depth falls as
         * s e^-x a scale height x above: the best of e^-(s e^-x) e^-x is
         * 1 / (e s), at x = ln s, the light of the lit air above. Past a
         * knee s_0 the exponent is so s_0 (1 + ln(s / s_0)) (equal
         * slopes at the knee); s_0 = 1 is the bound above (the air above
         * is not lit from every direction, as the isotropic term
         * assumes). In the shadow, times e^-climb/(4 H_R): the lit air
         * that lights a shadowed point lies up and toward the sun, along
         * a slant, nearer than the vertical climb to the edge says. Both
         * numbers (s_0 = 3, 4 H_R) are fitted against the reference of
         * the realistic Earth (aerosol optical depth 0.085) and Bond &
         * Henderson's twilight illuminance (the fit's figures:
         * docs/validation.md). */
        n->ms[i] = (s > 3.0 ? 3.0 + 3.0 * log(s / 3.0) : s) + 0.25 * raise / HR;
        /* The knee alone leaves the air near the ground, where the sun's
         * own column grazes (sunset, the shadow), far darker than the
         * reference's, whose source there is the skylight itself, the
         * sky's light around the point: at sun -4 deg the horizon toward
         * the sun, a long path through that air, G 0.023 kcd/m^2 in the
         * reference (above twice its zenith), 0.00026 here; at -0.9 deg
         * 0.21 and 0.0022. Only nearly horizontal rays show it (their far
         * air hides behind a horizontal aerosol depth of ~7): a dark band
         * just above the horizon around sunset and in twilight. So the
         * skylight's exponent (skylight below) is a floor under the
         * knee's, in full at the observer's height and fading over a
         * Rayleigh scale height above it (a point up there sees less of
         * the ground and of the low air's glow; the floor taken
         * everywhere brightens the twilight zenith). By day it lifts only
         * the lowest rays a little (its effect on the error:
         * docs/validation.md). */
        n->ms[i] -= low * fmax(n->ms[i] - f->rl_skylight[i], 0.0);
    }
}

/* The skylight: the isotropic mean of the light around a point near the
 * ground, half the sky's mean radiance over the upper hemisphere and half
 * the ground's (albedo times the sky's irradiance over pi), written as
 * the exponent that multiple scattering's phase term and the sun's
 * irradiance would need to give it (rl_node_at's floor). From the sky
 * itself: one pass of the same 4 x 8 quadrature as the frame's summary
 * (atmosphere.c), taken without the floor; 32 closed-form evaluations a
 * frame on the CPU, nothing on the GPU but a min per node. */
#define RL_NO_SKYLIGHT 1e4f
static void skylight(const sky_core *s, sky_frame *f)
{
    for (int i = 0; i < 3; i++) f->rl_skylight[i] = RL_NO_SKYLIGHT;
    /* Hillaire's path reads only the frame's extinction from here */
    if (s->atmosphere != SKY_ATMOSPHERE_RAYLEIGH && s->atmosphere != SKY_ATMOSPHERE_BLEND) return;
    static const double rl_mu_node[4] = {0.0694318442, 0.3300094782, 0.6699905218, 0.9305681558};
    static const double rl_mu_weight[4] = {0.1739274226, 0.3260725774, 0.3260725774, 0.1739274226};
    double mean[3] = {0, 0, 0}, irradiance[3] = {0, 0, 0};
    for (int k = 0; k < 4; k++) {
        double c = sqrt(1.0 - rl_mu_node[k] * rl_mu_node[k]);
        for (int a = 0; a < 8; a++) {
            double az = 2.0 * SKY_PI * (a + 0.5) / 8.0, d[3] = {c * sin(az), rl_mu_node[k], -c * cos(az)}, rgb[3];
            sky_rayleigh_eval(f, d, rgb);
            for (int i = 0; i < 3; i++) {
                mean[i] += rl_mu_weight[k] * rgb[i] / 8.0;
                irradiance[i] += 2.0 * SKY_PI * rl_mu_weight[k] * rl_mu_node[k] * rgb[i] / 8.0;
            }
        }
    }
    for (int i = 0; i < 3; i++) {
        double rho = sky_clampd(s->atm_rgb.ground_albedo[i], 0.0, 1.0);
        double J = 0.5 * (mean[i] + rho * irradiance[i] / SKY_PI);
        double unit = (double)f->sun_irradiance[i] * f->rl_multiple[i];
        if (J > 0.0 && unit > 0.0) f->rl_skylight[i] = (float)fmin(log(unit / J), RL_NO_SKYLIGHT);
    }
}

void sky_rayleigh_eval(const sky_frame *f, const double d[3], double rgb[3])
{
    double mu = fmax(d[1], 0.0);
    double m_rayleigh = sky_chapman(f->chapman_x[0], mu), m_mie = sky_chapman(f->chapman_x[1], mu);
    double m_ozone = 1.0 / sqrt(fmax(1.0 - f->chapman_x[2] * (1.0 - mu * mu), 1e-4));
    double c = d[0] * f->sun_dir[0] + d[1] * f->sun_dir[1] + d[2] * f->sun_dir[2];
    double sy = f->sun_dir[1];
    double r0 = f->rl_geometry[0], R = f->rl_geometry[1], HR = f->rl_geometry[2];
    double rayleigh_phase = 3.0 / (16.0 * SKY_PI) * (1.0 + c * c);
    double mie_phase = f->mie_phase[0] * (1.0 + c * c) / pow(fmax(f->mie_phase[1] - f->mie_phase[2] * c, 1e-4), 1.5);

    /* The Earth's shadow: the points whose ray toward the sun meets the
     * planet fill the cylinder of radius R behind it (P.s < 0 and
     * |P|^2 - (P.s)^2 < R^2, planet-centred). Along the view ray, P = O +
     * t d, that set is convex and, once the observer is in it, an
     * interval [0, t_lit): |P|^2 - (P.s)^2 - R^2 = A t^2 + 2 B t + C with
     * A = 1 - c^2, B = r0 (mu - s_y c), C = (r0 - R)(r0 + R) - (r0 s_y)^2;
     * its larger root is (-B + sqrt(B^2 - A C)) / A, or, without the
     * cancellation of B > 0, -C / (B + sqrt(B^2 - A C)) (C < 0 there). The
     * plane P.s = 0 is left at t = -r0 s_y / c. An observer in sunlight
     * looking up never enters the shadow (it lies below the tangent plane
     * of the terminator). */
    double t_lit = 0.0, sunlit = 1.0;
    double C = (r0 - R) * (r0 + R) - (r0 * sy) * (r0 * sy);
    if (sy < 0.0 && C < 0.0) {
        double A = fmax(1.0 - c * c, 0.0), B = r0 * (mu - sy * c), root = sqrt(fmax(B * B - A * C, 0.0));
        t_lit = B > 0.0 ? -C / (B + root) : (-B + root) / fmax(A, 1e-12);
        if (c > 0.0) t_lit = fmin(t_lit, -r0 * sy / c);
        /* an edge above the air (u < 1e-6, 110 km for Earth) leaves no lit
         * air: what sunlight the nodes there would lend (the air holds a
         * millionth of the column) is not taken */
        double t_top = distance_at(f, 1e-6, mu);
        if (t_lit > t_top) sunlit = 0.0;
        t_lit = fmin(t_lit, t_top);
    }
    /* height above the observer at t: (r^2 - r0^2) / (r + r0) */
    double q = t_lit * (2.0 * r0 * mu + t_lit);
    double u_lit = exp(-(q / (sqrt(r0 * r0 + q) + r0)) / HR);

    /* an eye in sunlight: the shadow's segments have no length (skipped) */
    int k0 = t_lit > 0.0 ? 0 : RL_SHADOW_NODES;
    rl_node n[RL_NODES];
    for (int k = k0; k < RL_SHADOW_NODES; k++) rl_node_at(f, fmin(t_lit, rl_shadow_node[k] * HR), mu, c, m_rayleigh, m_mie, &n[k]);
    for (int k = 0; k < RL_LIT_NODES; k++)
        rl_node_at(f, k ? distance_at(f, u_lit * rl_lit_node[k], mu) : t_lit, mu, c, m_rayleigh, m_mie,
                &n[RL_SHADOW_NODES + k]);
    memset(&n[RL_NODES - 1], 0, sizeof n[0]); /* the top: u = 0, no depth */

    for (int i = 0; i < 3; i++) {
        double a_r = f->tau_rayleigh[i] * m_rayleigh, a_m = f->tau_mie_ext[i] * m_mie, a_o = f->tau_ozone[i] * m_ozone;
        double s_m = f->tau_mie_sca[i] * m_mie;
        double single = 0.0, multiple = 0.0;
        /* each node's exponents (the view's depth from the eye plus the
         * sun's, or multiple scattering's) and their exponentials */
        double e_ss[RL_NODES], e_ms[RL_NODES], t_ss[RL_NODES], t_ms[RL_NODES];
        for (int k = k0; k < RL_NODES; k++) {
            double v = (a_r + a_o) * (1.0 - n[k].u_r) + a_m * (1.0 - n[k].u_m);
            e_ss[k] = v + n[k].sun[i];
            e_ms[k] = v + n[k].ms[i];
            t_ss[k] = exp(-e_ss[k]);
            t_ms[k] = exp(-e_ms[k]);
        }
        for (int k = k0; k + 1 < RL_NODES; k++) {
            const rl_node *lo = &n[k], *hi = &n[k + 1];
            if (k < RL_SHADOW_NODES) {
                /* In the shadow the exponent of multiple scattering grows
                 * with the climb to the shadow's edge, linearly in height,
                 * where each species' column falls exponentially: take
                 * the exponent less ln u linear in ln u (the integral of
                 * an exponential density along the segment, as the
                 * reference's seg_exp), which a long segment needs; its
                 * exponential is e^-E times u. */
                double lr_lo = log(fmax(lo->u_r, 1e-30)), lr_hi = log(fmax(hi->u_r, 1e-30));
                double lm_lo = log(fmax(lo->u_m, 1e-30)), lm_hi = log(fmax(hi->u_m, 1e-30));
                multiple += a_r * (lr_lo - lr_hi) *
                                seg_mean(t_ms[k] * lo->u_r, t_ms[k + 1] * hi->u_r, e_ms[k] - lr_lo, e_ms[k + 1] - lr_hi) +
                            s_m * (lm_lo - lm_hi) *
                                seg_mean(t_ms[k] * lo->u_m, t_ms[k + 1] * hi->u_m, e_ms[k] - lm_lo, e_ms[k + 1] - lm_hi);
            } else {
                double w_r = a_r * (lo->u_r - hi->u_r), w_m = s_m * (lo->u_m - hi->u_m);
                multiple += (w_r + w_m) * seg_mean(t_ms[k], t_ms[k + 1], e_ms[k], e_ms[k + 1]);
                single += (w_r * rayleigh_phase + w_m * mie_phase) * sunlit *
                          seg_mean(t_ss[k], t_ss[k + 1], e_ss[k], e_ss[k + 1]);
            }
        }
        rgb[i] = f->sun_irradiance[i] * (single + f->rl_multiple[i] * multiple);
    }
}
