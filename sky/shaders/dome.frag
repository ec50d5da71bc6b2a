/* dome.frag: one pass for everything behind and in the atmosphere, back to
 * front (Mueller sec. 5): night layers, attenuated by the atmosphere, plus
 * the atmosphere's own light, then the clouds over both. */
SKY_IN vec3 v_dir;
SKY_IN vec2 v_ndc;
void main()
{
    vec3 d;
    if (u_fisheye > 0.5) {
        vec2 p = v_ndc * u_aspect;
        if (dot(p, p) > 1.0) {
            SKY_FRAG_COLOR = vec4(0.0, 0.0, 0.0, 1.0);
            return;
        }
        d = sky_fisheye_dir(p);
    } else {
        d = normalize(v_dir);
    }
    vec3 L = vec3(0.0);
#ifdef SKY_HAS_FLICKER
    L += sky_flicker(d);
#endif
    L = L * sky_atmosphere_transmittance(d) + sky_atmosphere(d);
#ifdef SKY_HAS_CLOUDS
    vec4 c = sky_clouds(d);
    L = mix(L, c.rgb, c.a);
#endif
    SKY_FRAG_COLOR = sky_output(L, 1.0);
}
