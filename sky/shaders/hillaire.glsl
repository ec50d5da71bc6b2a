/* hillaire.glsl: Hillaire 2020's sky-view table (hillaire.c builds it):
 * one bilinear fetch per pixel. The table is radiance per unit solar
 * illuminance; the texture holds it as float (CORE33) or, in 8 bits
 * (COMPAT20), as a 16-bit log2 luminance split over two channels and an
 * rg chromaticity. A GPU may filter an 8-bit texture at 8-bit precision,
 * which would cut the 16-bit level back to 8 (steps of 7 %: bands), so
 * COMPAT20 reads the four texels unfiltered (NEAREST) and blends the
 * decoded colours itself: 2700 levels per stop survive. */
uniform sampler2D u_skyview;
uniform SKY_UP vec4 u_skyview_map;     /* xy: table size in texels, zw: table size / texture size */
uniform SKY_UP vec2 u_skyview_horizon; /* theta_h (zenith angle of the horizon), pi - theta_h */
uniform SKY_UP vec3 u_skyview_decode;  /* x: 1 = 8-bit encoding, y: log2 of the dimmest value, z: stops covered */

#ifdef SKY_HILLAIRE_ENCODED
vec3 sky_skyview_decode(vec2 uv)
{
    vec4 t = SKY_TEX2D(u_skyview, uv);
    /* the 16-bit level in 0..1, its weights written out: 1 / 65535 is
     * below mediump's smallest normal number, and a compiler that turns
     * the division into it at mediump flushes the level to 0 */
    float level = t.r * 0.99610895 + t.g * 0.0038910506; /* 65280 / 65535, 255 / 65535 */
    float Y = level > 0.0 ? exp2(u_skyview_decode.y + u_sun_gain_log2 + level * u_skyview_decode.z) : 0.0; /* 0: black */
    vec3 c = vec3(t.b, t.a, 1.0 - t.b - t.a);
    return c * (Y / max(dot(c, vec3(0.2126, 0.7152, 0.0722)), 1e-4));
}
#endif

vec3 sky_hillaire_radiance(vec3 d)
{
    /* Hillaire sec. 5.3: the horizon at v = 0.5, texels concentrated
     * toward it from both sides; u = sin(azimuth from the sun / 2) */
    float th = acos(clamp(d.y, -1.0, 1.0));
    float v = th < u_skyview_horizon.x ? 0.5 - 0.5 * sqrt(max(1.0 - th / u_skyview_horizon.x, 0.0))
                                       : 0.5 + 0.5 * sqrt(clamp((th - u_skyview_horizon.x) / u_skyview_horizon.y, 0.0, 1.0));
    float hd = length(d.xz), hs = length(u_sun_dir.xz);
    float cos_az = hd * hs > 1e-6 ? dot(d.xz, u_sun_dir.xz) / (hd * hs) : 1.0;
    float u = sqrt(clamp(0.5 - 0.5 * cos_az, 0.0, 1.0));
    /* position in table texels, 0 .. size - 1 between the edge centres */
    vec2 p = vec2(u, v) * (u_skyview_map.xy - 1.0);
    vec2 texture_size = u_skyview_map.xy / u_skyview_map.zw;
#ifdef SKY_HILLAIRE_ENCODED
    vec2 i0 = floor(p), f = p - i0;
    vec2 i1 = min(i0 + 1.0, u_skyview_map.xy - 1.0);
    vec3 a = mix(sky_skyview_decode((vec2(i0.x, i0.y) + 0.5) / texture_size),
                 sky_skyview_decode((vec2(i1.x, i0.y) + 0.5) / texture_size), f.x);
    vec3 b = mix(sky_skyview_decode((vec2(i0.x, i1.y) + 0.5) / texture_size),
                 sky_skyview_decode((vec2(i1.x, i1.y) + 0.5) / texture_size), f.x);
    vec3 L = mix(a, b, f.y);
#else
    vec3 L = SKY_TEX2D(u_skyview, (p + 0.5) / texture_size).rgb * exp2(u_sun_gain_log2);
#endif
    /* (the encoded table's decoding put the irradiance's gain back) */
    return u_sun_irradiance * L;
}

#ifndef SKY_HAS_BLEND
vec3 sky_atmosphere(vec3 d, vec3 moonlit)
{
    /* the table's own ground is lit by the sun alone (black under a
     * twilight sky): atmosphere.glsl's rule instead */
    return sky_or_ground(d, (sky_hillaire_radiance(d) + sky_moonlit(moonlit)) * sky_eclipse_dim(d) +
                                sky_night_floor(d));
}
#endif
