/* hillaire_build.glsl: what the GPU builds of Hillaire 2020's tables
 * share (CORE33; the GLSL twins of hillaire_cpu.c): the atmosphere's
 * constants, densities, segment columns integrated as exponential in path
 * length (the ozone tent exactly), ray geometry, the segment layout that
 * closes quadratically onto a ray's lowest point, and the transmittance
 * table's lookup. */
uniform sampler2D u_transmittance_table;
/* Psi, D_x, D_y, Q_xx, Q_yy, Z_4 with Q_xy in the alphas of the first
 * three and Z_3 in those of the last three (hillaire.c's order_slot) */
uniform sampler2DArray u_multiscatter_table;
uniform SKY_UP vec3 u_hl_chi;        /* Mie's chi_1, chi_2, Rayleigh's chi_2 */
uniform SKY_UP vec2 u_hl_chi_zonal;  /* Mie's chi_3, chi_4 */
uniform SKY_UP vec4 u_hl_geometry;   /* R, Rt, H = sqrt(Rt^2 - R^2), r0 (observer radius) */
uniform SKY_UP vec4 u_hl_profile;    /* Rayleigh and Mie scale heights, ozone peak and half width */
uniform SKY_UP vec3 u_hl_rayleigh;   /* scattering, 1/km */
uniform SKY_UP vec3 u_hl_mie_sca;
uniform SKY_UP vec3 u_hl_mie_ext;
uniform SKY_UP vec3 u_hl_ozone;
uniform SKY_UP vec3 u_hl_albedo;
uniform SKY_UP vec4 u_hl_sizes;      /* sky-view w, h; transmittance w, h */
uniform SKY_UP vec4 u_hl_misc;       /* multiscatter size, sun mu, sky-view steps, Mie g */
uniform SKY_UP vec4 u_hl_steps;      /* transmittance steps */

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

/* Segment boundary k of n on [0, len], n1 of them before the lowest
 * point tl (hillaire_cpu.c's layout). */
float hl_layout_t(float kf, float n1, float n2, float tl, float len)
{
    if (kf <= n1) {
        float u = (n1 - kf) / n1;
        return tl * (1.0 - u * u);
    }
    float u = (kf - n1) / n2;
    return kf == n1 + n2 ? len : tl + (len - tl) * u * u;
}

float hl_layout_n1(float n, float tl, float len)
{
    /* (GLSL's clamp is undefined for min > max: the C code's order) */
    if (n < 2.0 || tl <= 0.0) return 0.0;
    if (tl >= len) return n;
    return min(max(floor(n * tl / len + 0.5), 1.0), n - 1.0);
}

/* The multiple-scattering table's column of a solar cosine and back:
 * u = 0.5 + 0.5 sign(mu_s) sqrt|mu_s| (hillaire_cpu.c's ms_u) */
float hl_ms_u(float mu_s)
{
    float x = sqrt(clamp(abs(mu_s), 0.0, 1.0));
    return 0.5 + 0.5 * (mu_s < 0.0 ? -x : x);
}
float hl_ms_mu_s(float u)
{
    float x = clamp(2.0 * u - 1.0, -1.0, 1.0);
    return x * abs(x);
}

/* hillaire_cpu.c's ms_direction: direction k of the n_half one column
 * traces for the sun (sx, sy, 0), n_peak of them about the sun, and its
 * weight in the sphere's mean */
vec3 hl_ms_direction(float k, float n_half, float n_peak, float g, vec2 sun, out float weight)
{
    float n_even = n_half - n_peak;
    bool first = k < n_even;
    float j = first ? k : k - n_even, n_set = first ? n_even : n_peak;
    float xi = (j + 0.5) / n_set, c = 2.0 * xi - 1.0;
    if (!first && abs(g) >= 1e-3) {
        float s = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi);
        c = clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
    }
    float phi = SKY_PI * fract((j + 0.5) * 0.6180339887), s = hl_clamp_sqrt(1.0 - c * c);
    vec3 d = first ? vec3(s * cos(phi), c, s * sin(phi))
                   : vec3(c * sun.x - s * cos(phi) * sun.y, c * sun.y + s * cos(phi) * sun.x, s * sin(phi));
    float cs = d.x * sun.x + d.y * sun.y, den = 1.0 + g * g - 2.0 * g * cs;
    weight = 1.0 / (n_even + 2.0 * n_peak * 0.5 * (1.0 - g * g) / (den * sqrt(den)));
    return d;
}

/* Rayleigh's phase and Cornette & Shanks' (Hillaire 2020 eq. 4) */
float hl_phase_rayleigh(float c) { return 0.0596831 * (1.0 + c * c); }
float hl_phase_cs(float c, float g)
{
    float den = 1.0 + g * g - 2.0 * g * c;
    return 0.1193662 * (1.0 - g * g) * (1.0 + c * c) / ((2.0 + g * g) * den * sqrt(den));
}

float hl_radius(float r, float mu, float t) { return hl_clamp_sqrt(r * r + 2.0 * r * mu * t + t * t); }

/* (1 - e^-tau) / tau, a series where 1 - e cancels */
vec3 hl_seg_weight(vec3 tau, vec3 e)
{
    return mix((1.0 - e) / max(tau, vec3(1e-30)), 1.0 - tau * (0.5 - tau / 6.0), step(tau, vec3(1e-3)));
}

/* The multiple-scattering table's coordinates (hillaire_cpu.c's
 * multiscatter_unit) of radius r and solar cosine mu_s */
vec2 hl_ms_uv(float r, float mu_s)
{
    float R = u_hl_geometry.x, Rt = u_hl_geometry.y;
    return vec2(hl_unit_to_tex(hl_ms_u(mu_s), u_hl_misc.x),
                hl_unit_to_tex(clamp((r - R) / (Rt - R), 0.0, 1.0), u_hl_misc.x));
}

/* hillaire_cpu.c's ms_power: the tables hold Psi^(1/16) (and the
 * moments' ratios to Psi), which interpolate where Psi falls steeply */
vec3 hl_ms_power(vec3 root)
{
    vec3 x = root * root;
    x *= x;
    x *= x;
    return x * x;
}

/* hillaire_cpu.c's scatter_moments: the light that reaches a point (the
 * first six layers of tab at uv: the multiple-scattering table, or one
 * order's) scattered once more toward the view v, per unit scattering
 * coefficient: jr by the air, jm by the aerosol. vx, vy: v in the point's
 * frame (toward the sun's azimuth, up); cos_theta: v's cosine to the
 * sun. The mean, the dipole D . v, the quadrupole (5/2) v^T Q v and the
 * zonal terms Z_l P_l(cos_theta), each by the phase's Legendre moment. */
void hl_scatter_moments(sampler2DArray tab, vec2 uv, float vx, float vy, float cos_theta, out vec3 jr, out vec3 jm)
{
    vec4 psi = texture(tab, vec3(uv, 0.0)), mdx = texture(tab, vec3(uv, 1.0)), mdy = texture(tab, vec3(uv, 2.0));
    vec4 qxx = texture(tab, vec3(uv, 3.0)), qyy = texture(tab, vec3(uv, 4.0)), z4 = texture(tab, vec3(uv, 5.0));
    vec3 mean = hl_ms_power(psi.rgb), qxy = vec3(psi.a, mdx.a, mdy.a), z3 = vec3(qxx.a, qyy.a, z4.a);
    float vz2 = max(1.0 - vx * vx - vy * vy, 0.0), c2 = cos_theta * cos_theta;
    float p3 = 0.5 * cos_theta * (5.0 * c2 - 3.0), p4 = 0.125 * (35.0 * c2 * c2 - 30.0 * c2 + 3.0);
    /* per unit mean: the dipole, quadrupole and zonal parts */
    vec3 l1 = mdx.rgb * vx + mdy.rgb * vy;
    vec3 l2 = 2.5 * (qxx.rgb * (vx * vx) + qyy.rgb * (vy * vy) - (qxx.rgb + qyy.rgb) * vz2 + 2.0 * qxy * (vx * vy));
    jr = mean * max(1.0 + u_hl_chi.z * l2, 0.0);
    jm = mean * max(1.0 + u_hl_chi.x * l1 + u_hl_chi.y * l2 + u_hl_chi_zonal.x * p3 * z3 + u_hl_chi_zonal.y * p4 * z4.rgb,
                    0.0);
}

/* The light one segment of a view ray scatters toward the observer, per
 * unit of sunlight (skyview_row's sum in hillaire_cpu.c): col its
 * columns (hl_column), weight the transmittance to it times
 * hl_seg_weight, rm its middle's radius, mus the sun's cosine there, vy
 * the view's there, cos_theta the view's angle to the sun and the two
 * phases at it. Single scattering (eq. 1-3) and the multiple scattering
 * (eq. 11) scattered by the real phase functions (hl_scatter_moments). */
vec3 hl_segment_light(vec3 col, vec3 weight, float rm, float mus, float vy, float cos_theta, float phase_r,
                      float phase_m)
{
    float R = u_hl_geometry.x;
    vec3 ts = hl_sun_transmittance(rm, hl_clamp_sqrt(rm * rm - R * R), mus);
    /* the view in the sample's frame: y up, x toward the sun's azimuth */
    float sh = hl_clamp_sqrt(1.0 - mus * mus);
    float vx = sh > 1e-6 ? clamp((cos_theta - mus * vy) / sh, -1.0, 1.0) : 0.0;
    vec3 jr, jm;
    hl_scatter_moments(u_multiscatter_table, hl_ms_uv(rm, mus), vx, vy, cos_theta, jr, jm);
    return u_hl_rayleigh * col.x * weight * (phase_r * ts + jr) + u_hl_mie_sca * col.y * weight * (phase_m * ts + jm);
}
