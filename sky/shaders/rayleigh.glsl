/* rayleigh.glsl: analytic single scattering of Rayleigh + Mie light
 * (rayleigh.c derives it): closed-form optical depths from a Chapman-
 * function approximation, no ray march. Per pixel: two square-root
 * Chapman evaluations, one phase function pair, three exponentials. */
uniform vec3 u_tau_rayleigh;    /* vertical optical depths above the observer */
uniform vec3 u_tau_mie_sca;
uniform vec3 u_tau_mie_ext;
uniform vec3 u_tau_ozone;
uniform vec3 u_chapman_x;       /* R_obs/H_R, R_obs/H_M, (R_obs / R_ozone)^2  */
uniform vec3 u_sun_depth;       /* optical depth toward the sun from the observer */
uniform vec3 u_sun_irradiance;  /* klx per channel above the atmosphere      */
uniform vec3 u_mie_phase;       /* Cornette-Shanks: k, 1 + g^2, 2 g (rayleigh.c) */

/* Chapman's grazing-incidence function for mu >= 0: the column along the
 * ray over the vertical one, sqrt(pi X / 2) erfcx(mu sqrt(X / 2)), with
 * erfcx(y) ~ 2 / (sqrt(pi) (y + sqrt(y^2 + a))) (Abramowitz & Stegun
 * 7.1.13's bounds, a blended between them): within 0.6 % of the exact
 * integral for X 300..5300 at every mu. */
float sky_chapman(float X, float mu)
{
    float y = mu * sqrt(0.5 * X);
    float a = 1.2732395 + 0.7267605 * y / (y + 1.0);
    return sqrt(2.0 * X) / (y + sqrt(y * y + a));
}

/* (e^-a - e^-b) / (b - a) without cancellation: e^-min * (1 - e^-|b-a|) / |b-a| */
vec3 sky_exp_difference(vec3 a, vec3 b)
{
    vec3 x = abs(b - a);
    vec3 g = mix((1.0 - exp(-x)) / max(x, vec3(1e-4)), 1.0 - 0.5 * x, step(x, vec3(1e-3)));
    return exp(-min(a, b)) * g;
}

/* Optical depth from the observer to space along d (d.y >= 0). */
vec3 sky_view_depth(vec3 d, out float m_rayleigh, out float m_mie)
{
    float mu = max(d.y, 0.0);
    m_rayleigh = sky_chapman(u_chapman_x.x, mu);
    m_mie = sky_chapman(u_chapman_x.y, mu);
    /* ozone: a thin shell; the slant through it is 1 / its local cosine */
    float m_ozone = inversesqrt(max(1.0 - u_chapman_x.z * (1.0 - mu * mu), 1e-4));
    return u_tau_rayleigh * m_rayleigh + u_tau_mie_ext * m_mie + u_tau_ozone * m_ozone;
}

vec3 sky_atmosphere(vec3 d, vec3 day)
{
    float m_rayleigh, m_mie;
    vec3 view_depth = sky_view_depth(d, m_rayleigh, m_mie);
    float c = dot(d, u_sun_dir);
    float rayleigh_phase = 0.0596831 * (1.0 + c * c); /* 3 / (16 pi) (1 + c^2) */
    float mie_phase = u_mie_phase.x * (1.0 + c * c) / pow(max(u_mie_phase.y - u_mie_phase.z * c, 1e-4), 1.5);
    vec3 scattered = u_tau_rayleigh * (m_rayleigh * rayleigh_phase) + u_tau_mie_sca * (m_mie * mie_phase);
    vec3 L = u_sun_irradiance * scattered * sky_exp_difference(view_depth, u_sun_depth);
    return (L + sky_night_floor(d)) * sky_below_horizon(d);
}

float sky_atmosphere_transmittance(vec3 d)
{
    float m_rayleigh, m_mie;
    vec3 depth = sky_view_depth(d, m_rayleigh, m_mie);
    return d.y < 0.0 ? 0.0 : exp(-dot(depth, vec3(0.2126, 0.7152, 0.0722)));
}
