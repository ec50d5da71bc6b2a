/* composite.frag: the dome's image, already tone mapped and dithered at
 * its own scale, filtered up to the viewport's pixels: one fetch. (A
 * second dither at the viewport's scale would cost a tenth of a textured
 * full-screen quad; the image's dither, spread over a few pixels by the
 * filter, already keeps 8-bit gradients from banding.) The all-sky
 * image's variant keeps its circle sharp: outside it stays the margin
 * sky_draw cleared (a discard costs every pixel, so only that variant has
 * one), and the rim is read from one and a half texels inside, where the
 * filter does not reach the image's black margin. */
uniform sampler2D u_dome_tex;
uniform SKY_UP vec2 u_dome_texel; /* 1 / its texture's width, height */
uniform SKY_UP vec2 u_dome_scale; /* the share of the texture the image uses */
SKY_IN vec2 v_image;
void main()
{
    vec2 uv = v_image;
#ifdef SKY_FISHEYE_CIRCLE
    vec2 circle = (uv / u_dome_scale * 2.0 - 1.0) * u_aspect;
    float r = length(circle);
    if (r > 1.0) discard;
    vec2 texel = 2.0 * u_aspect * u_dome_texel / u_dome_scale; /* in the circle's units */
    float rim = 1.0 - 1.5 * max(texel.x, texel.y);
    if (r > rim) uv = (circle * (rim / r) / u_aspect + 1.0) * 0.5 * u_dome_scale;
#endif
#ifdef SKY_DOME_CORNER
    /* a power-of-two texture: the filter must not reach past the corner
     * in use (elsewhere the texture's edge clamps; the pass stays a bare
     * fetch, which llvmpipe draws on its fastest path) */
    uv = min(uv, u_dome_scale - 0.5 * u_dome_texel);
#endif
    SKY_FRAG_COLOR = vec4(SKY_TEX2D(u_dome_tex, uv).rgb, 1.0);
}
