/* stars.vert: catalogue stars as points (Mueller sec. 4), one vertex a
 * star. J2000 directions (proper motion applied on the CPU) turn into the
 * horizon frame through one rotation and the annual aberration vector per
 * frame (Mueller eq. 7-8 with an accurate precession); refraction lifts
 * each star by its own amount. Points are sized in the vertex shader
 * (eq. 9) and shaped in the fragment shader from gl_FragCoord, which GLSL
 * 1.10 has everywhere (gl_PointCoord it does not). */
uniform mat4 u_star_rot;          /* J2000 -> horizon (precession, nutation, sidereal) */
uniform vec3 u_star_aberration;   /* annual aberration, horizon frame          */
uniform vec4 u_star_size;         /* q (px), glare coefficient c_k (px), max radius (px), m_a */
uniform vec4 u_star_viewport;     /* x, y, width, height                       */
uniform vec3 u_star_pressure;     /* refraction pressure factor, -, -          */
uniform vec4 u_star_occulter;     /* moon's true direction, cos of its drawn radius */
SKY_ATTR vec2 a_pos;              /* x: star index (scintillation seed)         */
SKY_ATTR vec3 a_dir;
SKY_ATTR vec4 a_color;            /* rgb: colour of unit luminance, a: V mag    */
SKY_OUT vec3 v_dir;
SKY_OUT vec4 v_color;
SKY_OUT vec2 v_center;            /* window position of the star, px            */
SKY_OUT vec2 v_size;              /* x: billboard radius k (px), y: k / q        */
SKY_OUT float v_index;

/* Saemundsson refraction (astro.c), radians, for true altitude h. */
float sky_star_refraction(float h)
{
    float hd = max(degrees(h), -1.0);
    float r = 1.02 / tan(radians(hd + 10.3 / (hd + 5.11))) + 0.0019279;
    return radians(r / 60.0) * u_star_pressure.x;
}

void main()
{
    vec3 d = normalize((u_star_rot * vec4(a_dir, 0.0)).xyz + u_star_aberration);
    bool occulted = dot(d, u_star_occulter.xyz) > u_star_occulter.w; /* behind the moon */
    float h = asin(clamp(d.y, -1.0, 1.0));
    float ha = h + sky_star_refraction(h);
    vec2 horiz = d.xz / max(length(d.xz), 1e-6);
    d = vec3(horiz.x * cos(ha), sin(ha), horiz.y * cos(ha));
    v_dir = d;
    v_color = a_color;
    v_index = a_pos.x;
    /* eq. 9 and the glare radius k = max(q, c_k sqrt(I_G)) with
     * I_G = 2.512^(m_a - m - (V_T - 1)) - 1 for stars brighter than m_a */
    float q = u_star_size.x;
    float ig = max(pow(2.512, u_star_size.w - a_color.a - 0.167) - 1.0, 0.0);
    float k = min(max(q, u_star_size.y * sqrt(ig)), u_star_size.z);
    v_size = vec2(k, k / q);
    vec4 clip;
    if (u_fisheye > 0.5)
        clip = vec4(sky_fisheye_ndc(d) / u_aspect, 0.0, 1.0);
    else
        clip = (u_view_proj * vec4(d, 0.0)).xyww;
    /* below the horizon, behind the camera or the moon: outside the clip
     * volume */
    if (d.y < 0.0 || clip.w <= 0.0 || occulted) clip = vec4(2.0, 2.0, 2.0, 1.0);
    gl_Position = clip;
    gl_PointSize = 2.0 * k + 1.0;
    v_center = (clip.xy / clip.w * 0.5 + 0.5) * u_star_viewport.zw + u_star_viewport.xy;
}
