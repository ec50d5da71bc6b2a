/* stars.frag: a star's point spread (Mueller sec. 4.2): the intensity PSF
 * T(l) = 2l^3 - 3l^2 + 1 over radius q, normalised so that it integrates
 * to the star's illuminance (eq. 10 in physical units), plus the glare
 * PSF G(l) = 1 - l^(1/6) over the enlarged radius k; then extinction over
 * the optical path (eq. 11-12), scintillation growing toward the horizon,
 * the day-night fade (sec. 5) and the clouds in front. Added to the dome. */
uniform float u_star_flux_scale;  /* kcd/m^2 peak of a V = 0 star, incl. fade  */
uniform vec3 u_star_extinction;   /* zenith optical depth at R, G, B           */
uniform vec3 u_star_shell;        /* observer radius a, shell radius b, b - a (km) */
uniform float u_star_seed;        /* scintillation clock, 10 per second, wrapped */
SKY_IN vec3 v_dir;
SKY_IN vec4 v_color;
SKY_IN vec2 v_center;
SKY_IN vec2 v_size;
SKY_IN float v_index;

/* Path length through the atmosphere shell at zenith angle theta, the
 * geometry of Mueller eq. 11 in its stable form: finite at the zenith
 * (where eq. 11 is 0/0) and past the horizon. In units of the zenith path. */
float sky_star_airmass(float cos_theta)
{
    float a = u_star_shell.x, b = u_star_shell.y;
    float sin2 = max(1.0 - cos_theta * cos_theta, 0.0);
    float path = sqrt(max(b * b - a * a * sin2, 0.0)) - a * cos_theta;
    return path / max(u_star_shell.z, 1e-3);
}

void main()
{
    float l = length(gl_FragCoord.xy - v_center) / v_size.x;
    if (l >= 1.0) discard;
    float ls = l * v_size.y;                   /* distance in units of q */
    float psf = ls < 1.0 ? (2.0 * ls - 3.0) * ls * ls + 1.0 : 0.0;
    float glare = v_size.y > 1.0 ? 0.01 * (1.0 - pow(l, 1.0 / 6.0)) : 0.0;
    float flux = pow(2.512, -v_color.a);       /* relative to V = 0 */
    float airmass = sky_star_airmass(v_dir.y);
    vec3 extinction = exp(-u_star_extinction * airmass);
    /* Mueller sec. 4.3.2: a random basis n per star, remapped by N = 0.02 / n
     * so only a few stars twinkle at once; the amplitude grows with the
     * optical path and is strongest in blue (Rayleigh beta_r). Unlike the
     * paper's fresh number every frame, n is value noise in time (a new
     * random value ten times a second, blended smoothly), so a star swells
     * and fades instead of flashing on and off from one frame to the next. */
    float k0 = floor(u_star_seed), kt = u_star_seed - k0;
    float n0 = fract(sin(v_index * 12.9898 + k0 * 78.233) * 43758.5453);
    float n1 = fract(sin(v_index * 12.9898 + (k0 + 1.0) * 78.233) * 43758.5453);
    float n = mix(n0, n1, kt * kt * (3.0 - 2.0 * kt));
    float twinkle = min(0.02 / max(n, 1e-4), 1.0);
    vec3 beta = vec3(0.16, 0.37, 0.91) / 0.91;
    vec3 scint = vec3(1.0) - min(0.25 * (airmass - 1.0), 0.8) * twinkle * beta;
    vec3 L = u_star_flux_scale * flux * (psf + glare) * v_color.rgb * extinction * scint;
#ifdef SKY_HAS_CLOUDS
    L *= 1.0 - sky_clouds(v_dir).a;
#endif
    if (u_output_hdr < 0.5 && max(L.r, max(L.g, L.b)) * u_exposure < 1.0 / 1024.0) discard;
    SKY_FRAG_COLOR = sky_output(L, 1.0);
}
