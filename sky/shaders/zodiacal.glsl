/* zodiacal.glsl: the zodiacal light (zodiacal.c): Leinert et al.'s
 * (1998) table 17, resampled on the CPU by cos(lambda / 2) of the angle
 * from the sun along the ecliptic (across) and the sine of the ecliptic
 * latitude (down, folded: the table is symmetric), so a pixel finds it
 * with a rotation, a square root and one fetch, no trigonometry; stored
 * as a logarithm in 8 bits. dome.frag dims it by the air
 * (sky_night_extinction). */
uniform sampler2D u_zodiacal_tex; /* 64 x 32 */
uniform SKY_UP mat4 u_zodiacal_rot;      /* horizon -> ecliptic of date, +x at the sun */
uniform SKY_UP vec4 u_zodiacal;          /* rgb: kcd/m^2 at the encoding's 0; a: ln of
                                     its range */

vec3 sky_zodiacal(vec3 d)
{
    if (d.y <= 0.0) return vec3(0.0);
    vec3 e = (u_zodiacal_rot * vec4(d, 0.0)).xyz;
    float v = SKY_TEX2D(u_zodiacal_tex, vec2(sqrt(max(0.5 + 0.5 * e.x, 0.0)), abs(e.z))).r;
    return u_zodiacal.rgb * exp(v * u_zodiacal.a);
}
