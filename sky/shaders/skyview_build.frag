/* skyview_build.frag: Hillaire 2020's sky-view table built on the GPU
 * (CORE33), one texel per fragment: the GLSL twin of hillaire_cpu.c's
 * skyview_row. Radiance per unit solar illuminance (eq. 1-3 and 11),
 * segments in the energy-conserving form (S - S T) / sigma_t. */
SKY_IN vec2 v_unit;
void main()
{
    float R = u_hl_geometry.x, Rt = u_hl_geometry.y, r0 = u_hl_geometry.w;
    /* this texel's view: the inverse of the table's mapping (hillaire.c) */
    vec2 texel = floor(v_unit * u_hl_sizes.xy);
    float x = texel.x / (u_hl_sizes.x - 1.0), y = texel.y / (u_hl_sizes.y - 1.0);
    float th_h = SKY_PI - asin(clamp(R / r0, 0.0, 1.0)), th;
    bool ground = y > 0.5;
    if (!ground) {
        float q = 1.0 - 2.0 * y;
        th = th_h * (1.0 - q * q);
    } else {
        float q = 2.0 * y - 1.0;
        th = th_h + (SKY_PI - th_h) * q * q;
    }
    float caz = clamp(1.0 - 2.0 * x * x, -1.0, 1.0), saz = hl_clamp_sqrt(1.0 - caz * caz);
    float ct = cos(th), st = sin(th);
    vec3 view = vec3(st * caz, ct, st * saz);
    float mu_sun = u_hl_misc.y;
    vec3 sun = vec3(hl_clamp_sqrt(1.0 - mu_sun * mu_sun), mu_sun, 0.0);
    float cos_theta = dot(view, sun), g = u_hl_misc.w;
    float phase_r = hl_phase_rayleigh(cos_theta), phase_m = hl_phase_cs(cos_theta, g);

    /* enter the shell from above if the observer is outside it */
    float r = r0, mu = ct, start = 0.0;
    vec3 L = vec3(0.0);
    if (r > Rt) {
        float disc = r * r * (mu * mu - 1.0) + Rt * Rt;
        if (mu >= 0.0 || disc < 0.0) {
            SKY_FRAG_COLOR = vec4(0.0, 0.0, 0.0, 1.0);
            return;
        }
        start = (r * r - Rt * Rt) / (-r * mu + sqrt(disc));
        r = Rt;
        mu = clamp((r0 * ct + start) / Rt, -1.0, 1.0);
    }
    float len;
    if (ground) {
        float disc = r * r * (mu * mu - 1.0) + R * R, den2 = -r * mu + hl_clamp_sqrt(disc);
        len = (r * r - R * R) > 0.0 && den2 > 0.0 ? (r * r - R * R) / den2 : 0.0;
    } else {
        len = hl_dist_to_top(r, mu);
    }
    /* samples: all of them for the longest rays, a third for short ones */
    float full = 2.0 * u_hl_geometry.z;
    float n = min(max(ceil(u_hl_misc.z * clamp(sqrt(max(len / full, 0.0)), 1.0 / 3.0, 1.0)), 4.0), u_hl_misc.z);
    /* segments close quadratically onto the ray's lowest point */
    float tl = clamp(-r * mu, 0.0, len);
    float n1 = hl_layout_n1(n, tl, len), n2 = n - n1;
    vec3 transmittance = vec3(1.0);
    float ta = 0.0, ra = r;
    vec3 da = hl_density(ra);
    for (int k = 1; k <= 256; k++) {
        float kf = float(k);
        if (kf > n) break;
        float tb = hl_layout_t(kf, n1, n2, tl, len);
        float rb = hl_radius(r, mu, tb);
        vec3 db = hl_density(rb);
        vec3 col = hl_column(da, ra, db, rb, tb - ta);
        float tm = 0.5 * (ta + tb), rm = hl_radius(r, mu, tm);
        float rho = hl_clamp_sqrt(rm * rm - R * R);
        vec3 tau = u_hl_rayleigh * col.x + u_hl_mie_ext * col.y + u_hl_ozone * col.z;
        vec3 e = exp(-tau);
        vec3 weight = transmittance * hl_seg_weight(tau, e);
        float mus = clamp((r0 * sun.y + (start + tm) * cos_theta) / rm, -1.0, 1.0);
        vec3 ts = hl_sun_transmittance(rm, rho, mus);
        vec2 ms_uv = vec2(hl_unit_to_tex(hl_ms_u(mus), u_hl_misc.x),
                          hl_unit_to_tex(clamp((rm - R) / (Rt - R), 0.0, 1.0), u_hl_misc.x));
        vec4 psi = SKY_TEX2D(u_multiscatter_table, ms_uv);
        vec4 mdx = texture(u_ms_moments, vec3(ms_uv, 0.0)), mdy = texture(u_ms_moments, vec3(ms_uv, 1.0));
        vec3 qxx = texture(u_ms_moments, vec3(ms_uv, 2.0)).rgb, qyy = texture(u_ms_moments, vec3(ms_uv, 3.0)).rgb;
        vec3 qxy = vec3(psi.a, mdx.a, mdy.a);
        /* the view in the sample's frame: y up, x toward the sun's azimuth;
         * the second order scattered with the real phase functions' first
         * Legendre terms (hillaire_cpu.c's skyview_row) */
        float vy = clamp((r0 * ct + start + tm) / rm, -1.0, 1.0), sh = hl_clamp_sqrt(1.0 - mus * mus);
        float vx = sh > 1e-6 ? clamp((cos_theta - mus * vy) / sh, -1.0, 1.0) : 0.0;
        float vz2 = max(1.0 - vx * vx - vy * vy, 0.0);
        vec3 l1 = mdx.rgb * vx + mdy.rgb * vy;
        vec3 l2 = 2.5 * (qxx * (vx * vx) + qyy * (vy * vy) - (qxx + qyy) * vz2 + 2.0 * qxy * (vx * vy));
        L += u_hl_rayleigh * col.x * weight * (phase_r * ts + max(psi.rgb + u_hl_chi.z * l2, 0.0)) +
             u_hl_mie_sca * col.y * weight * (phase_m * ts + max(psi.rgb + u_hl_chi.x * l1 + u_hl_chi.y * l2, 0.0));
        transmittance *= e;
        ta = tb;
        ra = rb;
        da = db;
    }
    if (ground) { /* at altitude 0 the ray has no length, the ground still light */
        float rg = hl_radius(r, mu, len);
        float mug = (r0 * sun.y + (start + len) * cos_theta) / rg;
        if (mug > 0.0) L += transmittance * u_hl_albedo / SKY_PI * mug * hl_sun_transmittance(R, 0.0, clamp(mug, 0.0, 1.0));
    }
    SKY_FRAG_COLOR = vec4(L, 1.0);
}
