/* dome.vert: the full-screen pass. a_dir is the view ray of each corner
 * (unnormalised, computed on the CPU so that screen-linear interpolation is
 * exact for any perspective projection). */
SKY_ATTR vec2 a_pos;
SKY_ATTR vec3 a_dir;
SKY_OUT vec3 v_dir;
SKY_OUT vec2 v_ndc;
void main()
{
    v_dir = a_dir;
    v_ndc = a_pos;
    gl_Position = vec4(a_pos, 0.0, 1.0);
}
