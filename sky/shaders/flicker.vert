/* flicker.vert: one of Roden & Parberry's flickering stars (sec. 4) as a
 * point. a_pos is its texel's centre in the dome coordinate the texture
 * was tiled over (the stereographic projection from the nadir, |uv| < 1
 * above the horizon); a_color its texel: R the mean intensity (brightened
 * by the galaxy, over 4), G the flicker rate, B the relative variance, A
 * the phase, so I = R (1 + B sin(2 pi (G t + A))). The point reproduces
 * the texel as bilinear filtering drew it: a tent one texel wide on each
 * side, in pixels. */
uniform SKY_UP float u_star_luminance;  /* kcd/m^2 of a texel of intensity 1 (flicker.c) */
uniform SKY_UP float u_flicker_phase;   /* 255 * (rate_max * t / 255 mod 1), see flicker.c */
uniform SKY_UP float u_point_max;       /* the largest point size drawn               */
SKY_ATTR vec2 a_pos;
SKY_ATTR vec4 a_color;
SKY_OUT vec3 v_dir;
SKY_OUT float v_light;           /* kcd/m^2 at the tent's peak                  */
SKY_OUT vec2 v_center;           /* window position, px                         */
SKY_OUT float v_texel;           /* the tent's half width, px; 0: one pixel     */
void main()
{
    float r2 = dot(a_pos, a_pos);
    float y = (1.0 - r2) / (1.0 + r2);
    vec3 d = vec3(a_pos.x * (1.0 + y), y, a_pos.y * (1.0 + y));
    v_dir = d;
    float flick = 4.0 * a_color.r * (1.0 + a_color.b * sin(2.0 * SKY_PI * (a_color.g * u_flicker_phase + a_color.a)));
    /* a texel spans 1/1024 of the coordinate, (1 + y) / 1024 radians. Below
     * a pixel the star lights the one pixel it falls in, at its full
     * brightness, as the unfiltered texture showed it where a pixel met
     * the texel (without the texture's popping in and out as it moves) */
    float texel = (1.0 + y) / 1024.0 / u_pixel_angle;
    v_texel = texel < 1.0 ? 0.0 : min(texel, 0.5 * (u_point_max - sky_flicker_point_size(0.0)));
    /* the air in front: the same across a point this small */
    v_light = u_star_luminance * flick * sky_atmosphere_transmittance(normalize(d));
    vec4 clip;
    if (u_fisheye > 0.5)
        clip = vec4(sky_fisheye_ndc(d) / u_aspect, 0.0, 1.0);
    else
        clip = (u_view_proj * vec4(d, 0.0)).xyww;
    /* behind the camera, or (LDR) adding less than a quarter of an 8-bit
     * step: outside the clip volume */
    bool faint = u_output_hdr < 0.5 && v_light * sky_display_exposure < 1.0 / 1024.0;
    if (clip.w <= 0.0 || faint) clip = vec4(2.0, 2.0, 2.0, 1.0);
    gl_Position = sky_at_far(clip);
    /* the tent, or its pixel, and the margin; flicker.frag weighs what is
     * covered */
    gl_PointSize = sky_flicker_point_size(v_texel);
    v_center = (clip.xy / clip.w * 0.5 + 0.5) * u_viewport.zw + u_viewport.xy;
}
