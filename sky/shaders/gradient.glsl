/* gradient.glsl: Roden-Parberry's day sky (sec. 2, fig. 1 inset): a blue
 * gradient by elevation (interpolated from the dome's vertices), scaled by
 * the daylight luminance for the sun's altitude, with a forward-scattering
 * aureole tinted by the sunlight that reaches it and a faint night floor;
 * and the same gradient and aureole lit by the moon (gradient.c). */
uniform SKY_UP float u_day_luminance;    /* kcd/m^2 of a gradient texel of value 1 */
uniform SKY_UP vec3 u_sun_transmittance;
uniform SKY_UP vec3 u_horizon_tint;      /* colour of the low-sun horizon, see gradient.c */
uniform SKY_UP vec3 u_moon_sky;          /* the moonlit gradient's scale, per channel      */
uniform SKY_UP vec3 u_moon_beam;         /* the moon's light through the air               */

/* The two lobes of the aureole around a light at cosine mu from d, at
 * elevation sine e: a broad and a narrow one, strongest near the horizon
 * where the path is long. */
float sky_gradient_aureole(float mu, float e)
{
    float mu2 = mu * mu, mu4 = mu2 * mu2, mu8 = mu4 * mu4;
    return (0.25 * mu8 + 0.6 * mu8 * mu8 * mu8 * mu8) * (1.0 + 1.5 * (1.0 - e));
}

vec3 sky_atmosphere(vec3 d, vec3 day)
{
    /* (below the horizon: atmosphere.glsl's ground) */
    float e = clamp(d.y, 0.0, 1.0);
    float mu = max(dot(d, u_sun_dir), 0.0);
    float aureole = sky_gradient_aureole(mu, e);
    /* Low sun: the horizon takes the colour of the light that reaches it,
     * most strongly on the sun's side. */
    float low = (1.0 - e) * (1.0 - e) * (0.6 + 0.4 * mu) / (1.0 - 6.0 * min(d.y, 0.0));
    vec3 L = u_day_luminance * (day * mix(vec3(1.0), u_horizon_tint, low) + aureole * u_sun_transmittance) +
             u_moon_sky * (day + sky_gradient_aureole(max(dot(d, u_moon_dir), 0.0), e) * u_moon_beam);
    return sky_or_ground(d, L * sky_eclipse_dim(d) + sky_night_floor(d));
}

float sky_atmosphere_transmittance(vec3 d) { return sky_air_mass_transmittance(d); }
