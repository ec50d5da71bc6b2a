/* cloud_shadow.glsl: the clouds' shadows on the host's ground
 * (sky_cloud_shadow_glsl in sky.h). Include it after the #version line
 * (GLSL 1.10 .. 3.30, ES 1.00); sky_cloud_shadow_bind sets what it reads.
 * With the position relative to the observer in the host's units and
 * world frame:
 *
 *   vec3 sun = sky_sun_color * sky_cloud_shadow(world_pos - observer);
 *
 * the fraction of sky_lighting's sun_color that reaches the point (1 in
 * full sun). The map covers sky_get_cloud_shadow's extent around the
 * observer; toward its edge it fades to its mean, which holds beyond
 * (the edge's texels, clamped, would streak to the horizon). */
#if __VERSION__ >= 130
#define SKY_CLOUD_SHADOW_TEXTURE texture
#else
#define SKY_CLOUD_SHADOW_TEXTURE texture2D
#endif

uniform sampler2D sky_cloud_shadow_map;
uniform vec4 sky_cloud_shadow_s; /* the map's s and t from a position: a   */
uniform vec4 sky_cloud_shadow_t; /* dot with xyz, plus w                      */
uniform float sky_cloud_shadow_far; /* the map's mean                         */

float sky_cloud_shadow(vec3 position)
{
    vec2 st = vec2(dot(sky_cloud_shadow_s.xyz, position) + sky_cloud_shadow_s.w,
                   dot(sky_cloud_shadow_t.xyz, position) + sky_cloud_shadow_t.w);
    vec2 from_centre = abs(st - 0.5);
    float far = smoothstep(0.42, 0.5, max(from_centre.x, from_centre.y));
    return mix(SKY_CLOUD_SHADOW_TEXTURE(sky_cloud_shadow_map, st).r, sky_cloud_shadow_far, far);
}
