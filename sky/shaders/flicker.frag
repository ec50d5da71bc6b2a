/* flicker.frag: the star's tent (flicker.vert, dimmed there by the
 * atmosphere in front of it), hidden by the clouds. Added to the dome. */
SKY_IN vec3 v_dir;
SKY_IN float v_light;
SKY_IN vec2 v_center;
SKY_IN float v_texel;
void main()
{
    /* the tent, or below a texel of a pixel the pixel the star falls in
     * (half open, so a star on the edge between two lights one) */
    vec2 o = sky_point_offset(v_center, sky_flicker_point_size(v_texel));
    bool inside = o.x > -0.5 && o.x <= 0.5 && o.y > -0.5 && o.y <= 0.5;
    vec2 t = v_texel > 0.0 ? max(1.0 - abs(o) / v_texel, 0.0) : vec2(inside ? 1.0 : 0.0);
    float L = v_light * t.x * t.y;
#if defined(SKY_HAS_CLOUDS) || defined(SKY_HAS_DOME_COVER)
    L *= 1.0 - sky_front_cover(v_dir);
#endif
    if (u_output_hdr < 0.5 && L * sky_display_exposure < 1.0 / 1024.0) discard;
    SKY_FRAG_COLOR = sky_output(vec3(L), 1.0);
}
