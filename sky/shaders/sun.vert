/* sun.vert: a camera-facing quad around the sun direction (R-P sec. 2),
 * tessellated (disc.h's grid). Vertices are directions; w = 0
 * puts them at infinity, z = w on the far plane so no near/far setting
 * clips them. Each vertex also carries its true direction, refraction
 * undone, for the disc's shape: on the tangent planes at the sun's and
 * the moon's true centres (sky_tangent_plane). */
uniform SKY_UP vec3 u_sun_true_dir;     /* the centre without refraction        */
uniform SKY_UP vec3 u_eclipse_moon_dir; /* the moon's, when it eclipses; else 0  */
SKY_ATTR vec2 a_pos;   /* grid coordinates, -1..1 across the quad */
SKY_ATTR vec3 a_dir;
SKY_OUT vec3 v_dir;
SKY_OUT vec3 v_sun_plane;
SKY_OUT vec3 v_moon_plane;
void main()
{
    v_dir = a_dir;
    vec3 t = sky_unrefract(normalize(a_dir));
    v_sun_plane = sky_tangent_plane(t, normalize(u_sun_true_dir));
    vec3 m = u_eclipse_moon_dir;
    v_moon_plane = dot(m, m) > 0.0 ? sky_tangent_plane(t, normalize(m)) : vec3(0.0, 0.0, -1.0); /* no moon */
    if (u_fisheye > 0.5) {
        gl_Position = sky_at_far(vec4(sky_fisheye_ndc(normalize(a_dir)) / u_aspect, 0.0, 1.0));
    } else {
        vec4 p = u_view_proj * vec4(a_dir, 0.0);
        gl_Position = sky_at_far(p);
    }
}
