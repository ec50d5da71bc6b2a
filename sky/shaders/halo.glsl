/* halo.glsl: the halos (halo.c), light in front of the sky and the clouds
 * (dome.frag's sky_front_lights): the 22 and 46 degree halos from the
 * table and the parhelia beside them at its elevation, around the light
 * that makes the brighter halo (halo.c picks the sun or the moon: one
 * lookup a pixel), the moon's in grey. */
uniform sampler2D u_halo_tex;      /* rho from the light across, 0..60 degrees: sqrt of
                                      the light per steradian over its peak */
uniform SKY_UP vec4 u_halo;        /* rgb: the halos at the table's 1, kcd/m^2; a: 1 grey (the moon's) */
uniform SKY_UP vec4 u_halo_light;  /* xyz: toward the light; w: 1 / the cosine of its elevation */
uniform SKY_UP vec4 u_halo_dogs;   /* rgb: the parhelia's distance in azimuth per channel,
                                      radians; a: their strength (0: none) */

vec3 sky_halo(vec3 d)
{
    vec3 l = u_halo_light.xyz;
    float rho = acos(clamp(dot(d, l), -1.0, 1.0)) * (1.0 / 1.0471976); /* over 60 degrees */
    vec3 e = SKY_TEX2D(u_halo_tex, vec2((0.5 + min(rho, 1.0) * 255.0) / 256.0, 0.5)).rgb;
    e *= e * step(rho, 1.0);
    /* The parhelia at the light's elevation (1.3 degrees each way: the
     * plates' wobble; the elevations' difference as the sines' over the
     * light's cosine), on either side at the distance in azimuth past
     * which the plates' light falls off as 1 / sqrt, smoothed over a
     * degree (the sun's disc); six times the halo's peak at theirs
     * (sundogs outshine it). */
    float dy = (d.y - l.y) * u_halo_light.w * (1.0 / 0.0175); /* degrees */
    float across = inversesqrt(max(1.0 - d.y * d.y, 1e-6)) * u_halo_light.w;
    float az = acos(clamp(dot(d.xz, l.xz) * across, -1.0, 1.0));
    vec3 past = vec3(az) - u_halo_dogs.rgb, w = vec3(0.0175);
    vec3 dogs = sqrt(w / (max(past, vec3(0.0)) + w)) * smoothstep(-w, vec3(0.0), past);
    e += (6.0 * u_halo_dogs.a * exp(-0.3 * dy * dy)) * dogs;
    return u_halo.rgb * mix(e, vec3(dot(e, vec3(0.2126, 0.7152, 0.0722))), u_halo.a) * smoothstep(-0.03, 0.03, d.y);
}
