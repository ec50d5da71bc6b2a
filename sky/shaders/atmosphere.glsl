/* atmosphere.glsl: what every atmosphere path shares: the night sky's own
 * light, the darkening below the horizon, and the air-mass extinction the
 * non-physical paths use for light from behind the atmosphere. */
uniform float u_night_luminance;  /* kcd/m^2 of the night sky (moonlit or not) */
uniform vec4 u_eclipse_sky;       /* solar eclipse: x the day sky's light left,
                                     yzw the extra left at the horizon (rgb) */

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

/* The night sky's airglow and scattered moonlight: bluish, brighter toward
 * the horizon where the path through the glowing layer is longer. */
vec3 sky_night_floor(vec3 d)
{
    return u_night_luminance * vec3(0.55, 0.7, 1.0) * (2.0 - clamp(d.y, 0.0, 1.0));
}

/* Below the horizon a path shows the haze of the horizon, darkening with
 * depth, so a host's terrain gap shows haze rather than black: the
 * direction to evaluate is the horizon's below the point (else a sun
 * under the horizon would shine through the ground), and the factor
 * that darkens it. */
vec3 sky_horizon_clamp(vec3 d)
{
    float h = length(d.xz);
    return d.y < 0.0 ? (h > 1e-6 ? vec3(d.x / h, 0.0, d.z / h) : vec3(0.0, 0.0, -1.0)) : d;
}
float sky_below_horizon(vec3 d) { return d.y < 0.0 ? 1.0 / (1.0 - 4.0 * d.y) : 1.0; }

/* Extinction toward space with a Kasten-Young-like air mass that stays
 * finite at the horizon (zero below it: the ground). */
float sky_air_mass_transmittance(vec3 d)
{
    float s = max(d.y, 0.0);
    float airmass = 1.0 / (s + 0.025 * exp(-11.0 * s));
    return d.y < 0.0 ? 0.0 : exp(-0.25 * airmass);
}
