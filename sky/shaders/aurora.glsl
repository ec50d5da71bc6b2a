/* aurora.glsl: the aurora's curtains (aurora.c, which has the model and
 * its C twin, aurora_at): vertical sheets along geomagnetic east, one
 * every u_aurora_oval.z km poleward of the oval's equatorward edge, each
 * crossed once by the ray; green from a sharp lower edge at 95-110 km,
 * red tops from 170-250 km. dome.frag dims it by the air below. */
uniform SKY_UP vec4 u_aurora_axes;  /* xy: poleward unit (horizon x, z); z: observer's radius / R; w: rays' phase */
uniform SKY_UP vec4 u_aurora_oval;  /* km poleward: edge, poleward edge; z: spacing; w: wander phase */
uniform SKY_UP vec4 u_aurora_green; /* rgb: kcd/m^2 face-on (0: none); a: the seed's phase */
uniform SKY_UP vec4 u_aurora_red;   /* rgb: kcd/m^2 face-on; a: the folds' phase */

/* the aurora's light of this fragment's last sky_aurora (before the air
 * dims it), for dome.frag's colour vision (sky_aurora_brighter) */
vec3 sky_aurora_seen;

float sky_aurora_hash(float k)
{
    return fract(sin(k * 12.9898 + u_aurora_green.a) * 43758.5453);
}

/* the ground distance (km) where a ray of elevation e (cosine c) reaches h km */
float sky_aurora_ground(float e, float c, float h)
{
    return 6371.0 * (acos(clamp(c * u_aurora_axes.z * 6371.0 / (6371.0 + h), -1.0, 1.0)) - e);
}

vec3 sky_aurora(vec3 d)
{
    sky_aurora_seen = vec3(0.0);
    if (d.y <= 0.0 || u_aurora_green.g <= 0.0) return vec3(0.0);
    float y = min(d.y, 1.0);
    float c = sqrt(max(1.0 - y * y, 0.0));
    vec2 hd = c > 1e-6 ? d.xz / c : vec2(0.0);
    float cn = dot(hd, u_aurora_axes.xy);
    float ce = -hd.x * u_aurora_axes.y + hd.y * u_aurora_axes.x;
    float e = asin(y);
    float s_lo = sky_aurora_ground(e, c, 95.0), s_hi = sky_aurora_ground(e, c, 320.0);
    float nb = u_aurora_oval.x, np = u_aurora_oval.y, sp = u_aurora_oval.z, ph = u_aurora_red.a;
    float k0 = max(floor((min(s_lo * cn, s_hi * cn) - 60.0 - nb) / sp - 0.8), 0.0);
    float cn_safe = cn < 0.0 ? min(cn, -0.03) : max(cn, 0.03);
    vec3 L = vec3(0.0);
    for (int i = 0; i < 2; i++) { /* two sheets (aurora.c's twin alike): the cost */
        float k = k0 + float(i);
        float h1 = sky_aurora_hash(k), h2 = fract(h1 * 61.7 + 0.37);
        float nk = nb + (k + 0.5 + 0.3 * sin(6.2832 * h1 + u_aurora_oval.w)) * sp;
        float oval = smoothstep(nb - 100.0, nb + 100.0, nk) * (1.0 - smoothstep(np - 200.0, np + 50.0, nk));
        /* the ray's ground distance to the folded sheet: one step of
         * g = (nk + fold(g ce)) / cn */
        float g = nk / cn_safe;
        g = (nk + 60.0 * (0.65 * sin(g * ce / 330.0 + 6.2832 * h1 + ph) +
                          0.35 * sin(g * ce / 130.0 + 6.2832 * h2 - 2.0 * ph))) / cn_safe;
        float east = g * ce;
        /* the long wave's slope: what turns the curtain toward the eye */
        float slope = 60.0 * 0.65 / 330.0 * cos(east / 330.0 + 6.2832 * h1 + ph);
        float local = cos(e + g / 6371.0);
        float h = 6371.0 * (u_aurora_axes.z * c / max(local, 0.02) - 1.0);
        float green = smoothstep(95.0, 110.0, h) * exp(-max(h - 110.0, 0.0) / 30.0);
        float red = smoothstep(170.0, 250.0, h) * exp(-max(h - 250.0, 0.0) / 50.0);
        float oblique = 1.0 / max(abs(cn - slope * ce) * local, 0.15); /* aurora.c: OBLIQUITY_MAX */
        float envelope = 0.25 + 0.75 * smoothstep(-0.3, 0.8, sin(east / 700.0 + 6.2832 * h2 + ph));
        float rays = 0.55 + 0.45 * sin(east / 15.0 + 40.0 * h1 + u_aurora_axes.w) * sin(east / 6.5 + 2.0 * u_aurora_axes.w);
        float w = (g > 0.0 && local > 0.02) ? oval * oblique * envelope * rays * (0.4 + 0.6 * h2) : 0.0;
        L += (u_aurora_green.rgb * green + u_aurora_red.rgb * red) * w;
    }
    sky_aurora_seen = L;
    return L;
}

/* For the night's blue shift (display.glsl): how many times brighter a
 * pixel counts for the cones' share, where the aurora is part of its
 * light L (aurora: its share, through the air). Jensen's model sees no
 * colour at all below 0.01 cd/m^2, broad-band light in mind; observers
 * see the narrow green line of an IBC II aurora (10 kR, 2 mcd/m^2)
 * green and an IBC I one (1 kR) grey, and a player knows the aurora by
 * its green. So the aurora's share of a pixel counts 2000 times
 * brighter: a 10 kR curtain as 4 cd/m^2, the cones', a 1 kR one as 0.4,
 * half the rods'. The light itself is unchanged (HDR output, the
 * lighting). */
float sky_aurora_brighter(vec3 L, vec3 aurora)
{
    float y = dot(L, vec3(0.2126, 0.7152, 0.0722)), a = dot(aurora, vec3(0.2126, 0.7152, 0.0722));
    return 1.0 + 2000.0 * a / max(y, SKY_TINY);
}
