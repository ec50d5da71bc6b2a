/* rayleigh.glsl: the analytic sky (rayleigh.c derives it and is its CPU
 * twin, line for line): single scattering of Rayleigh + Mie light up to
 * the Earth's shadow, and an isotropic multiple-scattering term that also
 * lights the shadow, on extinction.glsl's closed-form optical depths. No
 * texture, no ray march: six nodes along the view ray and a closed-form
 * integral over each segment between them. Compiled into both stages: the
 * dome's vertices evaluate the integrals (dome.vert). */
uniform SKY_UP vec3 u_mie_phase;       /* Cornette-Shanks: k, 1 + g^2, 2 g (rayleigh.c) */
uniform SKY_UP vec4 u_rl_geometry;     /* r_obs, R_planet, H_rayleigh, H_mie (km)        */
uniform SKY_UP vec3 u_rl_multiple;     /* isotropic phase of multiple scattering         */
uniform SKY_UP vec3 u_rl_ozone;        /* ozone tent: peak, half width (km), 1 / column  */
uniform SKY_UP vec3 u_rl_skylight;     /* the skylight's floor under ms (rayleigh.c)     */

/* The mean of e^-E over a segment whose exponent runs linearly from a
 * to b, from the nodes' exponentials ta, tb (rayleigh.c's seg_mean). */
vec3 sky_seg_mean(vec3 ta, vec3 tb, vec3 a, vec3 b)
{
    vec3 x = b - a;
    vec3 near = step(abs(x), vec3(1e-3));
    return mix((ta - tb) / mix(x, vec3(1.0), near), max(ta, tb) * (1.0 - 0.5 * abs(x)), near);
}

/* Column toward the sun from a point, per unit of the observer's vertical
 * depth (rayleigh.c's sun_column). */
float sky_sun_column(float H, float r, float mu, float point, float r0_minus_rt, float rt)
{
    float up = point * sky_chapman(r / H, abs(mu));
    if (mu >= 0.0) return up; /* by day, every pixel: the branch is coherent */
    float grazing = 2.0 * sqrt(1.5707963 * rt / H) * exp(min(r0_minus_rt / H, 80.0));
    return max(grazing - up, 0.0);
}

/* The ozone tent's column above height h, km of peak density. */
float sky_ozone_above(float h)
{
    float peak = u_rl_ozone.x, hw = u_rl_ozone.y;
    if (h <= peak - hw) return hw;
    if (h <= peak) return hw - (h - (peak - hw)) * (h - (peak - hw)) / (2.0 * hw);
    if (h <= peak + hw) return (peak + hw - h) * (peak + hw - h) / (2.0 * hw);
    return 0.0;
}

/* Distance along the view ray to where the Rayleigh column above is u. */
float sky_rl_distance(float u, float mu)
{
    float r0 = u_rl_geometry.x, z = -u_rl_geometry.z * log(max(u, 1e-30));
    float w = z * (2.0 * r0 + z);
    return w / max(r0 * mu + sqrt(r0 * r0 * mu * mu + w), 1e-9);
}

/* One node of the view ray at distance t (rayleigh.c's node_at). */
void sky_rl_node(float t, float mu, float c, float m_r, float m_m, out float u_r, out float u_m, out vec3 sun,
                 out vec3 ms)
{
    float sy = u_sun_dir.y;
    float r0 = u_rl_geometry.x, R = u_rl_geometry.y, HR = u_rl_geometry.z, HM = u_rl_geometry.w;
    float w = t * (2.0 * r0 * mu + t);
    float r = sqrt(r0 * r0 + w), z = w / (r + r0);
    float a = r0 * sy + t * c;
    float rt = sqrt(max(w + r0 * r0 - a * a, 0.0));
    float raise = (a < 0.0 && rt < R) ? r * (R / max(rt, 1e-3 * R) - 1.0) : 0.0;
    float re = r + raise, ze = z + raise, ae = a * re / r, rte = raise > 0.0 ? R : rt;
    float mu_s = clamp(ae / re, -1.0, 1.0);
    float r0_minus_rt = raise > 0.0 ? r0 - R : (a * a - w) / (r0 + rt);
    /* the point's own columns (e^-z/H), shared by the view's share below;
     * a raised point's are its own */
    float er = exp(-z / HR), em = exp(-z / HM);
    float pr = er, pm = em;
    if (raise > 0.0) {
        pr = exp(-ze / HR);
        pm = exp(-ze / HM);
    }
    float col_r = sky_sun_column(HR, re, mu_s, pr, r0_minus_rt, rte);
    float col_m = sky_sun_column(HM, re, mu_s, pm, r0_minus_rt, rte);
    float oz_r = R + u_rl_ozone.x, h_t = min(rte, re) - R;
    float oz_above = sky_ozone_above(ze + r0 - R);
    float oz_dip = mu_s < 0.0 ? sky_ozone_above(h_t) - oz_above : 0.0;
    float k_up = rte / max(oz_r, re), k_dip = min(rte / oz_r, 1.0); /* the dip at the peak's cosine (rayleigh.c) */
    float col_o = (oz_above * inversesqrt(max(1.0 - k_up * k_up, 1e-3)) +
                   2.0 * oz_dip * inversesqrt(max(1.0 - k_dip * k_dip, 1e-3))) * u_rl_ozone.z;
    float mu_v = clamp((r0 * mu + t) / r, 0.0, 1.0);
    u_r = er * sky_chapman(r / HR, mu_v) / m_r;
    u_m = em * sky_chapman(r / HM, mu_v) / m_m;
    sun = min(u_tau_rayleigh * col_r + u_tau_mie_ext * col_m + u_tau_ozone * col_o, vec3(1e4));
    ms = sun;
    if (raise > 0.0) ms = mix(sun, vec3(sun.g), 1.0 - exp(-raise / HR)); /* neutral in the shadow (rayleigh.c) */
    /* the knee s_0 = 3 and the climb's e-folding 4 H_R (rayleigh.c) */
    if (any(greaterThan(ms, vec3(3.0)))) ms = mix(ms, 3.0 + 3.0 * log(max(ms / 3.0, vec3(1.0))), step(vec3(3.0), ms));
    ms += 0.25 * raise / HR;
    /* the skylight's floor, fading over H_R above the eye (rayleigh.c) */
    ms -= exp(-z / HR) * max(ms - u_rl_skylight, vec3(0.0));
}

/* The view ray's integrals, everything but the phase functions: what the
 * Rayleigh phase multiplies (single_r), what the Mie phase multiplies
 * (single_m), and the multiple-scattering light (multiple, its isotropic
 * phase in), all times the sun's irradiance. They vary slowly with the
 * view direction, so the dome evaluates them per vertex (dome.vert) and
 * its pixels only the phases (sky_rayleigh_phases), which vary fast near
 * the sun (the Mie aureole): the ARCHITECTURE's "per vertex what varies
 * slowly". Every other program evaluates both per pixel. */
void sky_rayleigh_integrals(vec3 view, out vec3 single_r, out vec3 single_m, out vec3 multiple)
{
    vec3 d = sky_horizon_clamp(view);
    float mu = max(d.y, 0.0);
    float m_rayleigh = sky_chapman(u_chapman_x.x, mu), m_mie = sky_chapman(u_chapman_x.y, mu);
    float m_ozone = inversesqrt(max(1.0 - u_chapman_x.z * (1.0 - mu * mu), 1e-4));
    float c = dot(d, u_sun_dir);
    float sy = u_sun_dir.y;
    float r0 = u_rl_geometry.x, R = u_rl_geometry.y, HR = u_rl_geometry.z;

    /* the Earth's shadow along the view ray: [0, t_lit) (rayleigh.c) */
    float t_lit = 0.0, sunlit = 1.0;
    float C = (r0 - R) * (r0 + R) - (r0 * sy) * (r0 * sy);
    if (sy < 0.0 && C < 0.0) {
        float A = max(1.0 - c * c, 0.0), B = r0 * (mu - sy * c), root = sqrt(max(B * B - A * C, 0.0));
        t_lit = B > 0.0 ? -C / (B + root) : (-B + root) / max(A, 1e-12);
        if (c > 0.0) t_lit = min(t_lit, -r0 * sy / c);
        float t_top = sky_rl_distance(1e-6, mu);
        if (t_lit > t_top) sunlit = 0.0;
        t_lit = min(t_lit, t_top);
    }
    float q = t_lit * (2.0 * r0 * mu + t_lit);
    float u_lit = exp(-(q / (sqrt(r0 * r0 + q) + r0)) / HR);

    vec3 a_r = u_tau_rayleigh * m_rayleigh, a_m = u_tau_mie_ext * m_mie, a_o = u_tau_ozone * m_ozone;
    vec3 s_m = u_tau_mie_sca * m_mie;
    single_r = vec3(0.0);
    single_m = vec3(0.0);
    multiple = vec3(0.0);
    float lo_r = 0.0, lo_m = 0.0;
    vec3 lo_ess = vec3(0.0), lo_ems = vec3(0.0), lo_tss = vec3(0.0), lo_tms = vec3(0.0);
    bool first = true;
    /* nodes: the shadow's at 0, 3 and 12 H_R (or its edge), the edge, the
     * lit part at 0.45 and 0.15 of the edge's column, the top */
    for (int k = 0; k < 7; k++) {
        /* an eye in sunlight: the shadow's segments have no length */
        if (k < 3 && t_lit <= 0.0) continue;
        float hi_r = 0.0, hi_m = 0.0;
        vec3 sun = vec3(0.0), ms = vec3(0.0);
        if (k < 6) {
            float t = k == 3 ? t_lit : min(t_lit, HR * (k == 1 ? 3.0 : 12.0));
            if (k == 0) t = 0.0;
            if (k > 3) t = sky_rl_distance(u_lit * (k == 4 ? 0.45 : 0.15), mu);
            sky_rl_node(t, mu, c, m_rayleigh, m_mie, hi_r, hi_m, sun, ms);
        }
        vec3 v = (a_r + a_o) * (1.0 - hi_r) + a_m * (1.0 - hi_m);
        vec3 hi_ess = v + sun, hi_ems = v + ms;
        vec3 hi_tss = exp(-hi_ess), hi_tms = exp(-hi_ems);
        if (!first) {
            if (k <= 3) {
                /* a segment in the shadow: multiple scattering alone, its
                 * exponent less ln u linear in ln u (rayleigh.c) */
                float lr_lo = log(max(lo_r, 1e-30)), lr_hi = log(max(hi_r, 1e-30));
                float lm_lo = log(max(lo_m, 1e-30)), lm_hi = log(max(hi_m, 1e-30));
                multiple += a_r * ((lr_lo - lr_hi) *
                                   sky_seg_mean(lo_tms * lo_r, hi_tms * hi_r, lo_ems - lr_lo, hi_ems - lr_hi)) +
                            s_m * ((lm_lo - lm_hi) *
                                   sky_seg_mean(lo_tms * lo_m, hi_tms * hi_m, lo_ems - lm_lo, hi_ems - lm_hi));
            } else {
                vec3 w_r = a_r * (lo_r - hi_r), w_m = s_m * (lo_m - hi_m);
                multiple += (w_r + w_m) * sky_seg_mean(lo_tms, hi_tms, lo_ems, hi_ems);
                vec3 lit = sunlit * sky_seg_mean(lo_tss, hi_tss, lo_ess, hi_ess);
                single_r += w_r * lit;
                single_m += w_m * lit;
            }
        }
        first = false;
        lo_r = hi_r;
        lo_m = hi_m;
        lo_ess = hi_ess;
        lo_ems = hi_ems;
        lo_tss = hi_tss;
        lo_tms = hi_tms;
    }
    /* the gain at the stage's default precision (the vertex stage's
     * highp: 2^gain is past mediump's range at night, and an expression of
     * mediump uniforms alone is evaluated at mediump) */
    float gain = u_sun_gain_log2;
    vec3 sun_irradiance = u_sun_irradiance * exp2(gain);
    single_r *= sun_irradiance;
    single_m *= sun_irradiance;
    multiple *= sun_irradiance * u_rl_multiple;
}

/* The radiance from the integrals and the phases of the view direction. */
vec3 sky_rayleigh_phases(vec3 view, vec3 single_r, vec3 single_m, vec3 multiple)
{
    float c = dot(sky_horizon_clamp(view), u_sun_dir);
    float rayleigh_phase = 0.0596831 * (1.0 + c * c); /* 3 / (16 pi) (1 + c^2) */
    float mie_phase = u_mie_phase.x * (1.0 + c * c) / pow(max(u_mie_phase.y - u_mie_phase.z * c, 1e-4), 1.5);
    return single_r * rayleigh_phase + single_m * mie_phase + multiple;
}

vec3 sky_rayleigh_radiance(vec3 view)
{
    vec3 single_r, single_m, multiple;
    sky_rayleigh_integrals(view, single_r, single_m, multiple);
    return sky_rayleigh_phases(view, single_r, single_m, multiple);
}

#ifndef SKY_HAS_BLEND
/* the sky around an analytic radiance already evaluated (the dome's) and
 * the moonlit sky's vertex value */
vec3 sky_atmosphere_over(vec3 d, vec3 analytic, vec3 moonlit)
{
    return sky_or_ground(d, (analytic + sky_moonlit(moonlit)) * sky_eclipse_dim(d) + sky_night_floor(d));
}
vec3 sky_atmosphere(vec3 d, vec3 moonlit) { return sky_atmosphere_over(d, sky_rayleigh_radiance(d), moonlit); }
#endif
