/* blend.glsl: the analytic sky and Hillaire's table mixed by one weight
 * per frame (atmosphere.c): automatic from the sun's elevation, or the
 * host's. */
uniform float u_blend_weight; /* 0 analytic .. 1 Hillaire */

vec3 sky_atmosphere(vec3 d, vec3 day)
{
    vec3 sky = mix(sky_rayleigh_radiance(d), sky_hillaire_radiance(d), u_blend_weight);
    return sky_or_ground(d, sky * sky_eclipse_dim(d) + sky_night_floor(d));
}
