/* froxel_build.frag: Hillaire 2020's aerial-perspective volume (sec. 5.4)
 * for one camera (CORE33): per froxel column one view ray, marched from
 * the observer through SKY_FROXEL_SLICES slices of u_froxel.y km each,
 * the light it gathers (kcd/m^2: per unit sun times the sun's light) and
 * its mean transmittance at each slice's far end. One pass writes eight
 * slices (colour 0 and sky_froxel_1..7), the slices from u_froxel.x on;
 * it marches the slices before them too, without writing them. */
SKY_IN vec2 v_unit;
uniform SKY_UP mat4 u_froxel_clip_to_dir;     /* clip to the horizon frame (a point on the view ray) */
uniform SKY_UP vec4 u_froxel;                 /* first slice of the pass, km per slice, steps per slice */
uniform SKY_UP vec3 u_froxel_sun_irradiance;  /* klx above the atmosphere, per channel */
uniform SKY_UP vec2 u_froxel_weather;         /* a weather's: x the deck's dimming of the air's light
                                                 (1: none), y its haze's extinction, 1/m (aerial.glsl) */
uniform SKY_UP vec3 u_froxel_haze;            /* the haze's light (the horizon's), kcd/m^2 */
layout(location = 1) out vec4 sky_froxel_1;
layout(location = 2) out vec4 sky_froxel_2;
layout(location = 3) out vec4 sky_froxel_3;
layout(location = 4) out vec4 sky_froxel_4;
layout(location = 5) out vec4 sky_froxel_5;
layout(location = 6) out vec4 sky_froxel_6;
layout(location = 7) out vec4 sky_froxel_7;
void main()
{
    float r0 = u_hl_geometry.w;
    /* the column's view: any point of its ray, seen from the observer */
    vec4 p = u_froxel_clip_to_dir * vec4(v_unit * 2.0 - 1.0, 0.5, 1.0);
    vec3 view = normalize(p.xyz / p.w);
    /* a view below the horizon taken as level (aerial.c: the host's
     * ground close by is seen through the air along the level) */
    if (view.y < 0.0) view = length(view.xz) > 1e-6 ? vec3(normalize(view.xz), 0.0).xzy : vec3(1.0, 0.0, 0.0);
    float ct = view.y, cos_theta = dot(view, u_sun_dir), g = u_hl_misc.w;
    float phase_r = hl_phase_rayleigh(cos_theta), phase_m = hl_phase_cs(cos_theta, g);
    float first = u_froxel.x, slice_km = u_froxel.y, steps = u_froxel.z;
    vec3 L = vec3(0.0), transmittance = vec3(1.0);
    vec4 out_slices[8];
    float ta = 0.0, ra = r0;
    vec3 da = hl_density(ra);
    for (int k = 0; k < 32; k++) {
        float kf = float(k);
        if (kf >= first + 8.0) break;
        for (int j = 1; j <= 16; j++) {
            float jf = float(j);
            if (jf > steps) break;
            float tb = (kf + jf / steps) * slice_km, rb = hl_radius(r0, ct, tb);
            vec3 db = hl_density(rb);
            vec3 col = hl_column(da, ra, db, rb, tb - ta);
            float tm = 0.5 * (ta + tb), rm = hl_radius(r0, ct, tm);
            vec3 tau = u_hl_rayleigh * col.x + u_hl_mie_ext * col.y + u_hl_ozone * col.z;
            vec3 e = exp(-tau);
            vec3 weight = transmittance * hl_seg_weight(tau, e);
            float mus = clamp((r0 * u_sun_dir.y + tm * cos_theta) / rm, -1.0, 1.0);
            float vy = clamp((r0 * ct + tm) / rm, -1.0, 1.0);
            L += hl_segment_light(col, weight, rm, mus, vy, cos_theta, phase_r, phase_m);
            transmittance *= e;
            ta = tb;
            ra = rb;
            da = db;
        }
        if (kf >= first) {
            /* a weather over the march, as aerial.glsl's sky_aerial: the
             * deck dims the air's light, the haze hides what lies beyond
             * the slice's far end in the horizon's light */
            float haze = exp(-u_froxel_weather.y * (kf + 1.0) * slice_km * 1000.0);
            vec3 light = L * u_froxel_sun_irradiance * (u_froxel_weather.x * haze) + u_froxel_haze * (1.0 - haze);
            out_slices[k - int(first)] = vec4(light, dot(transmittance, vec3(1.0 / 3.0)) * haze);
        }
    }
    SKY_FRAG_COLOR = out_slices[0];
    sky_froxel_1 = out_slices[1];
    sky_froxel_2 = out_slices[2];
    sky_froxel_3 = out_slices[3];
    sky_froxel_4 = out_slices[4];
    sky_froxel_5 = out_slices[5];
    sky_froxel_6 = out_slices[6];
    sky_froxel_7 = out_slices[7];
}
