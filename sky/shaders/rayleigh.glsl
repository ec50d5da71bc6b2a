/* rayleigh.glsl: analytic single scattering of Rayleigh + Mie light with
 * the Earth's shadow and an isotropic multiple-scattering term (rayleigh.c
 * derives it and is its CPU twin), on extinction.glsl's closed-form
 * optical depths: no texture, no ray march; the sun's depth is taken at
 * three nodes of the view ray's lit part and each segment between them
 * integrates in closed form. */
uniform vec3 u_sun_depth;       /* optical depth toward the sun from the observer */
uniform vec3 u_mie_phase;       /* Cornette-Shanks: k, 1 + g^2, 2 g (rayleigh.c) */
uniform vec4 u_rl_geometry;     /* r_obs, R_planet, H_rayleigh, H_mie (km)        */
uniform vec3 u_rl_multiple;     /* isotropic phase of multiple scattering         */

/* (e^-a - e^-b) / (b - a) without cancellation: e^-min * (1 - e^-|b-a|) / |b-a| */
vec3 sky_exp_difference(vec3 a, vec3 b)
{
    vec3 x = abs(b - a);
    vec3 g = mix((1.0 - exp(-x)) / max(x, vec3(1e-4)), 1.0 - 0.5 * x, step(x, vec3(1e-3)));
    return exp(-min(a, b)) * g;
}

/* Column toward the sun from a point, per unit of the observer's vertical
 * depth (rayleigh.c's sun_column: the tangent point's grazing ray both
 * ways less the far side above the point when mu < 0). */
float sky_sun_column(float H, float r, float mu, float z, float r0_minus_rt, float rt)
{
    float point = exp(min(-z / H, 0.0));
    float up = point * sky_chapman(r / H, abs(mu));
    float grazing = 2.0 * sqrt(1.5707963 * rt / H) * exp(min(r0_minus_rt / H, 80.0));
    return mu >= 0.0 ? up : max(grazing - up, 0.0);
}

vec3 sky_rayleigh_radiance(vec3 view)
{
    vec3 d = sky_horizon_clamp(view);
    float m_rayleigh, m_mie;
    vec3 view_depth = sky_view_depth(d, m_rayleigh, m_mie);
    float mu = max(d.y, 0.0);
    float c = dot(d, u_sun_dir);
    float sy = u_sun_dir.y;
    float r0 = u_rl_geometry.x, R = u_rl_geometry.y, HR = u_rl_geometry.z, HM = u_rl_geometry.w;
    float rayleigh_phase = 0.0596831 * (1.0 + c * c); /* 3 / (16 pi) (1 + c^2) */
    float mie_phase = u_mie_phase.x * (1.0 + c * c) / pow(max(u_mie_phase.y - u_mie_phase.z * c, 1e-4), 1.5);

    /* the Earth's shadow along the view ray: [0, t_lit) (rayleigh.c) */
    float t_lit = 0.0;
    float C = (r0 - R) * (r0 + R) - (r0 * sy) * (r0 * sy);
    if (sy < 0.0 && C < 0.0) {
        float A = max(1.0 - c * c, 0.0), B = r0 * (mu - sy * c);
        t_lit = -C / max(B + sqrt(max(B * B - A * C, 0.0)), 1e-6);
        if (c > 0.0) t_lit = min(t_lit, -r0 * sy / c);
    }
    float q = t_lit * (2.0 * r0 * mu + t_lit);
    float u_lit = exp(-(q / (sqrt(r0 * r0 + q) + r0)) / HR);

    /* the sun's depth at the nodes u_lit * (1, 0.45, 0.15) and 0 at the top */
    float oz2 = r0 * r0 / u_chapman_x.z;
    vec3 lit = vec3(0.0);
    float u_hi = 0.0;
    vec3 e_hi = view_depth; /* u = 0: the whole view column, no sun depth */
    for (int k = 2; k >= 0; k--) {
        float node = k == 0 ? 1.0 : (k == 1 ? 0.45 : 0.15);
        float u = u_lit * node;
        float z = -HR * log(max(u, 1e-30));
        float w = z * (2.0 * r0 + z);
        float t = w / (r0 * mu + sqrt(r0 * r0 * mu * mu + w));
        float r = r0 + z, a = r0 * sy + t * c, mu_s = clamp(a / r, -1.0, 1.0);
        float rt = sqrt(max(w + r0 * r0 - a * a, 0.0));
        float r0_minus_rt = (a * a - w) / (r0 + rt);
        float col_r = sky_sun_column(HR, r, mu_s, z, r0_minus_rt, rt);
        float col_m = sky_sun_column(HM, r, mu_s, z, r0_minus_rt, rt);
        float crossings = r * r <= oz2 ? 1.0 : (mu_s < 0.0 && rt * rt < oz2 ? 2.0 : 0.0);
        float col_o = crossings * inversesqrt(max(1.0 - rt * rt / oz2, 1e-4));
        vec3 S = min(u_tau_rayleigh * col_r + u_tau_mie_ext * col_m + u_tau_ozone * col_o, vec3(1e4));
        vec3 e = view_depth * (1.0 - u) + S;
        lit += (u - u_hi) * sky_exp_difference(e_hi, e);
        u_hi = u;
        e_hi = e;
    }
    vec3 scattered = u_tau_rayleigh * (m_rayleigh * (rayleigh_phase + u_rl_multiple)) +
                     u_tau_mie_sca * (m_mie * (mie_phase + u_rl_multiple));
    return u_sun_irradiance * scattered * lit;
}

#ifndef SKY_HAS_BLEND
vec3 sky_atmosphere(vec3 d, vec3 day)
{
    return sky_or_ground(d, sky_rayleigh_radiance(d) * sky_eclipse_dim(d) + sky_night_floor(d));
}
#endif
