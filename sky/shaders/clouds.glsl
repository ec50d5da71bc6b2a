/* clouds.glsl: Roden & Parberry's cloud shader (sec. 3.1, lines 14-28) on
 * one packed RGBA texture (R photo, G noise, B detail, A sunset gradient),
 * with the two primary layers drifting apart (sec. 3.2) and a thin upper
 * layer sampled with a stretched coordinate. */
uniform sampler2D u_clouds_tex;
uniform float u_cover, u_density, u_sunset;
uniform float u_cloud_uv_scale;      /* from the height slider               */
uniform vec2 u_cloud_offset0, u_cloud_offset1, u_cloud_offset_detail, u_cloud_offset_upper;
uniform vec3 u_cloud_light;          /* kcd/m^2 of a white cloud: R-P's
                                        amount_sunlight, tinted             */
uniform vec3 u_sunset_color;

/* The cloud dome: a sphere of radius R (in units of the cloud height) whose
 * centre lies R - 1 below the viewer. t is the distance to it along d,
 * written as c / (sqrt(b^2 + c) + b), which has no cancellation for any
 * elevation; at the horizon t = sqrt(2R - 1), finite. */
vec2 sky_cloud_plane(vec3 d)
{
    const float R = 16.0;
    float b = (R - 1.0) * max(d.y, 0.0);
    float c = 2.0 * R - 1.0;
    float t = c / (sqrt(b * b + c) + b);
    return d.xz * t * u_cloud_uv_scale;
}

vec4 sky_clouds(vec3 d)
{
    /* Derivatives first, in uniform control flow. */
    vec2 p = sky_cloud_plane(d);
    vec2 fw = fwidth(p) * 512.0;
    if (d.y <= 0.0 || u_cover <= 0.0) return vec4(0.0);
    vec2 tc0 = p + u_cloud_offset0;                              /* first layer  */
    vec2 tc1 = vec2(p.x * 0.96 - p.y * 0.28, p.x * 0.28 + p.y * 0.96) * 1.15
               + u_cloud_offset1;                                /* second layer */
    vec2 tc3 = p * 3.0 + u_cloud_offset_detail;                  /* detail       */
    vec2 tcu = vec2(p.x * 0.35, p.y * 2.5) + u_cloud_offset_upper; /* thin upper */
    /* tc2: the sunset gradient runs away from the sun */
    float from_sun = 0.5 - 0.5 * dot(d, u_sun_dir);
    vec2 tc2 = vec2(0.5, clamp(from_sun, 0.01, 0.99));

    float cloud1 = SKY_TEX2D(u_clouds_tex, tc0).r;
    float cloud2 = SKY_TEX2D(u_clouds_tex, tc1).g;
    float detail = SKY_TEX2D(u_clouds_tex, tc3).b;
    float upper = SKY_TEX2D(u_clouds_tex, tcu).g;

    vec4 c = vec4(cloud1 + cloud2 * (1.0 - cloud1));      /* 14 */
    c.a -= 1.0 - u_cover;                                  /* 15 */
    float cover = clamp(u_cover, 0.05, 1.0);               /* 16 */
    c.a *= 1.0 / cover;                                    /* 17 */
    c.rgb = c.rgb + detail * (1.0 - c.rgb);                /* 18 */
    c.a *= mix(detail, 1.0, u_density);                    /* 19 */
    if (c.a > 0.0) {                                       /* 20 */
        c += u_density * c.a * 2.0;                        /* 21 */
        if (c.r > 1.0) c.rgb = vec3(1.0 - (c.r - 1.0) * 0.5); /* 22-23 */
    }
    c = clamp(c, 0.0, 1.0);                                /* 25 */

    /* sec. 3.2: a thin, streaky upper layer added on top */
    float thin = clamp((upper - 0.55) * 2.5, 0.0, 1.0) * 0.35 * u_cover;
    c.rgb = mix(c.rgb, vec3(1.0), thin * (1.0 - c.a));
    c.a += thin * (1.0 - c.a);

    if (u_sunset > 0.0) { /* uniform: no fetch when the slider is at 0 */
        float sa = SKY_TEX2D(u_clouds_tex, tc2).a * u_sunset;  /* 26 */
        c.rgb = c.rgb * (1.0 - sa) + u_sunset_color * sa;      /* 27 */
    }
    c.rgb *= u_cloud_light;                                /* 28 */

    /* Beyond the paper: the texture has no mipmaps (memory budget), so where
     * one pixel spans many texels the pattern would alias; fade the clouds
     * there, as haze would near the horizon anyway. */
    float footprint = max(fw.x, fw.y);
    c.a *= 1.0 - 0.8 * smoothstep(2.0, 10.0, footprint);
    c.a *= smoothstep(0.0, 0.06, d.y);
    return c;
}
