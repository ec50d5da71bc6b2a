/* flicker.glsl: Roden-Parberry's night sky (sec. 4). Their 256x256 star
 * texture, tiled over the dome, is drawn as one point a star (flicker.c,
 * flicker.vert/.frag); the 128x128 galaxy image is stretched over the whole
 * dome, its value interpolated from the dome's vertices: its glow is part
 * of the dome, and the stars inside it are brightened (flicker.c). */
uniform SKY_UP float u_star_luminance;  /* kcd/m^2 of a texel of intensity 1, x night   */

vec3 sky_galaxy_glow(float galaxy) { return u_star_luminance * galaxy * vec3(0.07, 0.075, 0.095); }
