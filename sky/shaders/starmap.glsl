/* starmap.glsl: Mueller's star map (sec. 4.4): the light of the stars too
 * faint to draw one by one, and the Milky Way, from an equirectangular
 * J2000 map (tools/catgen.c), resampled into a cube map at load so a pixel
 * looks it up by direction (starmap.c), turned with the sky by the
 * frame's rotation (eq. 7). Brightness follows the control magnitude and the field of view
 * (c_s Delta_m / sqrt(q)), computed per frame in starmap.c. */
uniform samplerCube u_starmap_tex; /* the map by J2000 direction (starmap.c) */
uniform SKY_UP mat4 u_starmap_rot;     /* horizon -> J2000 equatorial */
uniform SKY_UP float u_starmap_scale;  /* kcd/m^2 of the brightest texel, with the fade */

vec3 sky_starmap(vec3 d)
{
    if (d.y <= 0.0) return vec3(0.0);
    vec3 c = SKY_TEXCUBE(u_starmap_tex, (u_starmap_rot * vec4(d, 0.0)).xyz).rgb;
    return u_starmap_scale * c * c; /* the map is stored with gamma ~2 */
}
