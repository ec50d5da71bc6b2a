/* multiscatter_build.frag: Hillaire 2020 sec. 5.5 on the GPU, one texel
 * (r, mu_s) per fragment: the GLSL twin of hillaire_cpu.c's
 * multiscatter_row. With the isotropic phase and equal-area directions
 * (a Fibonacci half sphere mirrored across the sun's plane):
 *   L_2nd = mean over w of L'(x, w), f_ms = mean of L_f(x, w),
 *   Psi = L_2nd / (1 - f_ms)   (eq. 5-10),
 * the sunlit Lambertian ground in L_2nd and its albedo x T in f_ms. */
SKY_IN vec2 v_unit;

void main()
{
    float R = u_hl_geometry.x, Rt = u_hl_geometry.y, size = u_hl_misc.x;
    vec2 texel = floor(v_unit * vec2(size));
    float mu_s = clamp(2.0 * texel.x / (size - 1.0) - 1.0, -1.0, 1.0);
    float r = R + (Rt - R) * texel.y / (size - 1.0);
    vec2 sun = vec2(hl_clamp_sqrt(1.0 - mu_s * mu_s), mu_s); /* in the (x, y) plane */
    float nd = u_hl_steps.y, ns = u_hl_steps.z, golden = SKY_PI * (3.0 - sqrt(5.0));
    vec3 l2 = vec3(0.0), fms = vec3(0.0);
    for (int k = 0; k < 512; k++) {
        float kf = float(k);
        if (kf >= nd) break;
        float z = 1.0 - (kf + 0.5) / nd, s = hl_clamp_sqrt(1.0 - z * z), phi = golden * kf;
        vec3 w = vec3(s * cos(phi), s * sin(phi), z);
        float mu = w.y;
        bool ground = mu < 0.0 && r * r * (mu * mu - 1.0) + R * R >= 0.0;
        float len;
        if (ground) {
            float den = -r * mu + hl_clamp_sqrt(r * r * (mu * mu - 1.0) + R * R);
            len = (r * r - R * R) > 0.0 && den > 0.0 ? (r * r - R * R) / den : 0.0;
        } else {
            len = hl_dist_to_top(r, mu);
        }
        vec3 tr = vec3(1.0);
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
                vec3 sc = (u_hl_rayleigh * col.x + u_hl_mie_sca * col.y) * hl_seg_weight(tau, e) * tr;
                fms += sc;
                tr *= e;
                float tm = 0.5 * (ta + tb), rm = hl_radius(r, mu, tm);
                float mus = clamp((w.x * tm * sun.x + (r + w.y * tm) * sun.y) / rm, -1.0, 1.0);
                l2 += sc * hl_sun_transmittance(rm, hl_clamp_sqrt(rm * rm - R * R), mus) / (4.0 * SKY_PI);
                ta = tb;
                ra = rb;
                da = db;
            }
        }
        if (ground) {
            vec3 g = vec3(w.x * len, r + w.y * len, w.z * len);
            float rg = length(g);
            fms += tr * u_hl_albedo;
            float mug = (g.x * sun.x + g.y * sun.y) / rg;
            if (mug > 0.0) l2 += tr * hl_sun_transmittance(R, 0.0, mug) * mug * u_hl_albedo / SKY_PI;
        }
    }
    vec3 f = fms / nd;
    SKY_FRAG_COLOR = vec4((l2 / nd) / max(1.0 - f, vec3(1e-3)), 1.0);
}
