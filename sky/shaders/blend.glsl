/* blend.glsl: the analytic sky and Hillaire's table mixed by one weight
 * per frame (atmosphere.c): automatic from the sun's elevation, or the
 * host's. */
uniform float u_blend_weight; /* 0 analytic .. 1 Hillaire */

vec3 sky_atmosphere(vec3 d, vec3 day)
{
    vec3 analytic = sky_rayleigh_radiance(d) * sky_below_horizon(d);
    vec3 tables = sky_hillaire_radiance(d);
    return mix(analytic, tables, u_blend_weight) * sky_eclipse_dim(d) + sky_night_floor(d) * sky_below_horizon(d);
}
