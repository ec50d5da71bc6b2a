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
        vec3 tau = u_hl_rayleigh * col.x + u_hl_mie_ext * col.y + u_hl_ozone * col.z;
        vec3 e = exp(-tau);
        vec3 weight = transmittance * hl_seg_weight(tau, e);
        float mus = clamp((r0 * sun.y + (start + tm) * cos_theta) / rm, -1.0, 1.0);
        float vy = clamp((r0 * ct + start + tm) / rm, -1.0, 1.0);
        L += hl_segment_light(col, weight, rm, mus, vy, cos_theta, phase_r, phase_m);
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
