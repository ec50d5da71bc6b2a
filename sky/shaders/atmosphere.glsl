/* atmosphere.glsl: what every atmosphere path shares: the night sky's own
 * light, the darkening below the horizon, and the air-mass extinction the
 * non-physical paths use for light from behind the atmosphere. */
uniform SKY_UP vec3 u_night_floor;      /* zenith kcd/m^2 of the stars fainter than the
                                    star map and the moonlit air (atmosphere.c) */
uniform SKY_UP vec3 u_artificial_glow;  /* zenith kcd/m^2 of light pollution          */
uniform SKY_UP vec3 u_night_depth;      /* the air's zenith optical depths             */
uniform SKY_UP vec3 u_night_air;        /* the shell, observer radius a, top b:
                                    (b/a)^2 - 1, 2 + (b - a)/a, a/(b - a)      */
uniform SKY_UP vec4 u_eclipse_sky;       /* solar eclipse: x the day sky's light left,
                                     yzw the extra left at the horizon (rgb) */
uniform SKY_UP vec3 u_ground;            /* kcd/m^2: the ground lit by sun and sky     */
uniform SKY_UP vec3 u_horizon;           /* kcd/m^2: the sky just above the horizon, its
                                     mean over azimuth                        */
uniform SKY_UP vec3 u_moonlit_light;     /* the physical paths' moonlit sky: the moon's
                                     light above the air (0 by day); the dome's
                                     vertices carry that sky per unit of it   */

/* The physical paths' moonlit sky (Jensen et al. 2001: their own model
 * lit by the moon, atmosphere.c) from the dome vertex's value per unit of
 * the moon's light: one multiply a pixel. */
vec3 sky_moonlit(vec3 per_unit) { return per_unit * u_moonlit_light; }

/* A solar eclipse dims the day sky by the light the moon hides (x). Around
 * totality what is left comes from the air outside the moon's shadow, lit
 * by the partly eclipsed sun and seen along long, low paths: a yellow-
 * orange ring along the horizon (yzw), fading within about 15 degrees of
 * it ((1 - sin h)^8). Without an eclipse x = 1 and yzw = 0. */
vec3 sky_eclipse_dim(vec3 d)
{
    float e = 1.0 - clamp(d.y, 0.0, 1.0);
    float e2 = e * e, e4 = e2 * e2;
    return vec3(u_eclipse_sky.x) + u_eclipse_sky.yzw * (e4 * e4);
}

/* What no night layer draws (atmosphere.c): the faint stars and the
 * moonlit air, brighter toward the horizon, and light pollution's glow,
 * about four times the zenith's at the horizon. */
vec3 sky_night_floor(vec3 d)
{
    float y = clamp(d.y, 0.0, 1.0);
    return u_night_floor * (2.0 - y) + u_artificial_glow * pow(1.15 / (y + 0.15), 0.7);
}

/* What the air leaves of light from above it seen along d, per channel:
 * the zenith depths over the path through a shell (Mueller eq. 11), in
 * units of the shell's thickness t. The path sqrt(b^2 - a^2 (1 - c^2)) -
 * a c is a (sqrt(k + c^2) - c) with k = (b/a)^2 - 1, written above the
 * horizon without its cancellation, a k / t (sqrt(k + c^2) + c), and
 * without a km^2 anywhere: a fragment stage without highp holds 2^14. */
vec3 sky_night_extinction(vec3 d)
{
    float c = clamp(d.y, -1.0, 1.0);
    float root = sqrt(u_night_air.x + c * c);
    float air_mass = c >= 0.0 ? u_night_air.y / (root + c) : min(u_night_air.z * (root - c), 1e4);
    return exp(-u_night_depth * air_mass);
}

/* One rule below the horizon for every path (atmosphere.c): a Lambertian
 * ground of the atmosphere's albedo lit by the sun and by the sky, seen
 * through the haze of the horizon, which fades into it over the first two
 * degrees. Both are means over azimuth, so no column of light stands
 * under a low sun, and a twilight sky lights its ground. The paths
 * evaluate their sky at the horizon's direction above a point under it
 * (a sun under the horizon must not shine through the ground) and then
 * take this instead. */
vec3 sky_horizon_clamp(vec3 d)
{
    float h = length(d.xz);
    return d.y < 0.0 ? (h > 1e-6 ? vec3(d.x / h, 0.0, d.z / h) : vec3(0.0, 0.0, -1.0)) : d;
}
vec3 sky_ground(vec3 d) { return mix(u_horizon, u_ground, smoothstep(0.0, 0.035, -d.y)); }
vec3 sky_or_ground(vec3 d, vec3 sky) { return d.y < 0.0 ? sky_ground(d) : sky; }

/* Extinction toward space with a Kasten-Young-like air mass that stays
 * finite at the horizon (zero below it: the ground). */
float sky_air_mass_transmittance(vec3 d)
{
    float s = max(d.y, 0.0);
    float airmass = 1.0 / (s + 0.025 * exp(-11.0 * s));
    return d.y < 0.0 ? 0.0 : exp(-0.25 * airmass);
}
