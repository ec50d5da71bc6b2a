/* starmap.glsl: Mueller's star map (sec. 4.4): the light of the stars too
 * faint to draw one by one, and the Milky Way, from an equirectangular
 * J2000 map (tools/catgen.c) turned with the sky by the frame's rotation
 * (eq. 7). Brightness follows the control magnitude and the field of view
 * (c_s Delta_m / sqrt(q)), computed per frame in starmap.c. */
uniform sampler2D u_starmap_tex;
uniform mat4 u_starmap_rot;     /* horizon -> J2000 equatorial */
uniform float u_starmap_scale;  /* kcd/m^2 of the brightest texel, with the fade */

vec3 sky_starmap(vec3 d)
{
    if (d.y <= 0.0) return vec3(0.0);
    vec3 e = (u_starmap_rot * vec4(d, 0.0)).xyz;
    float ra = atan(e.y, e.x);
    float dec = asin(clamp(e.z, -1.0, 1.0));
    vec2 uv = vec2(fract(ra / (2.0 * SKY_PI) + 1.0), clamp(0.5 - dec / SKY_PI, 0.5 / 256.0, 1.0 - 0.5 / 256.0));
    vec3 c = SKY_TEX2D(u_starmap_tex, uv).rgb;
    return u_starmap_scale * c * c; /* the map is stored with gamma ~2 */
}
