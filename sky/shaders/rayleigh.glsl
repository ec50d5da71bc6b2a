/* rayleigh.glsl: analytic single scattering of Rayleigh + Mie light
 * (rayleigh.c derives it), on extinction.glsl's closed-form optical
 * depths: no ray march, no texture. Per pixel: two square-root Chapman
 * evaluations, one phase function pair, three exponentials. */
uniform vec3 u_sun_depth;       /* optical depth toward the sun from the observer */
uniform vec3 u_mie_phase;       /* Cornette-Shanks: k, 1 + g^2, 2 g (rayleigh.c) */

/* (e^-a - e^-b) / (b - a) without cancellation: e^-min * (1 - e^-|b-a|) / |b-a| */
vec3 sky_exp_difference(vec3 a, vec3 b)
{
    vec3 x = abs(b - a);
    vec3 g = mix((1.0 - exp(-x)) / max(x, vec3(1e-4)), 1.0 - 0.5 * x, step(x, vec3(1e-3)));
    return exp(-min(a, b)) * g;
}

vec3 sky_rayleigh_radiance(vec3 view)
{
    vec3 d = sky_horizon_clamp(view);
    float m_rayleigh, m_mie;
    vec3 view_depth = sky_view_depth(d, m_rayleigh, m_mie);
    float c = dot(d, u_sun_dir);
    float rayleigh_phase = 0.0596831 * (1.0 + c * c); /* 3 / (16 pi) (1 + c^2) */
    float mie_phase = u_mie_phase.x * (1.0 + c * c) / pow(max(u_mie_phase.y - u_mie_phase.z * c, 1e-4), 1.5);
    vec3 scattered = u_tau_rayleigh * (m_rayleigh * rayleigh_phase) + u_tau_mie_sca * (m_mie * mie_phase);
    return u_sun_irradiance * scattered * sky_exp_difference(view_depth, u_sun_depth);
}

#ifndef SKY_HAS_BLEND
vec3 sky_atmosphere(vec3 d, vec3 day)
{
    return sky_or_ground(d, sky_rayleigh_radiance(d) * sky_eclipse_dim(d) + sky_night_floor(d));
}
#endif
