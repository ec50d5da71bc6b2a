/* moon.frag: the moon-sphere reconstructed per fragment (Mueller sec. 2):
 * normal n = (u, v, sqrt(1 - u^2 - v^2)) in the billboard frame, albedo
 * from the selenographic map after the orientation R_m (eq. 2: libration,
 * axis and parallactic angles, built in moon.c), Hapke-Lommel-Seeliger
 * shading (eq. 3, its phase terms per frame on the CPU), earthshine
 * (eq. 4), the reddish k_lambda, extinction, the lunar eclipse's colour
 * h(t_f) per fragment and brightness i(t_m) (sec. 3), a glare halo at
 * night, and the clouds in front. Each fragment's direction is first taken
 * back through refraction (at the grid's vertices, moon.vert), so a low
 * moon is flattened like the sun; the billboard frame is centred on the
 * true moon. */
uniform sampler2D u_moon_tex;       /* 256x128 albedo, selenographic        */
uniform SKY_UP mat4 u_moon_body;           /* billboard frame -> moon body frame    */
uniform SKY_UP mat4 u_moon_view;           /* billboard frame -> horizon frame      */
uniform SKY_UP vec3 u_moon_light;          /* direction to the sun, billboard frame */
uniform SKY_UP vec3 u_moon_color;          /* kcd/m^2 of the full moon's mean, per
                                       channel, with k_lambda, extinction, fade,
                                       and in LDR the sunlit part's own scale */
uniform SKY_UP vec4 u_moon_terms;          /* x: HLS phase factor, z: halo, w:
                                       occlusion of what is behind            */
uniform SKY_UP vec3 u_moon_earthshine;     /* earthshine relative to full sunlight,
                                       over that scale                       */
uniform SKY_UP float u_moon_radius_tan;    /* the drawn disc's tangent-plane radius */
uniform SKY_UP float u_moon_brighter;      /* 1 / that scale: the disc's real brightness
                                       for the cones' share of the blue shift */
#ifdef SKY_HAS_ECLIPSE
uniform sampler2D u_eclipse_tex;    /* h(t), log10-encoded: h = 10^(-5 texel) */
uniform SKY_UP vec3 u_shadow_offset;      /* the moon's centre from the shadow's axis,
                                       horizon frame, in moon radii (moon.c) */
uniform SKY_UP vec3 u_shadow_axis;         /* geocentric direction to the sun       */
uniform SKY_UP vec4 u_shadow;              /* umbra r, penumbra r, their difference
                                       (moon radii), i(t_m)                  */
#endif
SKY_IN vec3 v_dir;
SKY_IN vec3 v_disc; /* the true direction on the billboard's axes (moon.vert) */

void main()
{
    vec3 d = normalize(v_dir);
    /* nothing below the refracted horizon: there the ground is */
    if (d.y < 0.0) discard;
    /* the fragment's place on the true disc's tangent plane, in disc radii */
    if (v_disc.z <= 0.0) discard;
    vec2 uv = v_disc.xy / (v_disc.z * u_moon_radius_tan);
    float r2 = dot(uv, uv);
    if (r2 >= 16.0) discard;
    vec3 L = vec3(0.0);
    float cover = 0.0;
    if (r2 < 1.0) {
        vec3 n = vec3(uv, sqrt(1.0 - r2));
        vec3 b = (u_moon_body * vec4(n, 0.0)).xyz;
        vec2 st = vec2(0.5 + atan(b.x, b.z) / (2.0 * SKY_PI), 0.5 - asin(clamp(b.y, -1.0, 1.0)) / SKY_PI);
        float albedo = SKY_TEX2D(u_moon_tex, st).r;
        /* Lommel-Seeliger: cos i / (cos i + cos r); its phase factor is
         * in u_moon_terms.x */
        float cos_i = max(dot(n, u_moon_light), 0.0), cos_r = max(n.z, 1e-4);
        float lit = cos_i / (cos_i + cos_r) * u_moon_terms.x;
        L = u_moon_color * albedo * (vec3(lit) + u_moon_earthshine);
#ifdef SKY_HAS_ECLIPSE
        /* the fragment's distance from the shadow axis, in moon radii
         * (sec. 3.1) */
        vec3 q = (u_moon_view * vec4(n, 0.0)).xyz;
        float dist = length(u_shadow_offset + q - dot(q, u_shadow_axis) * u_shadow_axis);
        if (dist < u_shadow.y) {
            float t = dist < u_shadow.x ? 0.5 * dist / u_shadow.x : 0.5 + 0.5 * (dist - u_shadow.x) / u_shadow.z;
            vec3 h = pow(vec3(10.0), -5.0 * SKY_TEX2D(u_eclipse_tex, vec2(t * (127.0 / 128.0) + 0.5 / 128.0, 0.5)).rgb);
            L *= h * u_shadow.w;
        }
#endif
        cover = u_moon_terms.w;
    } else {
        /* halo: falls off with the square of the distance, windowed to the
         * quad's edge */
        float r = sqrt(r2), w = (4.0 - r) / 3.0;
        L = u_moon_color * u_moon_terms.z * w * w / r2;
    }
#if defined(SKY_HAS_CLOUDS) || defined(SKY_HAS_DOME_COVER)
    float c = sky_front_cover(d);
    L *= 1.0 - c;
    cover *= 1.0 - c;
#endif
    SKY_FRAG_COLOR = vec4(sky_output_seen(L, 1.0, u_moon_brighter).rgb, cover);
}
