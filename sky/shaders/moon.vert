/* moon.vert: the moon billboard (Mueller sec. 2.1): a quad on the tangent
 * plane of the unit sphere at the moon's direction, four disc radii wide
 * each way (the outer part carries the halo), tessellated (disc.h's
 * disc grid). a_dir is the vertex's direction; its true direction,
 * refraction undone, goes to moon.frag on the billboard's axes, from
 * which it finds the disc: linear in the direction, so interpolated as
 * exactly as the direction itself, and taken here, where a fragment stage
 * without highp would lose the small angles (it holds a unit vector's
 * components to 2^-11, a tenth of the disc's radius). */
uniform SKY_UP mat4 u_moon_view;    /* billboard frame -> horizon frame (moon.frag) */
SKY_ATTR vec3 a_dir;
SKY_OUT vec3 v_dir;
SKY_OUT vec3 v_disc;
void main()
{
    v_dir = a_dir;
    vec3 t = sky_unrefract(normalize(a_dir));
    v_disc = vec3(dot(t, u_moon_view[0].xyz), dot(t, u_moon_view[1].xyz), dot(t, -u_moon_view[2].xyz));
    if (u_fisheye > 0.5)
        gl_Position = sky_at_far(vec4(sky_fisheye_ndc(normalize(a_dir)) / u_aspect, 0.0, 1.0));
    else
        gl_Position = sky_at_far(u_view_proj * vec4(a_dir, 0.0));
}
