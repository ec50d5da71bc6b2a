/* aerial.glsl: the host's aerial perspective (sky_aerial_glsl in sky.h).
 * Include it in a fragment (or vertex) shader after the #version line
 * (GLSL 1.10 .. 3.30, ES 1.00 with highp); sky_aerial_bind sets what it
 * reads. In the world frame the host draws in, distances in metres:
 *
 *   vec3 seen = sky_aerial_apply(radiance, world_pos - eye, distance_m);
 *
 * radiance and the result in kcd/m^2 (the host's luminance before the
 * sky's exposure), linear RGB.
 *
 * The table (aerial.c): per slice of distance a block of 16 azimuths
 * from the sun's vertical (u = sin(az / 2)) by 32 elevations from the
 * horizon up (v = sqrt(el / 90 deg); a view below the horizon is taken as
 * level), 16 slices side by side: the observer, 50 km (k / 13)^2, 100
 * km, the view ray's end at the top of the atmosphere. The in-scattered
 * light's rows (the square root of the light over sky_aerial_params.x)
 * above the transmittance's. Texel i of n holds i / (n - 1). */
#if __VERSION__ >= 130
#define SKY_AERIAL_TEXTURE texture
#define SKY_AERIAL_TEXTURE3D texture
#else
#define SKY_AERIAL_TEXTURE texture2D
#define SKY_AERIAL_TEXTURE3D texture3D
#endif

uniform sampler2D sky_aerial_table;
uniform vec3 sky_aerial_up;     /* the horizon's up, world frame               */
uniform vec3 sky_aerial_sun;    /* toward the sun's azimuth on the horizon      */
uniform vec4 sky_aerial_params; /* x: kcd/m^2 of the light's 1, y: the slices'
                                   distance scale D (m), z: the observer's
                                   radius, w: the atmosphere's top (m)        */

uniform vec2 sky_aerial_weather; /* a weather's: x the deck's dimming of the
                                   air's light (1: none), y its haze's
                                   extinction beyond the clear sky's, 1/m  */
uniform vec3 sky_aerial_haze;    /* the haze's light (the horizon's), kcd/m^2 */

/* a 0..1 coordinate to texel centres: i / (n - 1) at texel i */
float sky_aerial_texel(float x, float n) { return (0.5 + clamp(x, 0.0, 1.0) * (n - 1.0)) / n; }

/* the height a ray from radius r0 at elevation sine mu has climbed after
 * distance d (the form without cancellation between two radii) */
float sky_aerial_height(float r0, float d, float mu)
{
    float q = d * d + 2.0 * r0 * d * mu;
    return q / (sqrt(r0 * r0 + q) + r0);
}

void sky_aerial(vec3 direction, float distance_m, out vec3 transmittance, out vec3 inscatter)
{
    vec3 d = normalize(direction);
    float up = clamp(dot(d, sky_aerial_up), -1.0, 1.0);
    vec3 flat_dir = d - up * sky_aerial_up;
    float flat_len = length(flat_dir);
    float caz = flat_len > 1e-6 ? clamp(dot(flat_dir, sky_aerial_sun) / flat_len, -1.0, 1.0) : 1.0;
    float u = sqrt(0.5 - 0.5 * caz);
    float mu = max(up, 0.0);
    float v = sqrt(asin(mu) / 1.5707963);
    /* the slice: 13 sqrt(d / D) to D, linear to 2 D (14), then to the
     * ray's end at the top (15) by the air passed: 1 - exp(-h / 8 km) of
     * the height h the ray has climbed (the air thins as it rises, and a
     * slant ray's transmittance is nearly final within a few scale
     * heights) */
    float D = sky_aerial_params.y, dm = max(distance_m, 0.0), t;
    if (dm <= D) {
        t = 13.0 * sqrt(dm / D);
    } else if (dm <= 2.0 * D) {
        t = 12.0 + dm / D;
    } else {
        float r0 = sky_aerial_params.z, rt = sky_aerial_params.w;
        float end = -r0 * mu + sqrt(max(r0 * r0 * mu * mu + (rt - r0) * (rt + r0), 0.0));
        float p2 = exp(-sky_aerial_height(r0, 2.0 * D, mu) / 8000.0);
        float pd = exp(-sky_aerial_height(r0, dm, mu) / 8000.0), pe = exp(-sky_aerial_height(r0, end, mu) / 8000.0);
        t = 14.0 + (end > 2.0 * D && p2 > pe ? clamp((p2 - pd) / (p2 - pe), 0.0, 1.0) : 1.0);
    }
    float k0 = min(floor(t), 14.0), f = t - k0;
    /* up to D the slices lie at t^2: the weight linear in distance */
    if (k0 < 13.0) f = (t * t - k0 * k0) / (2.0 * k0 + 1.0);
    float x0 = (k0 * 16.0 + 0.5 + u * 15.0) / 256.0, x1 = x0 + 16.0 / 256.0;
    float yl = sky_aerial_texel(v, 32.0) * 0.5, yt = yl + 0.5;
    vec3 l0 = SKY_AERIAL_TEXTURE(sky_aerial_table, vec2(x0, yl)).rgb;
    vec3 l1 = SKY_AERIAL_TEXTURE(sky_aerial_table, vec2(x1, yl)).rgb;
    vec3 t0 = SKY_AERIAL_TEXTURE(sky_aerial_table, vec2(x0, yt)).rgb;
    vec3 t1 = SKY_AERIAL_TEXTURE(sky_aerial_table, vec2(x1, yt)).rgb;
    inscatter = mix(l0 * l0, l1 * l1, f) * sky_aerial_params.x;
    /* the transmittance falls exponentially between slices (an 8-bit 0
     * is taken as half a step) */
    transmittance = exp(mix(log(max(t0, vec3(0.5 / 255.0))), log(max(t1, vec3(0.5 / 255.0))), f));
    /* a weather over it (nothing without one): the deck dims the air's
     * light, the haze hides what lies beyond in the horizon's light */
    float haze = exp(-sky_aerial_weather.y * dm);
    inscatter = inscatter * (sky_aerial_weather.x * haze) + sky_aerial_haze * (1.0 - haze);
    transmittance *= haze;
}

vec3 sky_aerial_apply(vec3 radiance, vec3 direction, float distance_m)
{
    vec3 transmittance, inscatter;
    sky_aerial(direction, distance_m, transmittance, inscatter);
    return radiance * transmittance + inscatter;
}

#ifndef GL_ES
/* Hillaire's froxel volume (sky_aerial_froxels, CORE33): screen_uv the
 * pixel's place in the viewport the volume was built for (0..1), slices
 * of 1 km, the first km from the identity, beyond 32 km the last slice. */
vec3 sky_aerial_froxel_apply(sampler3D volume, vec3 radiance, vec2 screen_uv, float distance_m)
{
    float km = max(distance_m, 0.0) / 1000.0;
    vec4 f = SKY_AERIAL_TEXTURE3D(volume, vec3(screen_uv, (clamp(km, 1.0, 32.0) - 0.5) / 32.0));
    f = mix(vec4(0.0, 0.0, 0.0, 1.0), f, clamp(km, 0.0, 1.0));
    return radiance * f.a + f.rgb;
}
#endif
