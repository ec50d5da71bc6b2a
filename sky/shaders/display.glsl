/* display.glsl: the 8-bit output's display stages (sky_display_glsl in
 * sky.h): the exposure, the rods' blue shift and the tone map, from the
 * sky's linear light (kcd/m^2) to display values 0..1 (sRGB-like; the
 * library's own frames add a dither of one 8-bit step). Every libsky
 * program includes it before common.glsl; a host that takes the sky's HDR
 * output includes it after its #version line (GLSL 1.10 .. 3.30, ES 1.00
 * with highp) and calls
 *
 *   vec3 shown = sky_display(radiance_kcd);
 *
 * with sky_display_bind setting its uniforms each frame. A host may
 * #define SKY_TONE_MAP_FILMIC or SKY_TONE_MAP_NEUTRAL before it for the
 * other curves of sky_config.tone_map (the hue map otherwise). */
#ifndef SKY_UP
#define SKY_UP
#endif
uniform SKY_UP float sky_display_exposure; /* scale from kcd/m^2 to the curve's input: the
                                        automatic exposure (exposure.c)        */
uniform SKY_UP float sky_display_rods;     /* 0 photopic .. 1 scotopic: the rods' share at
                                        the eye's adaptation, the blue shift's most */
uniform SKY_UP float sky_display_cd;       /* cd/m^2 of a unit of the curve's input */

/* the floor a division by a brightness is guarded with: a fragment stage
 * without highp flushes 1e-8 to 0 (its smallest normal number is 2^-14),
 * and its light arrives times the exposure, where 2^-14 is black */
#if defined(SKY_MEDIUMP) || (defined(GL_ES) && !defined(GL_FRAGMENT_PRECISION_HIGH))
const float SKY_TINY = 6.2e-5;
#else
const float SKY_TINY = 1e-8;
#endif

/* Hejl and Burgess-Dawson's filmic curve: a rational fit whose output
 * already carries an sRGB-like display gamma (no exp, no pow). On four
 * lanes, so one body serves a colour and a single value (the compiler
 * drops the lanes a caller leaves unused). Its toe (the 0.004 taken off,
 * a print's black) goes with the rods' share at the eye's adaptation: the
 * dark-adapted eye reads shapes in a moonless landscape that the toe
 * would crush to black (a wall an eighth of the sky's luminance). */
vec4 sky_filmic(vec4 e)
{
    vec4 x = max(e - 0.004 * (1.0 - sky_display_rods), vec4(0.0));
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

#ifndef SKY_PHOTOPIC
/* The blue shift of night vision (Jensen et al. 2000, as the thesis's sec.
 * 3.6 gives it): where the rods see, a colour's chromaticity moves toward
 * a blue point, by 1 - s, s the
 * cones' share for the colour's own luminance: 0 below 0.01 cd/m^2, 1
 * above 4, 3t^2 - 2t^3 on t = (log10 Y + 2) / 2.6 between. So what is
 * bright enough for the cones keeps its colour (the moon's disc, a bright
 * star, clouds lit at dusk), capped by the rods' share at the eye's own
 * adaptation (sky_display_rods). The luminance stays the photopic one the
 * exposure was set for (Jensen's 0.4468 times the scotopic luminance would
 * expose the night a second time). The blue point is (x, y) = (0.245,
 * 0.245), a step bluer than Jensen's (0.25, 0.25) of night paintings:
 * his shows b/r 1.59 on screen once the rods see alone, below the 1.6 a
 * night sky is held to, and any remnant of a physical moonlit sky's own
 * colour (b/r 1.35 in linear light) pulled it under; this one shows 1.67.
 * The mix of chromaticities written
 * without the matrices: with W = X + Y + Z = dot(e, (0.6443, 1.1920,
 * 1.2032)) (sRGB's primaries) and B the linear sRGB of the blue point at
 * W = 1, (0.1630, 0.2434, 0.5027), the shifted colour is
 * Y ((1 - r) e + r W B) / ((1 - r) Y + 0.245 r W). */
vec3 sky_scotopic_shift(vec3 e, float y, float brighter)
{
    float t = clamp((log2(max(y * sky_display_cd * brighter, 1e-10)) * 0.30103 + 2.0) / 2.6, 0.0, 1.0);
    float rods = min(sky_display_rods, 1.0 - t * t * (3.0 - 2.0 * t));
    float w = dot(e, vec3(0.6443, 1.1920, 1.2032));
    return y * mix(e, w * vec3(0.1630, 0.2434, 0.5027), rods) / max(mix(y, 0.245 * w, rods), SKY_TINY);
}
#endif

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
 *    desaturation, then sRGB.
 * brighter: how many times brighter the light really is than L, for the
 * cones' share of the blue shift (the moon's disc is exposed on its own:
 * moon.c); 1 elsewhere (sky_display). */
#ifndef SKY_PHOTOPIC
/* The night's grade: where the rods see, display values below the night
 * sky's own level (the knee, 0.15: a moonless sky's 38 of 255) rise toward
 * it, as knee (d / knee)^0.5 on the largest channel (the colour kept), by
 * the rods' share at the eye's adaptation. The dark-adapted eye makes out
 * walls and ground that a moonless sky lights to an eighth of its own
 * luminance, which the display's gamma leaves near black ((4, 5, 7)
 * under a sky of (20, 24, 33); (10, 12, 17) graded). What is brighter
 * than the knee (the stars, the moon, a moonlit sky) keeps its value; by
 * day, and wherever the cones see, nothing changes. */
vec3 sky_night_lift(vec3 d)
{
    const float knee = 0.15;
    float m = max(d.r, max(d.g, d.b));
    float lifted = m < knee ? knee * pow(max(m, 0.0) / knee, 0.5) : m;
    return d * mix(1.0, lifted / max(m, SKY_TINY), sky_display_rods);
}
#endif

vec3 sky_display_seen_graded(vec3 L, float brighter);
/* (below: the exposure, the rods' shift and the tone map; here the
 * night's grade after them) */
vec3 sky_display_seen(vec3 L, float brighter)
{
#ifndef SKY_PHOTOPIC
    return sky_night_lift(sky_display_seen_graded(L, brighter));
#else
    return sky_display_seen_graded(L, brighter);
#endif
}

vec3 sky_display_seen_graded(vec3 L, float brighter)
{
    vec3 e = max(L * sky_display_exposure, vec3(0.0));
    float y = dot(e, vec3(0.2126, 0.7152, 0.0722));
#ifndef SKY_PHOTOPIC /* (a program drawn only while the shift is off: dome.c) */
    e = sky_scotopic_shift(e, y, brighter);
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

vec3 sky_display(vec3 L) { return sky_display_seen(L, 1.0); }
