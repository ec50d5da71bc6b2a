/* stars.frag: a star's point spread (Mueller sec. 4.2): the intensity PSF
 * T(l) = 2l^3 - 3l^2 + 1 over radius q, normalised so that it integrates
 * to the star's illuminance (eq. 10 in physical units), plus the glare
 * PSF G(l) = 1 - l^(1/6) over the enlarged radius k, its light taken
 * from the star's (stars.vert), so the two sum to the illuminance; then
 * extinction over the optical path (eq. 11-12), scintillation growing toward the horizon,
 * the day-night fade (sec. 5) and the clouds in front. Added to the dome.
 * What is the same across the point comes from stars.vert. */
SKY_IN vec3 v_dir;
SKY_IN vec3 v_light;  /* the peak's light, with extinction and twinkle (stars.vert) */
SKY_IN vec2 v_center;
SKY_IN vec2 v_size;

void main()
{
    float l = length(sky_point_offset(v_center, sky_star_point_size(v_size.x))) / v_size.x;
    if (l >= 1.0) discard;
    float ls = l * v_size.y;                   /* distance in units of q */
    float psf = ls < 1.0 ? (2.0 * ls - 3.0) * ls * ls + 1.0 : 0.0;
    float glare = v_size.y > 1.0 ? 0.01 * (1.0 - pow(l, 1.0 / 6.0)) : 0.0;
    vec3 L = v_light * (psf + glare);
#if defined(SKY_HAS_CLOUDS) || defined(SKY_HAS_DOME_COVER)
    L *= 1.0 - sky_front_cover(v_dir);
#endif
    if (u_output_hdr < 0.5 && max(L.r, max(L.g, L.b)) * sky_display_exposure < 1.0 / 1024.0) discard;
    SKY_FRAG_COLOR = sky_output(L, 1.0);
}
