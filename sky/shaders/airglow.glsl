/* airglow.glsl: the upper atmosphere's own light (airglow.c), a thin
 * shell brighter toward the horizon by the van Rhijn factor; dome.frag
 * dims it by the air below (sky_night_extinction). */
uniform SKY_UP vec4 u_airglow; /* rgb: zenith kcd/m^2 above the air; a: (R / (R + h))^2 */

vec3 sky_airglow(vec3 d)
{
    if (d.y <= 0.0) return vec3(0.0);
    float y = min(d.y, 1.0);
    return u_airglow.rgb * inversesqrt(max(1.0 - u_airglow.a * (1.0 - y * y), 1e-6));
}
