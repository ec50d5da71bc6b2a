/* flicker.glsl: Roden-Parberry's night sky (sec. 4). A 256x256 RGBA star
 * texture tiled over the dome: R mean intensity (mostly black), G flicker
 * rate, B variance, A phase; each star's intensity is a sine of time. The
 * 128x128 galaxy image is stretched over the whole dome (its value arrives
 * interpolated from the dome's vertices), and stars inside it are
 * brightened. */
uniform sampler2D u_flicker_tex;
uniform float u_flicker_phase;   /* 255 * (rate_max * t / 255 mod 1), see flicker.c */
uniform float u_star_luminance;  /* kcd/m^2 of a texel of intensity 1, x night   */

/* Stereographic projection from the nadir: conformal, so stars stay round,
 * and finite everywhere on the upper hemisphere (|uv| <= 1 at the horizon). */
vec2 sky_dome_uv(vec3 d) { return d.xz / (1.0 + max(d.y, 0.0)); }

vec3 sky_flicker(vec3 d, float galaxy)
{
    if (d.y <= 0.0) return vec3(0.0);
    vec4 star = SKY_TEX2D(u_flicker_tex, sky_dome_uv(d) * 4.0);
    /* rate G = k/255 scales the sine horizontally, B (relative variance)
     * vertically, A offsets it: I = R (1 + B sin(2 pi (G t + A))). B is
     * relative so texels around a star, which carry the star's G, B, A for
     * clean filtering (tools/texgen.c), stay dark where R is 0. */
    float flick = star.r * (1.0 + star.b * sin(2.0 * SKY_PI * (star.g * u_flicker_phase + star.a)));
    float stars = flick * (1.0 + 3.0 * galaxy);
    return u_star_luminance * (vec3(stars) + galaxy * vec3(0.07, 0.075, 0.095));
}
