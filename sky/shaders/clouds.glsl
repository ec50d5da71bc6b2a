/* clouds.glsl: Roden & Parberry's cloud shader (sec. 3.1, lines 14-28) on
 * one packed RGBA texture (R photo, G noise, B detail baked at three times
 * the first layer's coordinate, A sunset gradient; clouds.c), with the two
 * primary layers drifting apart (sec. 3.2) and a thin upper layer sampled
 * with a stretched coordinate. In both stages: the dome finds each layer's
 * coordinate and the sunset per vertex (sky_clouds_vertex) and the clouds
 * per pixel from them (sky_clouds_at); the small quads of the sun, moon
 * and stars evaluate them per pixel from the direction (sky_clouds). */
uniform sampler2D u_clouds_tex;
uniform SKY_UP float u_cover, u_density, u_sunset;
uniform SKY_UP float u_deck;                /* a weather's deck: 0 none .. 1 no gaps */
uniform SKY_UP vec2 u_haze;                /* a weather's haze: optical depth up,
                                        its layer's height / horizon path */
uniform SKY_UP vec4 u_flash_dir;           /* lightning: toward the brightest flash;
                                        w the sharpness of the patch it lights */
uniform SKY_UP vec3 u_flash_light;         /* the deck lit by it, kcd/m^2 (0 between) */
uniform SKY_UP float u_upper_cover;         /* the cover the thin layer reads: the
                                        cover, or a weather's upper / 0.35   */
uniform SKY_UP float u_cloud_uv_scale;      /* from the height slider               */
uniform SKY_UP float u_cloud_texels_per_step; /* 512 over the viewport pixels a
                                        fragment step spans (clouds.c)      */
uniform SKY_UP float u_dome_step_pixels;    /* those pixels in the dome's image    */
uniform SKY_UP vec2 u_cloud_offset0, u_cloud_offset1, u_cloud_offset_upper;
uniform SKY_UP vec3 u_cloud_light;          /* kcd/m^2 of a white cloud: R-P's
                                        amount_sunlight, tinted             */
uniform SKY_UP vec3 u_sunset_color;
uniform SKY_UP float u_sunset_gradient[33]; /* SKY_SUNSET_SAMPLES of the alpha
                                        channel across 0..1 (clouds.c)      */

/* The cloud dome: a sphere of radius R (in units of the cloud height) whose
 * centre lies R - 1 below the viewer. The point under d is d.xz t, with t
 * the distance along d, written as c / (sqrt(b^2 + c) + b), which has no
 * cancellation for any elevation (at the horizon t = sqrt(2R - 1), finite).
 * As homogeneous coordinates, plane point = xy / z: interpolated across a
 * triangle of directions and divided per pixel, they are exact for a flat
 * cloud layer (z = d.y) and within a second-order term for the dome. */
vec3 sky_cloud_plane_h(vec3 d)
{
    const float R = 16.0;
    float b = (R - 1.0) * max(d.y, 0.0);
    float c = 2.0 * R - 1.0;
    return vec3(d.xz * u_cloud_uv_scale, (sqrt(b * b + c) + b) / c);
}

/* Each layer's texture coordinate, from the plane point p (homogeneous:
 * the offsets scaled by w): layer 0 (photo and detail), layer 1 (noise,
 * turned and scaled so the two never line up), the thin upper layer
 * (stretched, R-P 3.2). */
vec4 sky_cloud_layers(vec2 p, float w)
{
    return vec4(p + u_cloud_offset0 * w,
                vec2(p.x * 0.96 - p.y * 0.28, p.x * 0.28 + p.y * 0.96) * 1.15 + u_cloud_offset1 * w);
}
vec2 sky_cloud_upper(vec2 p, float w) { return vec2(p.x * 0.35, p.y * 2.5) + u_cloud_offset_upper * w; }

/* The sunset gradient runs away from the sun (R-P's tc2). */
float sky_cloud_from_sun(vec3 d) { return clamp(0.5 - 0.5 * dot(d, u_sun_dir), 0.01, 0.99); }

/* The clouds' fade into the horizon (haze hides them there); a weather's
 * deck reaches down to it. */
float sky_cloud_horizon_fade(float y)
{
    float fade = smoothstep(0.0, 0.06, y);
#ifdef SKY_HAS_WEATHER
    fade = mix(fade, smoothstep(0.0, 0.008, y), u_deck);
#endif
    return fade;
}

/* A weather's haze (weather.c): the share of what lies beyond it that the
 * haze in front replaces, 1 - exp(-tau), tau its optical depth along d
 * through a flat layer (below the horizon, toward the ground). 0 without
 * a weather. */
float sky_weather_haze(vec3 d)
{
#ifdef SKY_HAS_WEATHER
    return 1.0 - exp(-u_haze.x / max(abs(d.y), u_haze.y));
#else
    return 0.0;
#endif
}

/* Lightning lights the deck from inside: a patch around the flash, a tenth
 * of it everywhere (the light spreads through the cloud). 0 between
 * flashes and without a weather. */
vec3 sky_cloud_flash(vec3 d, float grey)
{
#ifdef SKY_HAS_WEATHER
    return u_flash_light * (grey * (0.1 + 0.9 * exp(u_flash_dir.w * (dot(d, u_flash_dir.xyz) - 1.0))));
#else
    return vec3(0.0);
#endif
}

/* Lines 26-28: the sunset tint and the light, kcd/m^2. */
vec3 sky_cloud_colour(float grey, float sunset_amount)
{
    return (grey * (1.0 - sunset_amount) + u_sunset_color * sunset_amount) * u_cloud_light;
}

#ifndef SKY_FRAGMENT
/* Per vertex, for the dome: the layers' coordinates (xy, zw) and the upper
 * layer's (upper.xy) as homogeneous numerators over upper.z; shade.x the
 * sunset amount (R-P line 26) from the gradient's samples, shade.y the
 * fade of the clouds into the horizon. */
void sky_clouds_vertex(vec3 d, out vec4 layers, out vec3 upper, out vec2 shade)
{
    vec3 h = sky_cloud_plane_h(d);
    layers = sky_cloud_layers(h.xy, h.z);
    upper = vec3(sky_cloud_upper(h.xy, h.z), h.z);
    float x = sky_cloud_from_sun(d) * 32.0;
    int i = int(min(floor(x), 31.0));
    shade.x = mix(u_sunset_gradient[i], u_sunset_gradient[i + 1], x - float(i)) * u_sunset;
    shade.y = sky_cloud_horizon_fade(d.y);
}
#else
/* R-P lines 14-25 and sec. 3.2's upper layer, from the texels: the first
 * layer's (photo in R, its detail in B), the second's noise and the upper
 * layer's noise. The colour stays grey until the sunset tint, so it is
 * carried as one value: returns (grey, alpha). */
vec2 sky_cloud_grey(vec4 first, float noise, float upper)
{
    float g = first.r + noise * (1.0 - first.r);              /* 14 */
    float a = g - (1.0 - u_cover);                             /* 15 */
    a *= 1.0 / clamp(u_cover, 0.05, 1.0);                      /* 16-17 */
    g = g + first.b * (1.0 - g);                               /* 18 */
    a *= mix(first.b, 1.0, u_density);                         /* 19 */
    /* 20-23 without a branch: only a positive alpha adds density, and
     * min() takes the fold 1 - (g - 1) / 2 exactly when g > 1 */
    float k = u_density * max(a, 0.0) * 2.0;                   /* 21 */
    g = min(g + k, 1.5 - 0.5 * (g + k));                       /* 22-23 */
    a += k;
    g = clamp(g, 0.0, 1.0);                                    /* 25 */
    a = clamp(a, 0.0, 1.0);
    /* beyond the paper: a weather's deck closes the gaps and flattens the
     * base's contrast (0 leaves R-P's clouds exactly) */
#ifdef SKY_HAS_WEATHER /* (the weather's code only in a sky with SKY_WEATHER: its cost) */
    g = mix(g, 0.55 + 0.45 * g, u_deck);
    a = mix(a, 1.0, u_deck);
#endif
    /* sec. 3.2: a thin, streaky upper layer added on top */
    float thin = clamp((upper - 0.55) * 2.5, 0.0, 1.0) * 0.35 * u_upper_cover * (1.0 - a);
    return vec2(g + thin * (1.0 - g), a + thin);
}

/* Beyond the paper: the texture has no mipmaps (memory budget), so where
 * one pixel of the viewport spans many texels the pattern would alias;
 * fade the clouds there, as haze would near the horizon anyway. fw: the
 * first layer's coordinate change across a fragment step. */
float sky_cloud_footprint_fade(vec2 fw)
{
    float footprint = max(fw.x, fw.y) * u_cloud_texels_per_step;
    float fade = 1.0 - 0.8 * smoothstep(2.0, 10.0, footprint);
#ifdef SKY_HAS_WEATHER
    /* (a weather's deck, its contrast flattened, stays whole: no gaps) */
    fade = mix(fade, 1.0, u_deck);
#endif
    return fade;
}

#ifdef SKY_NO_DERIVATIVES
/* GLSL ES 1.00 without OES_standard_derivatives has no fwidth: the first
 * layer's coordinate change across a fragment step is found from the
 * directions one step right of and above d, as fwidth sums the changes
 * along the screen's two axes. A perspective view's axes are the rows of
 * u_view_proj (x: right, y: up, w: forward), and its pixels lie evenly on
 * the plane at distance 1 in front: the step there is the pixel angle at
 * the centre. The all-sky image steps toward the horizon and across. */
#ifdef SKY_DOME_INTO_IMAGE
#define SKY_CLOUD_STEP_ANGLE (u_pixel_angle * u_dome_step_pixels)
#else
#define SKY_CLOUD_STEP_ANGLE u_pixel_angle
#endif
vec2 sky_cloud_step(vec3 d)
{
    vec3 right, up, on_plane = d;
    if (u_fisheye > 0.5) {
        up = vec3(0.0, 1.0, 0.0) - d * d.y;
        float n = length(up);
        up = n > 1e-6 ? up / n : vec3(1.0, 0.0, 0.0);
        right = cross(d, up);
    } else {
        right = normalize(vec3(u_view_proj[0][0], u_view_proj[1][0], u_view_proj[2][0]));
        up = normalize(vec3(u_view_proj[0][1], u_view_proj[1][1], u_view_proj[2][1]));
        vec3 forward = normalize(vec3(u_view_proj[0][3], u_view_proj[1][3], u_view_proj[2][3]));
        on_plane = d / max(dot(d, forward), 1e-3);
    }
    vec3 h0 = sky_cloud_plane_h(d);
    vec3 hx = sky_cloud_plane_h(normalize(on_plane + right * SKY_CLOUD_STEP_ANGLE));
    vec3 hy = sky_cloud_plane_h(normalize(on_plane + up * SKY_CLOUD_STEP_ANGLE));
    vec2 p0 = h0.xy / h0.z;
    return abs(hx.xy / hx.z - p0) + abs(hy.xy / hy.z - p0);
}
#define SKY_CLOUD_STEP(tc, d) sky_cloud_step(d)
#else
#define SKY_CLOUD_STEP(tc, d) fwidth(tc)
#endif

/* The dome's clouds in direction d from its interpolated coordinates
 * (sky_clouds_vertex): three fetches. */
vec4 sky_clouds_at(vec4 layers, vec3 upper, vec2 shade, vec3 d)
{
    float iw = 1.0 / upper.z;
    vec2 tc0 = layers.xy * iw;
    vec2 ga = sky_cloud_grey(SKY_TEX2D(u_clouds_tex, tc0), SKY_TEX2D(u_clouds_tex, layers.zw * iw).g,
                             SKY_TEX2D(u_clouds_tex, upper.xy * iw).g);
    return vec4(sky_cloud_colour(ga.x, shade.x) + sky_cloud_flash(d, ga.x),
                ga.y * sky_cloud_footprint_fade(SKY_CLOUD_STEP(tc0, d)) * shade.y);
}

/* The clouds in front of direction d, all per pixel (the sun's, moon's and
 * stars' small quads). */
vec4 sky_clouds(vec3 d)
{
    /* Derivatives first, in uniform control flow. */
    vec3 h = sky_cloud_plane_h(d);
    vec2 p = h.xy / h.z;
    vec4 tc = sky_cloud_layers(p, 1.0);
    vec2 fw = SKY_CLOUD_STEP(tc.xy, d);
    float haze = sky_weather_haze(d);
    if (d.y <= 0.0 || u_cover <= 0.0) return vec4(0.0, 0.0, 0.0, haze);
    float sunset_amount = 0.0;
    if (u_sunset > 0.0) /* uniform: no fetch when the slider is at 0 */
        sunset_amount = SKY_TEX2D(u_clouds_tex, vec2(0.5, sky_cloud_from_sun(d))).a * u_sunset;
    vec2 ga = sky_cloud_grey(SKY_TEX2D(u_clouds_tex, tc.xy), SKY_TEX2D(u_clouds_tex, tc.zw).g,
                             SKY_TEX2D(u_clouds_tex, sky_cloud_upper(p, 1.0)).g);
    float a = ga.y * sky_cloud_footprint_fade(fw) * sky_cloud_horizon_fade(d.y);
    /* what is beyond the clouds and the haze: the haze hides too */
    return vec4(sky_cloud_colour(ga.x, sunset_amount), a + (1.0 - a) * haze);
}

/* What hides a fragment of the quads over the dome (dome_cover.glsl's,
 * where the dome has an image). */
float sky_front_cover(vec3 d) { return sky_clouds(d).a; }
#endif
