/* common.glsl: shared by every libsky program (both stages), after
 * display.glsl (the exposure and the tone map, which hosts can include
 * too). The version prologue before them defines SKY_IN/SKY_OUT/SKY_ATTR,
 * SKY_TEX2D and SKY_FRAG_COLOR so one source serves GLSL 110, GLSL 330
 * and GLSL ES 1.00 (which also gets its precision there, and
 * SKY_NO_DERIVATIVES where the context has no OES_standard_derivatives). */
uniform SKY_UP float u_output_hdr;  /* 1: write linear kcd/m^2, 0: tone map + dither    */
uniform SKY_UP float u_fisheye;     /* 1: equidistant all-sky mapping                   */
uniform SKY_UP vec2 u_aspect;       /* fisheye: ndc scale that keeps the circle round    */
uniform SKY_UP vec3 u_sun_dir;      /* horizon frame: +x east, +y up, +z south           */
uniform SKY_UP vec3 u_moon_dir;     /* the same, refracted (the moonlit skies)            */
uniform SKY_UP mat4 u_view_proj;    /* horizon direction (w = 0) to clip space           */
uniform SKY_UP vec4 u_viewport;     /* window x, y, width, height of the host's viewport */
uniform SKY_UP float u_pixel_angle; /* radians per pixel at the view centre             */
uniform SKY_UP float u_far_z;       /* clip z / w of the host's far plane: 1, or for
                                reversed-Z -1 (or 0 with a 0..1 clip range) */
uniform SKY_UP float u_refraction_pressure; /* Saemundsson's scale at the observer (astro.c) */

const float SKY_PI = 3.14159265;

/* d on the tangent plane at the unit direction c, times d . c: (d . e0,
 * d . e1, d . c) for unit e0, e1 across c. Linear in d, so a vertex stage
 * takes it at highp and it interpolates exactly; the fragment's xy / z is
 * the gnomonic projection (the tangent of the angle from c), precise for
 * the small angles of a disc where a fragment stage without highp, which
 * holds unit vectors' components to 2^-11, could not take them from the
 * directions (the sun's radius is 4.7e-3). */
vec3 sky_tangent_plane(vec3 d, vec3 c)
{
    vec3 e0 = normalize(cross(c, abs(c.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    return vec3(dot(d, e0), dot(d, cross(c, e0)), dot(d, c));
}

/* How points cover pixels: as sprites (ES, a core profile) the pixels
 * whose centres lie within half the point's size of its centre; GL 2.0's
 * points without sprites those from floor(x) - floor(size / 2), which
 * takes a margin of a pixel or two more (the points' sizes say which). */
#if defined(SKY_ES) || defined(SKY_CORE)
const bool SKY_POINT_SPRITES = true;
#else
const bool SKY_POINT_SPRITES = false;
#endif
/* a catalogue star's point for its PSF's radius k in pixels (stars.vert),
 * and one of R-P's stars' for its tent's half width (flicker.vert) */
float sky_star_point_size(float k) { return 2.0 * k + (SKY_POINT_SPRITES ? 0.0 : 1.0); }
float sky_flicker_point_size(float texel) { return 2.0 * max(texel, 0.5) + (SKY_POINT_SPRITES ? 1.0 : 3.0); }

/* A position on the host's far plane (sky_config.depth): the sky is
 * farther than anything, so drawn after the scene with the depth test on
 * it shows only where the scene left the far plane. */
vec4 sky_at_far(vec4 clip) { return vec4(clip.xy, u_far_z * clip.w, clip.w); }

/* Equidistant fisheye: zenith at the centre, horizon at radius 1, north up,
 * east on the left (looking up). p is the aspect-corrected ndc, |p| <= 1. */
vec3 sky_fisheye_dir(vec2 p)
{
    float r = length(p);
    float theta = r * 0.5 * SKY_PI;
    vec2 h = r > 1e-6 ? -p / r : vec2(0.0, -1.0);
    return vec3(sin(theta) * h.x, cos(theta), sin(theta) * h.y);
}

/* The inverse of sky_fisheye_dir, for vertices (sun quad). */
vec2 sky_fisheye_ndc(vec3 d)
{
    float theta = acos(clamp(d.y, -1.0, 1.0));
    float hl = length(d.xz);
    vec2 h = hl > 1e-6 ? d.xz / hl : vec2(0.0, -1.0);
    return -h * theta / (0.5 * SKY_PI);
}

/* The true direction behind an apparent one: Saemundsson's refraction
 * (Meeus 16.4, what astro.c applies to the centre) inverted by three
 * fixed-point steps (it changes by a fifth of the altitude's change at the
 * horizon, so each step gains a factor of five). The sun and the moon
 * apply it across their discs (at the vertices of a fine grid): it lifts
 * the lower limb more than the upper, so a setting disc is flattened,
 * about 0.8 high to wide at the horizon. */
vec3 sky_unrefract(vec3 d)
{
    float ha = degrees(asin(clamp(d.y, -1.0, 1.0)));
    float ht = ha;
    for (int i = 0; i < 3; i++) {
        float hc = max(ht, -1.0);
        float r_arcmin = 1.02 / tan(radians(hc + 10.3 / (hc + 5.11))) + 0.0019279;
        ht = ha - r_arcmin / 60.0 * u_refraction_pressure;
    }
    /* Turn d down by the refraction alone, toward the horizon in its
     * vertical plane: d is kept exactly where the refraction vanishes
     * (a GPU's asin and sin can be off by arcminutes high in the sky,
     * which only the small refraction itself may see). */
    float lift = radians(ha - ht);
    vec3 toward_zenith = vec3(0.0, 1.0, 0.0) - d * d.y;
    float l = length(toward_zenith);
    toward_zenith = l > 1e-6 ? toward_zenith / l : vec3(0.0);
    return d * cos(lift) - toward_zenith * sin(lift);
}

#ifdef SKY_FRAGMENT
/* Ordered-looking but unstructured noise in [0,1) from the pixel position:
 * the dither that keeps 8-bit gradients from banding. */
float sky_hash(vec2 p)
{
    vec3 q = fract(vec3(p.xyx) * 0.1031);
    q += dot(q, q.yzx + 33.33);
    return fract((q.x + q.y) * q.z);
}

/* A point's fragment from the point's centre (window position, from the
 * vertex stage) in pixels, for a point drawn size pixels wide. ES draws
 * every point as a sprite, and gl_PointCoord gives the offset without
 * window coordinates, which a fragment stage without highp holds only to
 * a quarter of a pixel past 512 (a star one pixel wide then lights two,
 * or four). */
vec2 sky_point_offset(vec2 center, float size)
{
#ifdef SKY_ES
    return vec2(gl_PointCoord.x - 0.5, 0.5 - gl_PointCoord.y) * size; /* (its y runs down) */
#else
    return gl_FragCoord.xy - center;
#endif
}

/* One 8-bit step of dither, so smooth gradients do not band; kept within
 * 0..1, which a float target would otherwise receive as it is. */
vec3 sky_dither(vec3 display) { return clamp(display + (sky_hash(gl_FragCoord.xy) - 0.5) / 255.0, 0.0, 1.0); }

/* Linear luminance (kcd/m^2) to the output: linear for HDR hosts; else
 * tone mapped and dithered. GLSL ES 1.00's gl_FragColor is mediump: a
 * value past its 65504 arrives as infinity (Mesa writes it so), so HDR
 * output there stops at that (only the sun's disc is brighter). */
vec4 sky_output_seen(vec3 L, float alpha, float brighter)
{
#ifdef SKY_ES
    if (u_output_hdr > 0.5) return vec4(clamp(L, vec3(0.0), vec3(65504.0)), alpha);
#else
    if (u_output_hdr > 0.5) return vec4(max(L, vec3(0.0)), alpha);
#endif
    return vec4(sky_dither(sky_display_seen(L, brighter)), alpha);
}
vec4 sky_output(vec3 L, float alpha) { return sky_output_seen(L, alpha, 1.0); }
#endif /* SKY_FRAGMENT */
