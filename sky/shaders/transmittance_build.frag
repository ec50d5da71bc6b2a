/* transmittance_build.frag: Hillaire's transmittance table (Bruneton's
 * (r, mu) mapping) on the GPU, one texel per fragment: the GLSL twin of
 * hillaire_cpu.c's build. */
SKY_IN vec2 v_unit;

void main()
{
    float R = u_hl_geometry.x, Rt = u_hl_geometry.y, H = u_hl_geometry.z;
    vec2 texel = floor(v_unit * u_hl_sizes.zw);
    float xmu = texel.x / (u_hl_sizes.z - 1.0), xr = texel.y / (u_hl_sizes.w - 1.0);
    /* the inverse of the mapping: rho = H x_r, the distance to the top
     * between d_min and d_max, mu by the law of cosines */
    float rho = H * xr, r = sqrt(rho * rho + R * R);
    float dmin = Rt - r, dmax = rho + H, d = dmin + xmu * (dmax - dmin);
    float mu = d <= 0.0 ? 1.0 : clamp((H * H - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0);
    float len = hl_dist_to_top(r, mu), n = u_hl_steps.x;
    float tl = clamp(-r * mu, 0.0, len), n1 = hl_layout_n1(n, tl, len), n2 = n - n1;
    vec3 column = vec3(0.0);
    float ta = 0.0, ra = r;
    vec3 da = hl_density(ra);
    for (int k = 1; k <= 256; k++) {
        float kf = float(k);
        if (kf > n) break;
        float tb = hl_layout_t(kf, n1, n2, tl, len), rb = hl_radius(r, mu, tb);
        vec3 db = hl_density(rb);
        column += hl_column(da, ra, db, rb, tb - ta);
        ta = tb;
        ra = rb;
        da = db;
    }
    vec3 tau = u_hl_rayleigh * column.x + u_hl_mie_ext * column.y + u_hl_ozone * column.z;
    SKY_FRAG_COLOR = vec4(exp(-tau), 1.0);
}
