/* stars.vert: catalogue stars as points (Mueller sec. 4), one vertex a
 * star. J2000 directions (proper motion applied on the CPU) turn into the
 * horizon frame through one rotation and the annual aberration vector per
 * frame (Mueller eq. 7-8 with an accurate precession); refraction lifts
 * each star by its own amount. Points are sized in the vertex shader
 * (eq. 9) and shaped in the fragment shader from gl_FragCoord, which GLSL
 * 1.10 has everywhere (gl_PointCoord it does not). Everything that is the
 * same across a star's point (its flux, colour, extinction, twinkle) is
 * found here, once a star rather than once a pixel, and a star too faint
 * to add anything visible is not rasterised at all. */
uniform SKY_UP float u_star_flux_scale;  /* kcd/m^2 peak of a V = 0 star, incl. fade  */
uniform SKY_UP vec3 u_star_extinction;   /* zenith optical depth at R, G, B           */
uniform SKY_UP vec3 u_star_shell;        /* observer radius a, shell radius b, b - a (km) */
uniform SKY_UP float u_star_seed;        /* scintillation clock, 10 per second, wrapped */
uniform SKY_UP mat4 u_star_rot;          /* J2000 -> horizon (precession, nutation, sidereal) */
uniform SKY_UP vec3 u_star_aberration;   /* annual aberration, horizon frame          */
uniform SKY_UP vec4 u_star_size;         /* q (px), glare coefficient c_k (px), max radius (px), m_a */
uniform SKY_UP vec3 u_star_pressure;     /* refraction pressure factor, the faintest V
                                     drawn (sky_point_limit), -             */
uniform SKY_UP vec4 u_star_occulter;     /* moon's true direction, cos of its drawn radius */
SKY_ATTR vec2 a_pos;              /* x: star index (scintillation seed); y: the
                                     share of the twinkle a disc averages away
                                     (planets; 0 for a star)                 */
SKY_ATTR vec3 a_dir;
SKY_ATTR vec4 a_color;            /* rgb: colour of unit luminance, a: V mag    */
SKY_OUT vec3 v_dir;
SKY_OUT vec3 v_light;             /* kcd/m^2 at the PSF's peak, per channel      */
SKY_OUT vec2 v_center;            /* window position of the star, px            */
SKY_OUT vec2 v_size;              /* x: billboard radius k (px), y: k / q        */

/* Saemundsson refraction (astro.c), radians, for true altitude h. */
float sky_star_refraction(float h)
{
    float hd = max(degrees(h), -1.0);
    float r = 1.02 / tan(radians(hd + 10.3 / (hd + 5.11))) + 0.0019279;
    return radians(r / 60.0) * u_star_pressure.x;
}

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

/* The star's light at the PSF's peak (eq. 10 in physical units): its flux
 * relative to V = 0, its colour, the extinction over its optical path
 * (eq. 11-12) and the scintillation. Mueller sec. 4.3.2: a random basis n
 * per star, remapped by N = 0.02 / n so only a few stars twinkle at once;
 * the amplitude grows with the optical path and is strongest in blue
 * (Rayleigh beta_r). Unlike the paper's fresh number every frame, n is
 * value noise in time (a new random value ten times a second, blended
 * smoothly), so a star swells and fades instead of flashing on and off
 * from one frame to the next. */
vec3 sky_star_light(vec3 d, float index)
{
    float flux = pow(2.512, -a_color.a);       /* relative to V = 0 */
    float airmass = sky_star_airmass(d.y);
    vec3 extinction = exp(-u_star_extinction * airmass);
    float k0 = floor(u_star_seed), kt = u_star_seed - k0;
    float n0 = fract(sin(index * 12.9898 + k0 * 78.233) * 43758.5453);
    float n1 = fract(sin(index * 12.9898 + (k0 + 1.0) * 78.233) * 43758.5453);
    float n = mix(n0, n1, kt * kt * (3.0 - 2.0 * kt));
    float twinkle = min(0.02 / max(n, 1e-4), 1.0) * (1.0 - a_pos.y);
    vec3 beta = vec3(0.16, 0.37, 0.91) / 0.91;
    vec3 scint = vec3(1.0) - min(0.25 * (airmass - 1.0), 0.8) * twinkle * beta;
    /* what the naked eye would not see against this sky is not drawn:
     * full a quarter magnitude above the limit, gone a quarter below */
    float seen = clamp(2.0 * (u_star_pressure.y - a_color.a) + 0.5, 0.0, 1.0);
    return u_star_flux_scale * flux * a_color.rgb * extinction * scint * seen;
}

void main()
{
    vec3 d = normalize((u_star_rot * vec4(a_dir, 0.0)).xyz + u_star_aberration);
    bool occulted = dot(d, u_star_occulter.xyz) > u_star_occulter.w; /* behind the moon */
    float h = asin(clamp(d.y, -1.0, 1.0));
    float ha = h + sky_star_refraction(h);
    vec2 horiz = d.xz / max(length(d.xz), 1e-6);
    d = vec3(horiz.x * cos(ha), sin(ha), horiz.y * cos(ha));
    v_dir = d;
    v_light = sky_star_light(d, a_pos.x);
    /* eq. 9 and the glare radius k = max(q, c_k sqrt(I_G)) with
     * I_G = 2.512^(m_a - m - (V_T - 1)) - 1 for stars brighter than m_a */
    float q = u_star_size.x;
    float ig = max(pow(2.512, u_star_size.w - a_color.a - 0.167) - 1.0, 0.0);
    float k = min(max(q, u_star_size.y * sqrt(ig)), u_star_size.z);
    v_size = vec2(k, k / q);
    /* The glare is light the eye spreads around the star, not light added
     * to it (Mueller eq. 9-10 normalise the PSF to the star's
     * illuminance): share it out so PSF and glare together sum to the
     * star's light. Over the plane, T(l) over radius q integrates to
     * 0.3 pi q^2 and the glare 0.01 (1 - l^(1/6)) over radius k to
     * 0.01 2 pi k^2 (1/2 - 6/13) = 0.01 pi k^2 / 13: the glare adds
     * (k / q)^2 / 390 of the PSF's light (a 17 px Sirius at m_a 4: 37 %). */
    if (k > q) v_light /= 1.0 + (k / q) * (k / q) / 390.0;
    vec4 clip;
    if (u_fisheye > 0.5)
        clip = vec4(sky_fisheye_ndc(d) / u_aspect, 0.0, 1.0);
    else
        clip = (u_view_proj * vec4(d, 0.0)).xyww;
    /* LDR: a star whose brightest pixel (the PSF's peak plus the glare's,
     * 1.01) adds less than a quarter of an 8-bit step is left out, as
     * stars.frag would discard each of its pixels */
    bool faint = u_output_hdr < 0.5 && max(v_light.r, max(v_light.g, v_light.b)) * 1.01 * sky_display_exposure < 1.0 / 1024.0;
    /* below the horizon, behind the camera or the moon, or too faint:
     * outside the clip volume */
    if (d.y < 0.0 || clip.w <= 0.0 || occulted || faint) clip = vec4(2.0, 2.0, 2.0, 1.0);
    gl_Position = sky_at_far(clip);
    gl_PointSize = sky_star_point_size(k);
    v_center = (clip.xy / clip.w * 0.5 + 0.5) * u_viewport.zw + u_viewport.xy;
}
