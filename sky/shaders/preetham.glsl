/* preetham.glsl: Preetham, Shirley & Smits (1999): the Perez et al. sky
 * luminance distribution (eq. 3) for Y and the chromaticities x and y,
 * with coefficients fitted to turbidity (appendix A.2), computed per frame
 * on the CPU (preetham.c). Pure arithmetic: no texture. */
uniform SKY_UP vec3 u_perez_a, u_perez_b, u_perez_c, u_perez_d, u_perez_e; /* for (Y, x, y) */
uniform SKY_UP vec3 u_perez_zenith; /* (Y_z, x_z, y_z) / F(0, theta_s), Y in kcd/m^2, Y times
                              the twilight scale (preetham.c: measured twilight) */
uniform SKY_UP vec3 u_perez_moon_zenith; /* the same for the moonlit sky, Y times the moon's
                                   light over the sun's; 0 by day (preetham.c) */
uniform SKY_UP vec3 u_moon_tint;         /* the moon's colour, unit luminance            */

/* F(theta, gamma) for a light along l with the given zenith values, in
 * linear sRGB. At and below the horizon the distribution takes its
 * horizon value (cos theta held at 1e-3: B / cos theta -> -inf, the term
 * -> 0). */
vec3 sky_perez_rgb(vec3 d, vec3 l, vec3 zenith)
{
    float cos_theta = max(d.y, 1e-3);
    float cos_gamma = clamp(dot(d, l), -1.0, 1.0);
    float gamma = acos(cos_gamma);
    vec3 F = (1.0 + u_perez_a * exp(u_perez_b / cos_theta)) *
             (1.0 + u_perez_c * exp(u_perez_d * gamma) + u_perez_e * cos_gamma * cos_gamma);
    vec3 Yxy = zenith * F;
    /* xyY -> XYZ -> linear sRGB (IEC 61966-2-1) */
    float y = max(Yxy.z, 1e-4);
    vec3 XYZ = vec3(Yxy.y / y, 1.0, (1.0 - Yxy.y - Yxy.z) / y) * Yxy.x;
    vec3 rgb = vec3(dot(vec3(3.2406, -1.5372, -0.4986), XYZ), dot(vec3(-0.9689, 1.8758, 0.0415), XYZ),
                    dot(vec3(0.0557, -0.2040, 1.0570), XYZ));
    return max(rgb, vec3(0.0));
}

/* The sky's radiance (kcd/m^2) without the night floor, also the blend's
 * analytic partner (blend.glsl, sky_config.blend_partner). */
vec3 sky_preetham_radiance(vec3 view) { return sky_perez_rgb(sky_horizon_clamp(view), u_sun_dir, u_perez_zenith); }

/* The moonlit sky (Jensen et al. 2001): the same model lit by the moon,
 * Preetham's own path only (the blend's night is Hillaire's). A uniform
 * branch: nothing by day. */
vec3 sky_preetham_moonlit(vec3 view)
{
    if (u_perez_moon_zenith.x <= 0.0) return vec3(0.0);
    return sky_perez_rgb(sky_horizon_clamp(view), u_moon_dir, u_perez_moon_zenith) * u_moon_tint;
}

#ifndef SKY_HAS_BLEND
vec3 sky_atmosphere(vec3 view, vec3 day)
{
    vec3 sky = sky_preetham_radiance(view) + sky_preetham_moonlit(view);
    return sky_or_ground(view, sky * sky_eclipse_dim(view) + sky_night_floor(view));
}

/* (the blend's is extinction.glsl's) */
float sky_atmosphere_transmittance(vec3 d) { return sky_air_mass_transmittance(d); }
#endif
