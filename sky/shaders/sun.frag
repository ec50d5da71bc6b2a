/* sun.frag: limb-darkened solar disc (Schneegans et al. eq. 1, u = 0.6)
 * with a small glare halo, dimmed by the atmosphere and hidden by clouds.
 * Drawn additively over the dome. */
uniform float u_sun_radius;     /* angular radius, radians                */
uniform float u_sun_luminance;  /* kcd/m^2 at the disc centre             */
uniform vec3 u_sun_transmittance;
uniform vec3 u_sun_true_dir;    /* the centre without refraction         */
uniform float u_refraction_pressure;
SKY_IN vec3 v_dir;

/* The true direction behind an apparent one: Saemundsson's refraction
 * (Meeus 16.4, what astro.c applies to the centre) inverted by three
 * fixed-point steps (it changes by a fifth of the altitude's change at the
 * horizon, so each step gains a factor of five). Applied at every point
 * of the disc, it lifts the lower limb more than the upper: a setting sun
 * is flattened, about 0.8 high to wide at the horizon. */
vec3 sky_unrefract(vec3 d)
{
    float ha = degrees(asin(clamp(d.y, -1.0, 1.0)));
    float ht = ha;
    for (int i = 0; i < 3; i++) {
        float hc = max(ht, -1.0);
        float r_arcmin = 1.02 / tan(radians(hc + 10.3 / (hc + 5.11))) + 0.0019279;
        ht = ha - r_arcmin / 60.0 * u_refraction_pressure;
    }
    vec2 h = length(d.xz) > 1e-6 ? normalize(d.xz) : vec2(0.0, -1.0);
    return vec3(h.x * cos(radians(ht)), sin(radians(ht)), h.y * cos(radians(ht)));
}

void main()
{
    vec3 view = normalize(v_dir);
    /* nothing below the refracted horizon: there the ground is */
    if (view.y < 0.0) discard;
    vec3 d = sky_unrefract(view);
    /* |d x s| is the sine of the angle: precise for the small angles here,
     * where acos(dot) would lose most of its digits in float. */
    float phi = length(cross(d, u_sun_true_dir));
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
    L *= 1.0 - sky_clouds(view).a;
#endif
    /* Additive: where the sun adds nothing visible, add nothing at all (the
     * dome already carries the dither). */
    if (u_output_hdr < 0.5 && max(L.r, max(L.g, L.b)) * u_exposure < 1.0 / 1024.0) discard;
    SKY_FRAG_COLOR = sky_output(L, 1.0);
}
