/* preetham.glsl: Preetham, Shirley & Smits (1999): the Perez et al. sky
 * luminance distribution (eq. 3) for Y and the chromaticities x and y,
 * with coefficients fitted to turbidity (appendix A.2), computed per frame
 * on the CPU (preetham.c). Pure arithmetic: no texture. */
uniform SKY_UP vec3 u_perez_a, u_perez_b, u_perez_c, u_perez_d, u_perez_e; /* for (Y, x, y) */
uniform SKY_UP vec3 u_perez_zenith; /* (Y_z, x_z, y_z) / F(0, theta_s), Y in kcd/m^2, Y times
                              the twilight scale (preetham.c: measured twilight) */

/* The sky's radiance (kcd/m^2) without the night floor, also the blend's
 * analytic partner (blend.glsl, sky_config.blend_partner). */
vec3 sky_preetham_radiance(vec3 view)
{
    /* At and below the horizon the distribution takes its horizon value
     * (cos theta held at 1e-3: B / cos theta -> -inf, the term -> 0). */
    vec3 d = sky_horizon_clamp(view);
    float cos_theta = max(d.y, 1e-3);
    float cos_gamma = clamp(dot(d, u_sun_dir), -1.0, 1.0);
    float gamma = acos(cos_gamma);
    vec3 F = (1.0 + u_perez_a * exp(u_perez_b / cos_theta)) *
             (1.0 + u_perez_c * exp(u_perez_d * gamma) + u_perez_e * cos_gamma * cos_gamma);
    vec3 Yxy = u_perez_zenith * F;
    /* xyY -> XYZ -> linear sRGB (IEC 61966-2-1) */
    float y = max(Yxy.z, 1e-4);
    vec3 XYZ = vec3(Yxy.y / y, 1.0, (1.0 - Yxy.y - Yxy.z) / y) * Yxy.x;
    vec3 rgb = vec3(dot(vec3(3.2406, -1.5372, -0.4986), XYZ), dot(vec3(-0.9689, 1.8758, 0.0415), XYZ),
                    dot(vec3(0.0557, -0.2040, 1.0570), XYZ));
    return max(rgb, vec3(0.0));
}

#ifndef SKY_HAS_BLEND
vec3 sky_atmosphere(vec3 view, vec3 day)
{
    return sky_or_ground(view, sky_preetham_radiance(view) * sky_eclipse_dim(view) + sky_night_floor(view));
}

/* (the blend's is extinction.glsl's) */
float sky_atmosphere_transmittance(vec3 d) { return sky_air_mass_transmittance(d); }
#endif
