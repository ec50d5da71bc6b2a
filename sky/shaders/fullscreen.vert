/* fullscreen.vert: one triangle over the whole viewport from gl_VertexID
 * (CORE33 only: the table builds draw it with no vertex attributes). */
SKY_OUT vec2 v_unit;
void main()
{
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    v_unit = p;
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
