/* sun.frag: limb-darkened solar disc (Schneegans et al. eq. 1, u = 0.6)
 * with a small glare halo, dimmed by the atmosphere and hidden by clouds.
 * Drawn additively over the dome. */
uniform float u_sun_radius;     /* angular radius, radians                */
uniform float u_sun_luminance;  /* kcd/m^2 at the disc centre             */
uniform vec3 u_sun_transmittance;
SKY_IN vec3 v_dir;
void main()
{
    vec3 d = normalize(v_dir);
    if (d.y < 0.0) discard;
    /* |d x s| is the sine of the angle: precise for the small angles here,
     * where acos(dot) would lose most of its digits in float. */
    float phi = length(cross(d, u_sun_dir));
    float r = phi / u_sun_radius;
    float disc = 0.0;
    if (r < 1.0) disc = 1.0 - 0.6 * (1.0 - sqrt(max(1.0 - r * r, 0.0)));
    /* Glare: falls off with the square of the distance from the limb and is
     * windowed to zero at the quad's edge (16 radii) so no square shows. */
    float out_r = max(r - 1.0, 0.0);
    float window = max(1.0 - r / 16.0, 0.0);
    float glare = 5e-6 * window * window / (1.0 + out_r * out_r);
    vec3 L = u_sun_luminance * (disc + glare) * u_sun_transmittance;
#ifdef SKY_HAS_CLOUDS
    L *= 1.0 - sky_clouds(d).a;
#endif
    /* Additive: where the sun adds nothing visible, add nothing at all (the
     * dome already carries the dither). */
    if (u_output_hdr < 0.5 && max(L.r, max(L.g, L.b)) * u_exposure < 1.0 / 1024.0) discard;
    SKY_FRAG_COLOR = sky_output(L, 1.0);
}
