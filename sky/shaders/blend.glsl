/* blend.glsl: the analytic sky (Rayleigh's, or Preetham's when
 * sky_config.blend_partner asks for it: atmosphere.c includes that one's
 * snippet) and Hillaire's table mixed by one weight per frame
 * (atmosphere.c): automatic from the sun's elevation, or the host's. */
uniform SKY_UP float u_blend_weight; /* 0 analytic .. 1 Hillaire */

/* the sky around the analytic radiance already evaluated (the dome's
 * Rayleigh integrals come per vertex: rayleigh.glsl) and the moonlit
 * sky's vertex value (mixed on the CPU: atmosphere.c) */
vec3 sky_atmosphere_over(vec3 d, vec3 analytic, vec3 moonlit)
{
    vec3 sky = mix(analytic, sky_hillaire_radiance(d), u_blend_weight) + sky_moonlit(moonlit);
    return sky_or_ground(d, sky * sky_eclipse_dim(d) + sky_night_floor(d));
}

vec3 sky_atmosphere(vec3 d, vec3 moonlit)
{
#ifdef SKY_HAS_PREETHAM
    return sky_atmosphere_over(d, sky_preetham_radiance(d), moonlit);
#else
    return sky_atmosphere_over(d, sky_rayleigh_radiance(d), moonlit);
#endif
}
