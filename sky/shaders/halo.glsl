/* halo.glsl: the halos (halo.c), light in front of the sky and the clouds
 * (dome.frag's sky_front_lights): the 22 and 46 degree halos around the
 * sun and the moon from the table, and the parhelia beside them at their
 * elevation; the moon's in grey. */
uniform sampler2D u_halo_tex;         /* rho from the light across, 0..60 degrees: sqrt of
                                         the light per steradian over its peak */
uniform SKY_UP vec4 u_halo;           /* rgb: the sun's halos at the table's 1, kcd/m^2 */
uniform SKY_UP vec4 u_halo_moon;      /* rgb: the moon's (grey) */
uniform SKY_UP vec4 u_halo_dogs;      /* rgb: the sun's parhelia's distance in azimuth per
                                         channel, radians; a: their strength (0: none) */
uniform SKY_UP vec4 u_halo_moon_dogs; /* the moon's */

vec3 sky_halo_table(vec3 d, vec3 l)
{
    float rho = acos(clamp(dot(d, l), -1.0, 1.0)) * (1.0 / 1.0471976); /* over 60 degrees */
    if (rho >= 1.0) return vec3(0.0);
    vec3 e = SKY_TEX2D(u_halo_tex, vec2((0.5 + rho * 255.0) / 256.0, 0.5)).rgb;
    return e * e;
}

/* The parhelia at light l's elevation (1.3 degrees each way: the plates'
 * wobble), on either side at the distance in azimuth past which the
 * plates' light falls off as 1 / sqrt, smoothed over a degree (the sun's
 * disc); six times the halo's peak at theirs (sundogs outshine it). */
vec3 sky_halo_parhelia(vec3 d, vec3 l, vec4 dogs)
{
    if (dogs.a <= 0.0) return vec3(0.0);
    float dy = (asin(clamp(d.y, -1.0, 1.0)) - asin(clamp(l.y, -1.0, 1.0))) * (1.0 / 0.0175); /* degrees */
    float az = abs(atan(d.x * l.z - d.z * l.x, d.x * l.x + d.z * l.z));
    vec3 past = vec3(az) - dogs.rgb, w = vec3(0.0175);
    vec3 profile = sqrt(w / (max(past, vec3(0.0)) + w)) * smoothstep(-w, vec3(0.0), past);
    return 6.0 * dogs.a * exp(-0.3 * dy * dy) * profile;
}

vec3 sky_halo(vec3 d)
{
    float above = smoothstep(-0.03, 0.03, d.y);
    if (above <= 0.0) return vec3(0.0);
    vec3 L = u_halo.rgb * (sky_halo_table(d, u_sun_dir) + sky_halo_parhelia(d, u_sun_dir, u_halo_dogs)) +
             u_halo_moon.rgb * dot(sky_halo_table(d, u_moon_dir) + sky_halo_parhelia(d, u_moon_dir, u_halo_moon_dogs),
                                   vec3(0.2126, 0.7152, 0.0722));
    return L * above;
}
