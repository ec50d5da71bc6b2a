/* dome.vert: the sky dome (dome.c), a sphere of directions drawn at
 * infinity. a_color carries the per-vertex day gradient (rgb; on the
 * physical paths their moonlit sky per unit of the moon's light instead,
 * atmosphere.c) and galaxy brightness (a). w = 0 puts the vertices at infinity; z = w puts them on
 * the far plane so no near/far setting clips them. What varies slowly
 * across the sky is evaluated here, per vertex, rather than per pixel: the
 * gradient path's whole sky (it has no texture and no sharp feature the
 * dome's rings would miss), the analytic (Rayleigh) sky's integrals along
 * the view ray (its phase functions, sharp near the sun, stay per pixel),
 * and the clouds' coordinates and sunset. */
SKY_ATTR vec3 a_dir;
SKY_ATTR vec4 a_color;
SKY_OUT vec3 v_dir;
SKY_OUT vec4 v_color;
#ifdef SKY_HAS_GRADIENT
SKY_OUT vec3 v_sky;        /* the gradient path's radiance, kcd/m^2 */
#if defined(SKY_HAS_FLICKER) || defined(SKY_HAS_STARMAP)
SKY_OUT float v_night_transmittance; /* what reaches the eye from behind it */
#endif
#endif
#ifdef SKY_HAS_RAYLEIGH
/* rayleigh.glsl's integrals, packed into two vec4 and a float (GL 2.0
 * hardware guarantees 8 vec4 of varyings; with the clouds' the dome
 * uses 7): single_r.rgb + multiple.r, single_m.rgb + multiple.g,
 * multiple.b */
SKY_OUT vec4 v_rl_single_r;
SKY_OUT vec4 v_rl_single_m;
SKY_OUT float v_rl_multiple_b;
#endif
#ifdef SKY_HAS_CLOUDS
SKY_OUT vec4 v_cloud_layers; /* sky_clouds_vertex's outputs */
SKY_OUT vec3 v_cloud_upper;
SKY_OUT vec2 v_cloud_shade;
#endif
void main()
{
    v_dir = a_dir;
    v_color = a_color;
#ifdef SKY_HAS_GRADIENT
    v_sky = sky_atmosphere(a_dir, a_color.rgb);
#if defined(SKY_HAS_FLICKER) || defined(SKY_HAS_STARMAP)
    v_night_transmittance = sky_atmosphere_transmittance(a_dir);
#endif
#endif
#ifdef SKY_HAS_RAYLEIGH
    vec3 single_r, single_m, multiple;
    sky_rayleigh_integrals(a_dir, single_r, single_m, multiple);
    v_rl_single_r = vec4(single_r, multiple.r);
    v_rl_single_m = vec4(single_m, multiple.g);
    v_rl_multiple_b = multiple.b;
#endif
#ifdef SKY_HAS_CLOUDS
    sky_clouds_vertex(a_dir, v_cloud_layers, v_cloud_upper, v_cloud_shade);
#endif
    if (u_fisheye > 0.5) {
        gl_Position = sky_at_far(vec4(sky_fisheye_ndc(a_dir) / u_aspect, 0.0, 1.0));
    } else {
        vec4 p = u_view_proj * vec4(a_dir, 0.0);
        gl_Position = sky_at_far(p);
    }
}
