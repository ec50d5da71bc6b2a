/* rainbow.glsl: the rainbows (rainbow.c), light in front of the sky and
 * the clouds (dome.frag's sky_front_lights): the table's primary and
 * secondary bows around the point opposite the sun, and the moon's in
 * grey, in the rain below its top. */
uniform sampler2D u_rainbow_tex;  /* rho across (0..64 degrees), the drops' radius down;
                                     sqrt of the light per steradian over its peak */
uniform SKY_UP vec4 u_rainbow;      /* rgb: the sun's bow at the table's 1, kcd/m^2; a: the drops' row */
uniform SKY_UP vec4 u_rainbow_moon; /* rgb: the moon's (grey), a: unused */
uniform SKY_UP vec2 u_rainbow_rain; /* the sines of the rain's (or fog's) bottom and top in view */

/* The table around the point opposite light direction l. */
vec3 sky_rainbow_table(vec3 d, vec3 l)
{
    float rho = acos(clamp(-dot(d, l), -1.0, 1.0)) * (1.0 / 1.1170107); /* over 64 degrees */
    if (rho >= 1.0) return vec3(0.0);
    vec3 e = SKY_TEX2D(u_rainbow_tex, vec2((0.5 + rho * 255.0) / 256.0, u_rainbow.a)).rgb;
    return e * e;
}

vec3 sky_rainbow(vec3 d)
{
    /* the rain hangs below its top and fades into the distance at the
     * horizon (fog lies all around: its bow goes on below the horizon);
     * each edge over a few degrees */
    float rain = smoothstep(u_rainbow_rain.x - 0.03, u_rainbow_rain.x + 0.03, d.y) *
                 (1.0 - smoothstep(u_rainbow_rain.y - 0.05, u_rainbow_rain.y + 0.05, d.y));
    if (rain <= 0.0) return vec3(0.0);
    vec3 L = u_rainbow.rgb * sky_rainbow_table(d, u_sun_dir) +
             u_rainbow_moon.rgb * dot(sky_rainbow_table(d, u_moon_dir), vec3(0.2126, 0.7152, 0.0722));
    return L * rain;
}
