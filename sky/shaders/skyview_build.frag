/* skyview_build.frag: Hillaire 2020's sky-view table built on the GPU
 * (CORE33), one texel per fragment: the GLSL twin of hillaire_cpu.c's
 * skyview_row, reading the CPU-built transmittance and multiple-scattering
 * tables. Radiance per unit solar illuminance (eq. 1-3 and 11), segments
 * in the energy-conserving form (S - S T) / sigma_t, the density of a
 * segment integrated as exponential in path length, the ozone tent
 * exactly. */
SKY_IN vec2 v_unit;
uniform sampler2D u_transmittance_table;
uniform sampler2D u_multiscatter_table;
uniform vec4 u_hl_geometry;   /* R, Rt, H = sqrt(Rt^2 - R^2), r0 (observer radius) */
uniform vec4 u_hl_profile;    /* Rayleigh and Mie scale heights, ozone peak and half width */
uniform vec3 u_hl_rayleigh;   /* scattering, 1/km */
uniform vec3 u_hl_mie_sca;
uniform vec3 u_hl_mie_ext;
uniform vec3 u_hl_ozone;
uniform vec3 u_hl_albedo;
uniform vec4 u_hl_sizes;      /* sky-view w, h; transmittance w, h */
uniform vec4 u_hl_misc;       /* multiscatter size, sun mu, steps, Mie g */

float hl_clamp_sqrt(float x) { return sqrt(max(x, 0.0)); }

float hl_unit_to_tex(float x, float n) { return 0.5 / n + x * (1.0 - 1.0 / n); }

vec3 hl_density(float r)
{
    float h = max(r - u_hl_geometry.x, 0.0);
    return vec3(exp(-h / u_hl_profile.x), exp(-h / u_hl_profile.y),
                max(1.0 - abs(h - u_hl_profile.z) / u_hl_profile.w, 0.0));
}

float hl_seg_exp(float da, float db, float ha, float hb, float scale, float ds)
{
    float x = -(hb - ha) / scale;
    return abs(x) < 1e-4 ? da * ds * (1.0 + x * (0.5 + x / 6.0)) : ds * (db - da) / x;
}

float hl_tent(float h)
{
    float x = h - u_hl_profile.z, w = u_hl_profile.w;
    if (x <= -w) return 0.0;
    if (x <= 0.0) return 0.5 * (x + w) * (x + w) / w;
    if (x < w) return 0.5 * w + x - 0.5 * x * x / w;
    return w;
}

/* column of each constituent over a segment between radii ra and rb */
vec3 hl_column(vec3 a, float ra, vec3 b, float rb, float ds)
{
    float ha = max(ra - u_hl_geometry.x, 0.0), hb = max(rb - u_hl_geometry.x, 0.0);
    float oz = abs(hb - ha) < 1e-6 * u_hl_profile.w ? 0.5 * (a.z + b.z) * ds : ds * (hl_tent(hb) - hl_tent(ha)) / (hb - ha);
    return vec3(hl_seg_exp(a.x, b.x, ha, hb, u_hl_profile.x, ds), hl_seg_exp(a.y, b.y, ha, hb, u_hl_profile.y, ds), oz);
}

float hl_dist_to_top(float r, float mu)
{
    return max(-r * mu + hl_clamp_sqrt(r * r * (mu * mu - 1.0) + u_hl_geometry.y * u_hl_geometry.y), 0.0);
}

vec3 hl_sun_transmittance(float r, float rho, float mu_s)
{
    float R = u_hl_geometry.x;
    if (mu_s < 0.0 && r * r * (mu_s * mu_s - 1.0) + R * R >= 0.0) return vec3(0.0); /* the planet's shadow */
    float d = hl_dist_to_top(r, mu_s), dmin = u_hl_geometry.y - r, dmax = rho + u_hl_geometry.z;
    float xmu = dmax > dmin ? clamp((d - dmin) / (dmax - dmin), 0.0, 1.0) : 0.0;
    float xr = clamp(rho / u_hl_geometry.z, 0.0, 1.0);
    return SKY_TEX2D(u_transmittance_table, vec2(hl_unit_to_tex(xmu, u_hl_sizes.z), hl_unit_to_tex(xr, u_hl_sizes.w))).rgb;
}

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
    float phase_r = 0.0596831 * (1.0 + cos_theta * cos_theta);
    float den = 1.0 + g * g - 2.0 * g * cos_theta;
    float phase_m = 0.1193662 * (1.0 - g * g) * (1.0 + cos_theta * cos_theta) / ((2.0 + g * g) * den * sqrt(den));

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
    float n = clamp(ceil(u_hl_misc.z * clamp(sqrt(max(len / full, 0.0)), 1.0 / 3.0, 1.0)), 4.0, u_hl_misc.z);
    /* segments close quadratically onto the ray's lowest point */
    float tl = clamp(-r * mu, 0.0, len);
    float n1 = tl <= 0.0 ? 0.0 : (tl >= len ? n : clamp(floor(n * tl / len + 0.5), 1.0, n - 1.0));
    float n2 = n - n1;
    vec3 transmittance = vec3(1.0);
    float ta = 0.0, ra = r;
    vec3 da = hl_density(ra);
    for (int k = 1; k <= 256; k++) {
        float kf = float(k);
        if (kf > n) break;
        float tb;
        if (kf <= n1) {
            float u = (n1 - kf) / n1;
            tb = tl * (1.0 - u * u);
        } else {
            float u = (kf - n1) / n2;
            tb = kf == n ? len : tl + (len - tl) * u * u;
        }
        float rb = hl_clamp_sqrt(r * r + 2.0 * r * mu * tb + tb * tb);
        vec3 db = hl_density(rb);
        vec3 col = hl_column(da, ra, db, rb, tb - ta);
        float tm = 0.5 * (ta + tb), rm = hl_clamp_sqrt(r * r + 2.0 * r * mu * tm + tm * tm);
        float rho = hl_clamp_sqrt(rm * rm - R * R);
        vec3 tau = u_hl_rayleigh * col.x + u_hl_mie_ext * col.y + u_hl_ozone * col.z;
        vec3 e = exp(-tau);
        vec3 weight = transmittance * mix((1.0 - e) / max(tau, vec3(1e-30)), 1.0 - tau * (0.5 - tau / 6.0),
                                          step(tau, vec3(1e-3)));
        float mus = clamp((r0 * sun.y + (start + tm) * cos_theta) / rm, -1.0, 1.0);
        vec3 ts = hl_sun_transmittance(rm, rho, mus);
        vec2 ms_uv = vec2(hl_unit_to_tex(0.5 + 0.5 * mus, u_hl_misc.x),
                          hl_unit_to_tex(clamp((rm - R) / (Rt - R), 0.0, 1.0), u_hl_misc.x));
        vec3 psi = SKY_TEX2D(u_multiscatter_table, ms_uv).rgb;
        L += u_hl_rayleigh * col.x * weight * (phase_r * ts + psi) + u_hl_mie_sca * col.y * weight * (phase_m * ts + psi);
        transmittance *= e;
        ta = tb;
        ra = rb;
        da = db;
    }
    if (ground && len > 0.0) {
        float rg = hl_clamp_sqrt(r * r + 2.0 * r * mu * len + len * len);
        float mug = (r0 * sun.y + (start + len) * cos_theta) / rg;
        if (mug > 0.0) L += transmittance * u_hl_albedo / SKY_PI * mug * hl_sun_transmittance(R, 0.0, clamp(mug, 0.0, 1.0));
    }
    SKY_FRAG_COLOR = vec4(L, 1.0);
}
