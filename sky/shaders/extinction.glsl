/* extinction.glsl: the physical paths' closed-form optical depth from the
 * observer to space (rayleigh.c derives it), shared by the analytic sky,
 * Hillaire's and their blend: it dims the night layers behind the
 * atmosphere (Mueller sec. 5) without a texture. */
uniform SKY_UP vec3 u_tau_rayleigh;    /* vertical optical depths above the observer */
uniform SKY_UP vec3 u_tau_mie_sca;
uniform SKY_UP vec3 u_tau_mie_ext;
uniform SKY_UP vec3 u_tau_ozone;
uniform SKY_UP vec3 u_chapman_x;       /* R_obs/H_R, R_obs/H_M, (R_obs / R_ozone)^2  */
uniform SKY_UP vec3 u_sun_irradiance;  /* klx per channel above the atmosphere, over
                                    2^u_sun_gain_log2 (0 but on a fragment stage
                                    without highp: exposure.c)                 */
uniform SKY_UP float u_sun_gain_log2;

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

/* Optical depth from the observer to space along d (the horizon's below it). */
vec3 sky_view_depth(vec3 d, out float m_rayleigh, out float m_mie)
{
    float mu = max(d.y, 0.0);
    m_rayleigh = sky_chapman(u_chapman_x.x, mu);
    m_mie = sky_chapman(u_chapman_x.y, mu);
    /* ozone: a thin shell; the slant through it is 1 / its local cosine */
    float m_ozone = inversesqrt(max(1.0 - u_chapman_x.z * (1.0 - mu * mu), 1e-4));
    return u_tau_rayleigh * m_rayleigh + u_tau_mie_ext * m_mie + u_tau_ozone * m_ozone;
}

float sky_atmosphere_transmittance(vec3 d)
{
    float m_rayleigh, m_mie;
    vec3 depth = sky_view_depth(d, m_rayleigh, m_mie);
    return d.y < 0.0 ? 0.0 : exp(-dot(depth, vec3(0.2126, 0.7152, 0.0722)));
}
