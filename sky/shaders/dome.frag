/* dome.frag: everything behind and in the atmosphere, back to front
 * (Mueller sec. 5): the atmosphere's own light, the night layers behind it
 * dimmed by its extinction, then the clouds over both. */
SKY_IN vec3 v_dir;
SKY_IN vec4 v_color;  /* rgb: the gradient path's day gradient, the physical
                         paths' moonlit sky per unit of the moon's light; a:
                         galaxy */
#ifdef SKY_HAS_GRADIENT
SKY_IN vec3 v_sky;
#if defined(SKY_HAS_FLICKER) || defined(SKY_HAS_STARMAP)
SKY_IN float v_night_transmittance;
#endif
#endif
#ifdef SKY_HAS_RAYLEIGH
SKY_IN vec4 v_rl_single_r; /* rayleigh.glsl's integrals (dome.vert) */
SKY_IN vec4 v_rl_single_m;
SKY_IN float v_rl_multiple_b;
#endif
#ifdef SKY_HAS_CLOUDS
SKY_IN vec4 v_cloud_layers;
SKY_IN vec3 v_cloud_upper;
SKY_IN vec2 v_cloud_shade;
#endif
void main()
{
    /* The perspective-correct interpolation of the directions of a flat
     * triangle drawn at infinity is the pixel's own ray: exact. */
    vec3 d = normalize(v_dir);
    if (u_fisheye > 0.5 && d.y < 0.0) {
        SKY_FRAG_COLOR = vec4(0.0, 0.0, 0.0, 1.0); /* outside the all-sky circle */
        return;
    }
#ifdef SKY_HAS_GRADIENT
    vec3 L = v_sky;
#elif defined(SKY_HAS_RAYLEIGH)
    vec3 L = sky_atmosphere_over(d, sky_rayleigh_phases(d, v_rl_single_r.rgb, v_rl_single_m.rgb,
                                                        vec3(v_rl_single_r.a, v_rl_single_m.a, v_rl_multiple_b)),
                                 v_color.rgb);
#else
    vec3 L = sky_atmosphere(d, v_color.rgb);
#endif
    /* night layers: only in the night variant of this program (dome.c),
     * behind the atmosphere and dimmed by it (per vertex where the path
     * is evaluated there: a smooth function of elevation) */
#if defined(SKY_HAS_FLICKER) || defined(SKY_HAS_STARMAP)
#ifdef SKY_HAS_GRADIENT
    float night_t = v_night_transmittance;
#else
    float night_t = sky_atmosphere_transmittance(d);
#endif
#endif
#ifdef SKY_HAS_FLICKER
    L += sky_galaxy_glow(v_color.a) * night_t;
#endif
#ifdef SKY_HAS_STARMAP
    L += sky_starmap(d) * night_t;
#endif
    /* the night's glows above the air (the snippets with a glow function,
     * summed by sky_night_glows, which the program build writes), dimmed
     * by it per channel */
    float brighter = 1.0; /* for the night's blue shift: the aurora's green */
#ifdef SKY_HAS_NIGHT_GLOWS
    vec3 glow_t = sky_night_extinction(d);
    L += sky_night_glows(d) * glow_t;
#ifdef SKY_HAS_AURORA
    brighter = sky_aurora_brighter(L, sky_aurora_seen * glow_t);
#endif
#endif
    float cover = 0.0;
#ifdef SKY_HAS_CLOUDS
#ifdef SKY_HAS_WEATHER
    /* behind a weather's deck no clear sky (nor star): where its layers
     * thin out into the horizon, the air under it in the horizon's light,
     * which the deck has dimmed (weather.c); below the horizon the ground
     * as sky_ground has it (the gradient's vertices would carry the clear
     * horizon's light down into it) */
    L = mix(L, d.y < 0.0 ? sky_ground(d) : u_horizon, u_deck);
#endif
    vec4 c = sky_clouds_at(v_cloud_layers, v_cloud_upper, v_cloud_shade, d);
    L = mix(L, c.rgb, c.a);
    cover = c.a;
    /* a weather's haze in front of sky, clouds and ground alike, its light
     * the horizon's (clouds.glsl; 0 without a weather) */
#ifdef SKY_HAS_WEATHER
    float haze = sky_weather_haze(d);
    L = mix(L, u_horizon, haze);
    cover += (1.0 - cover) * haze;
#endif
    /* the optics' light in front of sky, clouds and haze (a rainbow in the
     * rain, a fogbow in the fog itself, a halo in the ice: the optics
     * variants of the dome, dome.c) */
#ifdef SKY_HAS_FRONT_LIGHTS
    L += sky_front_lights(d);
#endif
#endif
    /* (clouds in front take the aurora's share of the light with them) */
    brighter = mix(brighter, 1.0, cover);
#ifdef SKY_DOME_INTO_IMAGE
    /* the image keeps the clouds' alpha for what is drawn over it */
    SKY_FRAG_COLOR = sky_output_seen(L, cover, brighter);
#else
    SKY_FRAG_COLOR = sky_output_seen(L, 1.0, brighter);
#endif
}
