/* composite.vert: the dome's image (dome.c) over the whole viewport: a
 * quad of two triangles whose corners are the image's (the corner of its
 * texture it uses). */
uniform SKY_UP vec2 u_dome_scale;
SKY_ATTR vec2 a_pos;
SKY_OUT vec2 v_image;
void main()
{
    v_image = (a_pos * 0.5 + 0.5) * u_dome_scale;
    gl_Position = sky_at_far(vec4(a_pos, 0.0, 1.0));
}
