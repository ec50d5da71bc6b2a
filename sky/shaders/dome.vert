/* dome.vert: the sky dome (dome.c), a sphere of directions drawn at
 * infinity. a_color carries the per-vertex day gradient (rgb) and galaxy
 * brightness (a). w = 0 puts the vertices at infinity; z = w puts them on
 * the far plane so no near/far setting clips them. */
SKY_ATTR vec3 a_dir;
SKY_ATTR vec4 a_color;
SKY_OUT vec3 v_dir;
SKY_OUT vec4 v_color;
void main()
{
    v_dir = a_dir;
    v_color = a_color;
    if (u_fisheye > 0.5) {
        gl_Position = vec4(sky_fisheye_ndc(a_dir) / u_aspect, 0.0, 1.0);
    } else {
        vec4 p = u_view_proj * vec4(a_dir, 0.0);
        gl_Position = p.xyww;
    }
}
