/* multiscatter_build.frag: one order of the light that reaches each
 * texel (r, mu_s) of the multiple-scattering table, on the GPU: the GLSL
 * twin of hillaire_cpu.c's order_row. Order 1 (u_ms_pass.x) is the
 * sunlight scattered once toward the texel by the real phase functions,
 * and the sunlit Lambertian ground; a later order is the previous order's
 * light (u_ms_order) scattered once more toward it (hl_scatter_moments),
 * and the ground's reflection of the previous order's irradiance. The
 * directions about the sun of hl_ms_direction, mirrored across the sun's
 * plane. Seven outputs, the layers of SKY_TEX_MS_ORDER (hillaire.c's
 * order_slot): the mean, D_x, D_y, Q_xx, Q_yy and Z_4 with Q_xy's and
 * Z_3's channels in their alphas, then the irradiance of a level surface
 * facing up; the mean and the irradiance as their sixteenth roots, the
 * rest per unit mean (as the lookups interpolate them):
 *   mean = mean of L(w), D = 3 mean(L w), Q = 3 mean(L w w^T) - mean,
 *   Z_l = (2l + 1) mean(L P_l(s . w)) (order 1 alone),
 *   irradiance = 4 pi mean(L max(w_y, 0)). */
SKY_IN vec2 v_unit;
uniform sampler2DArray u_ms_order; /* the previous order (SKY_TEX_MS_ORDER_PREV) */
uniform SKY_UP vec4 u_ms_pass;     /* the order, its directions (half), steps, and
                                      how many directions follow the aerosol's peak */
layout(location = 1) out vec4 sky_ms_dx;
layout(location = 2) out vec4 sky_ms_dy;
layout(location = 3) out vec4 sky_ms_qxx;
layout(location = 4) out vec4 sky_ms_qyy;
layout(location = 5) out vec4 sky_ms_z4;
layout(location = 6) out vec4 sky_ms_irradiance;

void main()
{
    float R = u_hl_geometry.x, size = u_hl_misc.x, g = u_hl_misc.w;
    vec2 texel = floor(v_unit * vec2(size));
    float mu_s = hl_ms_mu_s(texel.x / (size - 1.0));
    float r = R + (u_hl_geometry.y - R) * texel.y / (size - 1.0);
    vec2 sun = vec2(hl_clamp_sqrt(1.0 - mu_s * mu_s), mu_s); /* in the (x, y) plane */
    bool first = u_ms_pass.x < 1.5;
    float nd = u_ms_pass.y, ns = u_ms_pass.z;
    vec3 mean = vec3(0.0), dx = vec3(0.0), dy = vec3(0.0), mxx = vec3(0.0), myy = vec3(0.0), mxy = vec3(0.0);
    vec3 z3 = vec3(0.0), z4 = vec3(0.0), up = vec3(0.0);
    for (int k = 0; k < 512; k++) {
        float kf = float(k);
        if (kf >= nd) break;
        float wk;
        vec3 w = hl_ms_direction(kf, nd, u_ms_pass.w, g, sun, wk);
        float mu = w.y;
        /* the sun's light turned toward x: from the sun into -w */
        float cos_sw = w.x * sun.x + w.y * sun.y, c2 = cos_sw * cos_sw;
        float phase_r = hl_phase_rayleigh(cos_sw), phase_m = hl_phase_cs(cos_sw, g);
        bool ground = mu < 0.0 && r * r * (mu * mu - 1.0) + R * R >= 0.0;
        float len;
        if (ground) {
            float den = -r * mu + hl_clamp_sqrt(r * r * (mu * mu - 1.0) + R * R);
            len = (r * r - R * R) > 0.0 && den > 0.0 ? (r * r - R * R) / den : 0.0;
        } else {
            len = hl_dist_to_top(r, mu);
        }
        vec3 tr = vec3(1.0), lk = vec3(0.0);
        if (len > 0.0) {
            float tl = clamp(-r * mu, 0.0, len), n1 = hl_layout_n1(ns, tl, len), n2 = ns - n1;
            float ta = 0.0, ra = r;
            vec3 da = hl_density(ra);
            for (int j = 1; j <= 256; j++) {
                float jf = float(j);
                if (jf > ns) break;
                float tb = hl_layout_t(jf, n1, n2, tl, len), rb = hl_radius(r, mu, tb);
                vec3 db = hl_density(rb);
                vec3 col = hl_column(da, ra, db, rb, tb - ta);
                vec3 tau = u_hl_rayleigh * col.x + u_hl_mie_ext * col.y + u_hl_ozone * col.z;
                vec3 e = exp(-tau);
                vec3 wgt = hl_seg_weight(tau, e) * tr;
                float tm = 0.5 * (ta + tb), rm = hl_radius(r, mu, tm);
                float mus = clamp((w.x * tm * sun.x + (r + w.y * tm) * sun.y) / rm, -1.0, 1.0);
                vec3 jr, jm;
                if (first) {
                    vec3 ts = hl_sun_transmittance(rm, hl_clamp_sqrt(rm * rm - R * R), mus);
                    jr = phase_r * ts;
                    jm = phase_m * ts;
                } else { /* w in the midpoint's frame */
                    float vy = clamp((tm + r * mu) / rm, -1.0, 1.0), sh = hl_clamp_sqrt(1.0 - mus * mus);
                    float vx = sh > 1e-6 ? clamp((cos_sw - mus * vy) / sh, -1.0, 1.0) : 0.0;
                    hl_scatter_moments(u_ms_order, hl_ms_uv(rm, mus), vx, vy, cos_sw, jr, jm);
                }
                lk += (u_hl_rayleigh * col.x * jr + u_hl_mie_sca * col.y * jm) * wgt;
                tr *= e;
                ta = tb;
                ra = rb;
                da = db;
            }
        }
        if (ground) { /* the irradiance there: the sun's, or the previous order's */
            vec3 gp = vec3(w.x * len, r + w.y * len, w.z * len);
            float mug = clamp((gp.x * sun.x + gp.y * sun.y) / length(gp), -1.0, 1.0);
            vec3 irradiance = vec3(0.0);
            if (!first) irradiance = hl_ms_power(texture(u_ms_order, vec3(hl_ms_uv(R, mug), 6.0)).rgb);
            else if (mug > 0.0) irradiance = hl_sun_transmittance(R, 0.0, mug) * mug;
            lk += tr * irradiance * u_hl_albedo / SKY_PI;
        }
        vec3 lw = lk * wk;
        mean += lw;
        dx += lw * w.x;
        dy += lw * w.y;
        mxx += lw * (w.x * w.x);
        myy += lw * (w.y * w.y);
        mxy += lw * (w.x * w.y);
        up += lw * max(w.y, 0.0);
        if (first) {
            z3 += lw * (0.5 * cos_sw * (5.0 * c2 - 3.0));
            z4 += lw * (0.125 * (35.0 * c2 * c2 - 30.0 * c2 + 3.0));
        }
    }
    /* as the lookups read them: the mean's sixteenth root, the rest per
     * unit mean (hillaire_cpu.c's ms_encode) */
    vec3 per_mean = vec3(greaterThan(mean, vec3(0.0))) / max(mean, vec3(1e-37));
    vec3 qxy = 3.0 * mxy * per_mean;
    z3 *= 7.0 * per_mean;
    SKY_FRAG_COLOR = vec4(pow(max(mean, 0.0), vec3(0.0625)), qxy.r);
    sky_ms_dx = vec4(3.0 * dx * per_mean, qxy.g);
    sky_ms_dy = vec4(3.0 * dy * per_mean, qxy.b);
    sky_ms_qxx = vec4((3.0 * mxx - mean) * per_mean, z3.r);
    sky_ms_qyy = vec4((3.0 * myy - mean) * per_mean, z3.g);
    sky_ms_z4 = vec4(9.0 * z4 * per_mean, z3.b);
    sky_ms_irradiance = vec4(pow(max(4.0 * SKY_PI * up, 0.0), vec3(0.0625)), 0.0);
}
