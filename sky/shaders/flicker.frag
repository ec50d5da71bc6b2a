/* flicker.frag: the star's tent (flicker.vert), dimmed by the atmosphere
 * in front of it and hidden by the clouds. Added to the dome. */
SKY_IN vec3 v_dir;
SKY_IN float v_light;
SKY_IN vec2 v_center;
SKY_IN float v_texel;
void main()
{
    /* the tent, or below a texel of a pixel the pixel the star falls in */
    vec2 off = abs(sky_point_offset(v_center, 2.0 * max(v_texel, 0.5) + 3.0)); /* flicker.vert's size */
    vec2 t = v_texel > 0.0 ? max(1.0 - off / v_texel, 0.0) : vec2(off.x <= 0.5 && off.y <= 0.5 ? 1.0 : 0.0);
    float L = v_light * t.x * t.y * sky_atmosphere_transmittance(normalize(v_dir));
#if defined(SKY_HAS_CLOUDS) || defined(SKY_HAS_DOME_COVER)
    L *= 1.0 - sky_front_cover(v_dir);
#endif
    if (u_output_hdr < 0.5 && L * u_exposure < 1.0 / 1024.0) discard;
    SKY_FRAG_COLOR = sky_output(vec3(L), 1.0);
}
