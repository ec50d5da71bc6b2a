/* dome_cover.glsl: what hides a fragment drawn over the dome, where the
 * dome was drawn into its image (dome.c): the clouds' alpha at the
 * fragment's place, filtered from the image, in place of evaluating the
 * clouds again. */
uniform sampler2D u_dome_tex;
uniform SKY_UP vec2 u_dome_texel; /* 1 / its texture's width, height */
uniform SKY_UP vec2 u_dome_scale; /* the share of the texture the image uses */

float sky_front_cover(vec3 d)
{
    vec2 uv = (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw * u_dome_scale;
#ifdef SKY_DOME_CORNER
    uv = min(uv, u_dome_scale - 0.5 * u_dome_texel); /* composite.frag says why */
#endif
    return SKY_TEX2D(u_dome_tex, uv).a;
}
