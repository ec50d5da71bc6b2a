/* sun.frag: limb-darkened solar disc (Schneegans et al. eq. 1, u = 0.6)
 * with a small glare halo, dimmed by the atmosphere, eclipsed by the
 * moon's true disc with the corona around it, and hidden by clouds. Drawn
 * additively over the dome. */
uniform SKY_UP float u_sun_radius;     /* angular radius, radians                */
uniform SKY_UP vec3 u_sun_disc;        /* kcd/m^2 at the disc centre, through the
                                   air (sun.c: within mediump's range)    */
uniform SKY_UP vec3 u_sun_glare;       /* the glare's peak, through the air      */
uniform SKY_UP vec3 u_sun_transmittance;
uniform SKY_UP vec4 u_eclipse_sun;     /* x: moon's angular radius, y: the sun's
                                   light left, z: corona scale (kcd/m^2) */
SKY_IN vec3 v_dir;
SKY_IN vec3 v_sun_plane;  /* the true direction on the tangent planes at */
SKY_IN vec3 v_moon_plane; /* the two centres (sun.vert)                 */

void main()
{
    vec3 view = normalize(v_dir);
    /* (nothing is drawn below the refracted horizon, but the discard waits
     * until the derivatives below have been taken in uniform control flow) */
    /* the tangent of the angle from the centre (the angle itself within
     * 0.2 % out to the quad's edge, 16 radii) */
    float phi = v_sun_plane.z > 0.0 ? length(v_sun_plane.xy) / v_sun_plane.z : 1.0;
    float r = phi / u_sun_radius;
    float disc = 0.0;
    if (r < 1.0) disc = 1.0 - 0.6 * (1.0 - sqrt(max(1.0 - r * r, 0.0)));
    /* the moon in front: its edge smoothed over about a pixel outside the
     * true disc, so a total eclipse leaves no partly lit pixel at the
     * sun's limb */
    float to_moon = v_moon_plane.z > 0.0 ? length(v_moon_plane.xy) / v_moon_plane.z : 1.0;
#ifdef SKY_NO_DERIVATIVES
    float edge = max(u_pixel_angle, 1e-7); /* to_moon changes by about the pixel's angle across it */
#else
    float edge = max(fwidth(to_moon), 1e-7);
#endif
    float behind_moon = 1.0 - smoothstep(u_eclipse_sun.x, u_eclipse_sun.x + 1.5 * edge, to_moon);
    disc *= 1.0 - behind_moon;
    /* Glare: falls off with the square of the distance from the limb and is
     * windowed to zero at the quad's edge (16 radii) so no square shows.
     * It is the air's, in front of the moon, and carries the share of the
     * sun's light the moon leaves. */
    float out_r = max(r - 1.0, 0.0);
    float window = max(1.0 - r / 16.0, 0.0);
    float glare = window * window / (1.0 + out_r * out_r) * u_eclipse_sun.y;
    /* the corona (Baumbach's bracket, sun.c), behind the moon */
    float corona = 0.0;
    if (u_eclipse_sun.z > 0.0) {
        float ir = 1.0 / max(r, 1.0), ir2 = ir * ir, ir7 = ir2 * ir2 * ir2 * ir;
        corona = u_eclipse_sun.z * (0.0532 * ir2 * sqrt(ir) + 1.425 * ir7 + 2.565 * ir7 * ir7 * ir2 * ir) * window *
                 (1.0 - behind_moon);
    }
    vec3 L = u_sun_disc * disc + u_sun_glare * glare + corona * u_sun_transmittance;
#if defined(SKY_HAS_CLOUDS) || defined(SKY_HAS_DOME_COVER)
    L *= 1.0 - sky_front_cover(view);
#endif
    /* nothing below the refracted horizon: there the ground is */
    if (view.y < 0.0) discard;
    /* Additive: where the sun adds nothing visible, add nothing at all (the
     * dome already carries the dither). */
    if (u_output_hdr < 0.5 && max(L.r, max(L.g, L.b)) * sky_display_exposure < 1.0 / 1024.0) discard;
    SKY_FRAG_COLOR = sky_output(L, 1.0);
}
