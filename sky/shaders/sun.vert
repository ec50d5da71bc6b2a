/* sun.vert: a camera-facing quad around the sun direction (R-P sec. 2),
 * tessellated (disc.h's grid). Vertices are directions; w = 0
 * puts them at infinity, z = w on the far plane so no near/far setting
 * clips them. Each vertex also carries its true direction, refraction
 * undone, for the disc's shape. */
SKY_ATTR vec2 a_pos;   /* grid coordinates, -1..1 across the quad */
SKY_ATTR vec3 a_dir;
SKY_OUT vec3 v_dir;
SKY_OUT vec3 v_true_dir;
void main()
{
    v_dir = a_dir;
    v_true_dir = sky_unrefract(normalize(a_dir));
    if (u_fisheye > 0.5) {
        gl_Position = sky_at_far(vec4(sky_fisheye_ndc(normalize(a_dir)) / u_aspect, 0.0, 1.0));
    } else {
        vec4 p = u_view_proj * vec4(a_dir, 0.0);
        gl_Position = sky_at_far(p);
    }
}
