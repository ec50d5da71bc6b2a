/* common.glsl: shared by every libsky program (both stages). The version
 * prologue before it defines SKY_IN/SKY_OUT/SKY_ATTR, SKY_TEX2D and
 * SKY_FRAG_COLOR so one source serves GLSL 110, GLSL 330 and GLSL ES 1.00
 * (which also gets its precision there, and SKY_NO_DERIVATIVES where the
 * context has no OES_standard_derivatives). */
uniform SKY_UP float u_exposure;    /* LDR: scale from kcd/m^2 to tone-map input       */
uniform SKY_UP float u_output_hdr;  /* 1: write linear kcd/m^2, 0: tone map + dither    */
uniform SKY_UP float u_fisheye;     /* 1: equidistant all-sky mapping                   */
uniform SKY_UP vec2 u_aspect;       /* fisheye: ndc scale that keeps the circle round    */
uniform SKY_UP vec3 u_sun_dir;      /* horizon frame: +x east, +y up, +z south           */
uniform SKY_UP float u_night_shift; /* 0 photopic .. 1 scotopic: the rods' share at the eye's
                                adaptation (exposure.c), the blue shift's most */
uniform SKY_UP float u_display_cd;  /* cd/m^2 of a unit of the tone map's input (after the exposure) */
uniform SKY_UP mat4 u_view_proj;    /* horizon direction (w = 0) to clip space           */
uniform SKY_UP vec4 u_viewport;     /* window x, y, width, height of the host's viewport */
uniform SKY_UP float u_pixel_angle; /* radians per pixel at the view centre             */
uniform SKY_UP float u_far_z;       /* clip z / w of the host's far plane: 1, or for
                                reversed-Z -1 (or 0 with a 0..1 clip range) */
uniform SKY_UP float u_refraction_pressure; /* Saemundsson's scale at the observer (astro.c) */

const float SKY_PI = 3.14159265;
/* the floor a division by a brightness is guarded with: a fragment stage
 * without highp flushes 1e-8 to 0 (its smallest normal number is 2^-14),
 * and its light arrives times the exposure, where 2^-14 is black */
#ifdef SKY_MEDIUMP
const float SKY_TINY = 6.2e-5;
#else
const float SKY_TINY = 1e-8;
#endif

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

/* Hejl and Burgess-Dawson's filmic curve: a rational fit whose output
 * already carries an sRGB-like display gamma (no exp, no pow). On four
 * lanes, so one body serves a colour and a single value (the compiler
 * drops the lanes a caller leaves unused). */
vec4 sky_filmic(vec4 e)
{
    vec4 x = max(e - 0.004, vec4(0.0));
    return (x * (6.2 * x + 0.5)) / (x * (6.2 * x + 1.7) + 0.06);
}

/* r to the power 1 / 2.2 for r in 0..1, the curve's display gamma, as
 * 1.109 sqrt(r) - 0.109 r (within 1.5 % from r = 0.2 to 1, 5 % at 0.05):
 * a software rasteriser pays for every pow. */
vec4 sky_display_power(vec4 r) { return 1.109 * sqrt(r) - 0.109 * r; }

/* IEC 61966-2-1: linear to sRGB. */
vec3 sky_srgb_encode(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

/* Linear luminance (kcd/m^2) to display values (LDR): exposure, the night
 * shift, then the tone map sky_config.tone_map chose (sky.h):
 *  hue (default): the filmic curve on the colour's luminance, the colour
 *    scaled with it in linear light, so hue and saturation stay what the
 *    sky computed and the brightness is what filmic gives a grey; a soft
 *    shoulder on the largest channel keeps it below white (from 0.8 of
 *    the display range), and only what is far above white (the sun, its
 *    glare) turns white, from 8 to 128 times the exposure's white. The
 *    curve's output carries its display gamma of about 2.2, so the other
 *    channels are the largest one's value times their ratio to it to the
 *    power 1 / 2.2 (and the largest the grey's over the luminance's ratio
 *    to it to that power: sky_display_power);
 *  filmic: the curve on each channel apart (bright colours drift toward
 *    white and yellow, the classic shoulder);
 *  neutral: Khronos' PBR Neutral (2024): linear up to 0.76, then a
 *    rational shoulder on the largest channel with a little
 *    desaturation, then sRGB. */
#ifndef SKY_PHOTOPIC
/* The blue shift of night vision (Jensen et al. 2000, as the thesis's sec.
 * 3.6 gives it): where the rods see, a colour's chromaticity moves toward
 * the blue point (x, y) = (0.25, 0.25) of night paintings, by 1 - s, s the
 * cones' share for the colour's own luminance: 0 below 0.01 cd/m^2, 1
 * above 4, 3t^2 - 2t^3 on t = (log10 Y + 2) / 2.6 between. So what is
 * bright enough for the cones keeps its colour (the moon's disc, a bright
 * star, clouds lit at dusk), capped by the rods' share at the eye's own
 * adaptation (u_night_shift). The luminance stays the photopic one the
 * exposure was set for (Jensen's 0.4468 times the scotopic luminance would
 * expose the night a second time). The mix of chromaticities written
 * without the matrices: with W = X + Y + Z = dot(e, (0.6443, 1.1920,
 * 1.2032)) (sRGB's primaries) and B the linear sRGB of the blue point at
 * W = 1, (0.1765, 0.2476, 0.4914), the shifted colour is
 * Y ((1 - r) e + r W B) / ((1 - r) Y + r W / 4). */
vec3 sky_scotopic_shift(vec3 e, float y)
{
    float t = clamp((log2(max(y * u_display_cd, 1e-10)) * 0.30103 + 2.0) / 2.6, 0.0, 1.0);
    float rods = min(u_night_shift, 1.0 - t * t * (3.0 - 2.0 * t));
    float w = dot(e, vec3(0.6443, 1.1920, 1.2032));
    return y * mix(e, w * vec3(0.1765, 0.2476, 0.4914), rods) / max(mix(y, 0.25 * w, rods), SKY_TINY);
}
#endif

vec3 sky_tonemap(vec3 L)
{
    vec3 e = max(L * u_exposure, vec3(0.0));
    float y = dot(e, vec3(0.2126, 0.7152, 0.0722));
#ifndef SKY_PHOTOPIC /* (a program drawn only while the shift is off: dome.c) */
    e = sky_scotopic_shift(e, y);
#endif
#if defined(SKY_TONE_MAP_FILMIC)
    return sky_filmic(vec4(e, 0.0)).rgb;
#elif defined(SKY_TONE_MAP_NEUTRAL)
    /* the toe: a small offset taken off dark colours (Khronos' 0.04) */
    float lo = min(e.r, min(e.g, e.b));
    e -= lo < 0.08 ? lo - 6.25 * lo * lo : 0.04;
    float peak = max(e.r, max(e.g, e.b));
    const float start = 0.76, span = 0.24; /* 0.8 - 0.04, 1 - start */
    if (peak >= start) {
        float top = 1.0 - span * span / (peak + span - start);
        e *= top / peak;
        e = mix(e, vec3(top), 1.0 - 1.0 / (0.15 * (peak - top) + 1.0));
    }
    return sky_srgb_encode(e);
#else
    /* the display value of a grey of the colour's luminance, and what the
     * largest channel then needs to keep the colour (display values carry
     * the curve's gamma of 2.2) */
    float m = max(max(e.r, max(e.g, e.b)), SKY_TINY);
    vec4 g = sky_display_power(vec4(e / m, max(y, SKY_TINY) / m)); /* the channels', the luminance's */
    float top = sky_filmic(vec4(y)).x / g.w;
    /* a soft shoulder keeps that channel below white: the colour's hue and
     * saturation survive, only its brightness gives way */
    top = top <= 0.8 ? top : 0.8 + 0.2 * (top - 0.8) / (top - 0.6);
    return mix(top * g.xyz, vec3(top), clamp((m - 8.0) / 120.0, 0.0, 1.0));
#endif
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
vec4 sky_output(vec3 L, float alpha)
{
#ifdef SKY_ES
    if (u_output_hdr > 0.5) return vec4(clamp(L, vec3(0.0), vec3(65504.0)), alpha);
#else
    if (u_output_hdr > 0.5) return vec4(max(L, vec3(0.0)), alpha);
#endif
    return vec4(sky_dither(sky_tonemap(L)), alpha);
}
#endif /* SKY_FRAGMENT */
