/* rainbow.glsl: the rainbows (rainbow.c), light in front of the sky and
 * the clouds (dome.frag's sky_front_lights): the table's primary and
 * secondary bows around the point opposite the light that makes the
 * brighter bow (rainbow.c picks the sun or the moon: one lookup a pixel),
 * the moon's in grey, in the rain below its top. */
uniform sampler2D u_rainbow_tex;     /* rho across (0..64 degrees), the drops' radius down;
                                        sqrt of the light per steradian over its peak */
uniform SKY_UP vec4 u_rainbow;       /* rgb: the bow at the table's 1, kcd/m^2; a: the drops' row */
uniform SKY_UP vec4 u_rainbow_light; /* xyz: toward its light; w: 1 grey (the moon's), 0 in colour */
uniform SKY_UP vec2 u_rainbow_rain;  /* the sines of the rain's (or fog's) bottom and top in view */

vec3 sky_rainbow(vec3 d)
{
    /* the rain hangs below its top and fades into the distance at the
     * horizon (fog lies all around: its bow goes on below the horizon);
     * each edge over a few degrees */
    float rain = smoothstep(u_rainbow_rain.x - 0.03, u_rainbow_rain.x + 0.03, d.y) *
                 (1.0 - smoothstep(u_rainbow_rain.y - 0.05, u_rainbow_rain.y + 0.05, d.y));
    float rho = acos(clamp(-dot(d, u_rainbow_light.xyz), -1.0, 1.0)) * (1.0 / 1.1170107); /* over 64 degrees */
    vec3 e = SKY_TEX2D(u_rainbow_tex, vec2((0.5 + min(rho, 1.0) * 255.0) / 256.0, u_rainbow.a)).rgb;
    e *= e * (rain * step(rho, 1.0));
    return u_rainbow.rgb * mix(e, vec3(dot(e, vec3(0.2126, 0.7152, 0.0722))), u_rainbow_light.w);
}
