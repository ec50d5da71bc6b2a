/* multiscatter_build.frag: Hillaire 2020 sec. 5.5 on the GPU, one texel
 * (r, mu_s) per fragment: the GLSL twin of hillaire_cpu.c's
 * multiscatter_row. The first bounce with the real phase functions, the
 * rest with the isotropic phase; the directions about the sun of
 * hl_ms_direction, mirrored across the sun's plane:
 *   L_2nd = mean over w of L'(x, w), f_ms = mean of L_f(x, w),
 *   Psi = L_2nd / (1 - f_ms)   (eq. 5-10),
 * the sunlit Lambertian ground in L_2nd and its albedo x T in f_ms; and
 * L''s dipole D = 3 mean(L' w) and traceless quadrupole Q = 3 mean(L' w
 * w^T) - L_2nd. Five outputs: Psi with Q_xy's red, then the layers of
 * u_ms_moments: D_x with Q_xy's green, D_y with its blue, Q_xx, Q_yy. */
SKY_IN vec2 v_unit;
layout(location = 1) out vec4 sky_ms_dx;
layout(location = 2) out vec4 sky_ms_dy;
layout(location = 3) out vec4 sky_ms_qxx;
layout(location = 4) out vec4 sky_ms_qyy;

void main()
{
    float R = u_hl_geometry.x, Rt = u_hl_geometry.y, size = u_hl_misc.x, g = u_hl_misc.w;
    vec2 texel = floor(v_unit * vec2(size));
    float mu_s = hl_ms_mu_s(texel.x / (size - 1.0));
    float r = R + (Rt - R) * texel.y / (size - 1.0);
    vec2 sun = vec2(hl_clamp_sqrt(1.0 - mu_s * mu_s), mu_s); /* in the (x, y) plane */
    float nd = u_hl_steps.y, ns = u_hl_steps.z;
    vec3 l2 = vec3(0.0), fms = vec3(0.0), dx = vec3(0.0), dy = vec3(0.0), mxx = vec3(0.0), myy = vec3(0.0),
         mxy = vec3(0.0);
    for (int k = 0; k < 512; k++) {
        float kf = float(k);
        if (kf >= nd) break;
        float wk;
        vec3 w = hl_ms_direction(kf, nd, g, sun, wk);
        float mu = w.y;
        /* the sun's light turned toward x: from the sun into -w */
        float cos_sw = w.x * sun.x + w.y * sun.y;
        float phase_r = hl_phase_rayleigh(cos_sw), phase_m = hl_phase_cs(cos_sw, g);
        bool ground = mu < 0.0 && r * r * (mu * mu - 1.0) + R * R >= 0.0;
        float len;
        if (ground) {
            float den = -r * mu + hl_clamp_sqrt(r * r * (mu * mu - 1.0) + R * R);
            len = (r * r - R * R) > 0.0 && den > 0.0 ? (r * r - R * R) / den : 0.0;
        } else {
            len = hl_dist_to_top(r, mu);
        }
        vec3 tr = vec3(1.0), lk = vec3(0.0), fk = vec3(0.0);
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
                vec3 sc_r = u_hl_rayleigh * col.x * wgt, sc_m = u_hl_mie_sca * col.y * wgt;
                fk += sc_r + sc_m;
                tr *= e;
                float tm = 0.5 * (ta + tb), rm = hl_radius(r, mu, tm);
                float mus = clamp((w.x * tm * sun.x + (r + w.y * tm) * sun.y) / rm, -1.0, 1.0);
                lk += (sc_r * phase_r + sc_m * phase_m) * hl_sun_transmittance(rm, hl_clamp_sqrt(rm * rm - R * R), mus);
                ta = tb;
                ra = rb;
                da = db;
            }
        }
        if (ground) {
            vec3 gp = vec3(w.x * len, r + w.y * len, w.z * len);
            float mug = (gp.x * sun.x + gp.y * sun.y) / length(gp);
            fk += tr * u_hl_albedo;
            if (mug > 0.0) lk += tr * hl_sun_transmittance(R, 0.0, mug) * mug * u_hl_albedo / SKY_PI;
        }
        vec3 lw = lk * wk;
        l2 += lw;
        fms += fk * wk;
        dx += lw * w.x;
        dy += lw * w.y;
        mxx += lw * (w.x * w.x);
        myy += lw * (w.y * w.y);
        mxy += lw * (w.x * w.y);
    }
    vec3 qxy = 3.0 * mxy;
    SKY_FRAG_COLOR = vec4(l2 / max(1.0 - fms, vec3(1e-3)), qxy.r);
    sky_ms_dx = vec4(3.0 * dx, qxy.g);
    sky_ms_dy = vec4(3.0 * dy, qxy.b);
    sky_ms_qxx = vec4(3.0 * mxx - l2, 0.0);
    sky_ms_qyy = vec4(3.0 * myy - l2, 0.0);
}
