/* dome_cover.glsl: what hides a fragment drawn over the dome, where the
 * dome was drawn into its image (dome.c): the clouds' alpha at the
 * fragment's place, filtered from the image, in place of evaluating the
 * clouds again. */
uniform sampler2D u_dome_tex;

float sky_front_cover(vec3 d) { return SKY_TEX2D(u_dome_tex, (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw).a; }
