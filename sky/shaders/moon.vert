/* moon.vert: the moon billboard (Mueller sec. 2.1): a quad on the tangent
 * plane of the unit sphere at the moon's direction, four disc radii wide
 * each way (the outer part carries the halo), tessellated (disc.h's
 * disc grid). a_dir is the vertex's direction; its true direction,
 * refraction undone, goes to moon.frag, which finds the disc from it. */
SKY_ATTR vec3 a_dir;
SKY_OUT vec3 v_dir;
SKY_OUT vec3 v_true_dir;
void main()
{
    v_dir = a_dir;
    v_true_dir = sky_unrefract(normalize(a_dir));
    if (u_fisheye > 0.5)
        gl_Position = sky_at_far(vec4(sky_fisheye_ndc(normalize(a_dir)) / u_aspect, 0.0, 1.0));
    else
        gl_Position = sky_at_far(u_view_proj * vec4(a_dir, 0.0));
}
