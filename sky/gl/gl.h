/*
 * The GL room: every rule about GL state lives here (docs/ARCHITECTURE.md,
 * "GL state"). Function loading and profile choice, programs built from
 * snippets with their uniform tables, textures and buffers with their byte
 * counts, the host's state saved and restored around sky_draw, render
 * targets for the lookup tables, and the few per-draw state changes the
 * layers ask for by name (blend modes). Layers never call raw GL for
 * state; they bind their own buffers and draw.
 */
#ifndef SKY_GL_H
#define SKY_GL_H

#include "../core.h"

/* ---- programs and the uniform table ------------------------------------- */
typedef enum sky_uniform_type {
    SKY_U_F1, SKY_U_F2, SKY_U_F3, SKY_U_F4, SKY_U_M4, SKY_U_TEX,
    SKY_U_F1V /* a float array: its element count in the row's count */
} sky_uniform_type;

/* One row per uniform: the GLSL name, its type, and where its value lives:
 * an offset into sky_frame, or into the state of the layer that owns the
 * snippet (in_state: a layer keeps its uniforms' values in its own state,
 * bound to its snippets with sky_snippet_bind), or a texture id (for
 * SKY_U_TEX: the id itself, or with in_state the offset of an int holding
 * one, for a texture registered at run time). Each room owns its rows; a
 * program built from several snippets sets the rows of each. */
typedef struct sky_uniform_desc {
    const char *name;
    sky_uniform_type type;
    size_t offset;           /* into sky_frame or the state; texture id      */
    int count;               /* SKY_U_F1V: elements                          */
    unsigned light;          /* components (bit i: component i) that are light
                                in kcd/m^2, sent times sky_frame.light_scale */
    int in_state;            /* offset is into the snippet's bound state      */
} sky_uniform_desc;
#define SKY_UF(name, type, field) { name, type, offsetof(sky_frame, field), 1, 0, 0 }
/* a row whose components in mask (SKY_RGB, or 1 << i) are light */
#define SKY_UL(name, type, field, mask) { name, type, offsetof(sky_frame, field), 1, mask, 0 }
#define SKY_RGB 7u
#define SKY_UT(name, tex) { name, SKY_U_TEX, (size_t)(tex), 1, 0, 0 }
/* rows whose values live in a layer's state (of type state_type) */
#define SKY_US(name, type, state_type, field) { name, type, offsetof(state_type, field), 1, 0, 1 }
#define SKY_USL(name, type, state_type, field, mask) { name, type, offsetof(state_type, field), 1, mask, 1 }
#define SKY_UTS(name, state_type, field) { name, SKY_U_TEX, offsetof(state_type, field), 1, 0, 1 }
#define SKY_UFV(name, field) \
    { name, SKY_U_F1V, offsetof(sky_frame, field), (int)(sizeof(((sky_frame *)0)->field) / sizeof(float)), 0, 0 }
#define SKY_UNIFORM_COUNT(rows) ((int)(sizeof rows / sizeof rows[0]))

/* A snippet: the GLSL functions of one phenomenon plus its uniform rows.
 * Its source goes into the fragment stage; a vertex_source (often the same
 * file: code it needs there is pure arithmetic, and what only a fragment
 * stage can do sits under #ifdef SKY_FRAGMENT) into the vertex stage too,
 * for what a program evaluates per vertex. */
typedef struct sky_snippet {
    const char *define;      /* e.g. "SKY_HAS_CLOUDS"                          */
    const char *source;      /* embedded GLSL file name; NULL = uniform rows only */
    const sky_uniform_desc *uniforms;
    int uniform_count;
    const char *vertex_source; /* NULL: fragment stage only                    */
    /* A night glow's GLSL function, vec3 NAME(vec3 d): its light above the
     * air from horizon direction d. A program with such snippets gets
     * sky_night_glows(d), their sum in the snippets' order, and the define
     * SKY_HAS_NIGHT_GLOWS (dome.frag dims the sum by the air): a new glow
     * touches no other shader. NULL: not one. */
    const char *glow_function;
    /* A front light's GLSL function, vec3 NAME(vec3 d): light an optical
     * phenomenon adds in front of the sky and the clouds from horizon
     * direction d (a rainbow in the rain, a halo in the ice), kcd/m^2. A
     * program with such snippets gets sky_front_lights(d), their sum, and
     * the define SKY_HAS_FRONT_LIGHTS (dome.frag adds it over the clouds
     * and the haze). NULL: not one. */
    const char *front_function;
} sky_snippet;

/* A program and its uniform rows (as many as its snippets bring: no cap),
 * each with its location and the state its values are read from (NULL:
 * sky_frame). */
typedef struct sky_program {
    GLuint id;
    int uniform_count;
    const sky_uniform_desc **uniforms;
    const void **states;
    GLint *locations;
} sky_program;
/* A snippet's rows marked in_state read from state in every program built
 * with the snippet after this call (a layer binds its snippets in its
 * create, before building). -1 when out of memory. */
int sky_snippet_bind(sky_core *s, const sky_snippet *snippet, const void *state);

/* The common prologue's uniforms (exposure, camera, sun): every program. */
extern const sky_snippet sky_common_snippet;

/* gl/win32.c: on Windows, name's entry point in opengl32.dll (NULL when
 * it has none); elsewhere NULL. */
sky_gl_proc sky_gl_system_proc(const char *name);
/* Loads the function table and picks the profile. Returns 0 or writes err. */
int sky_gl_init(sky_core *s, char *err, size_t err_len);
/* Compiles and links a program from the common prologue, the given snippets
 * and a vertex and fragment main file. Attributes: 0 a_pos, 1 a_dir,
 * 2 a_color. */
int sky_program_build(sky_core *s, sky_program *p, const char *vert_main, const char *frag_main,
                      const sky_snippet *const *snippets, int snippet_count, char *err, size_t err_len);
void sky_program_destroy(sky_core *s, sky_program *p);
/* Sets every uniform of the program from s->frame and binds its textures. */
void sky_program_apply(sky_core *s, const sky_program *p);

/* A value for a uniform of the host's own program, set by name: n floats
 * (1 to 4), or with n 0 the sampler's texture unit in unit. */
typedef struct sky_gl_host_uniform {
    const char *name;
    int n;
    float v[4];
    int unit;
} sky_gl_host_uniform;
/* Sets count such uniforms in the host's program; with texture non-zero
 * it binds it (2D) on texture_unit first. The host's current program and
 * active unit come back; the texture stays bound on its unit. */
void sky_gl_host_uniforms(sky_core *s, GLuint program, const sky_gl_host_uniform *u, int count, int texture_unit,
                          GLuint texture);
/* The number of texture units a program's stages may use together. */
int sky_gl_texture_units(sky_core *s);

/* ---- textures and buffers ------------------------------------------------ */
/* Uploads an 8-bit image of 3 (RGB) or 4 (RGBA) channels. repeat: wrap
 * mode. Power-of-two sizes only. */
int sky_texture_create(sky_core *s, sky_texture_id id, sky_layer owner, const unsigned char *pixels, int channels,
                       int w, int h, int repeat, char *err, size_t err_len);
/* An RGBA8 image to render into (sky_gl_target_begin) and sample: linear,
 * clamped, no mipmaps, so any size where the context has NPOT textures
 * (the subset GL 2.0 and ES 2.0 hardware filter), powers of two elsewhere. */
int sky_texture_create_image(sky_core *s, sky_texture_id id, sky_layer owner, int w, int h, char *err,
                             size_t err_len);
/* Loads a texture by file name: the override directory first, then the
 * embedded copy. Checks size and channel count against what is expected. */
int sky_texture_load(sky_core *s, sky_texture_id id, sky_layer owner, const char *name, int expect_w, int expect_h,
                     int repeat, char *err, size_t err_len);
/* A power-of-two lookup texture without contents: RGBA32F with linear
 * filtering (is_float) or RGBA8 for an encoding, unfiltered;
 * sky_texture_update_lut fills its w x h corner (one of the two data
 * pointers). */
int sky_texture_create_lut(sky_core *s, sky_texture_id id, sky_layer owner, int w, int h, int is_float, char *err,
                           size_t err_len);
/* An RGBA32F 2D array of layers w x h (CORE33), linear, clamped; rgba:
 * its contents, layer after layer, or NULL for none (to render into). */
int sky_texture_create_lut_layers(sky_core *s, sky_texture_id id, sky_layer owner, int w, int h, int layers,
                                  const float *rgba, char *err, size_t err_len);
void sky_texture_update_lut(sky_core *s, sky_texture_id id, int w, int h, const unsigned char *rgba8,
                            const float *rgb32f);
/* A w x h x d RGBA16F volume to render into slice by slice and sample
 * (CORE33): linear, clamped. */
int sky_texture_create_volume(sky_core *s, sky_texture_id id, sky_layer owner, int w, int h, int d, char *err,
                              size_t err_len);
/* A cube map of six size x size faces, in GL's order (+x, -x, +y, -y,
 * +z, -z), each face's rows following GL's convention; linear, clamped at
 * the edges. RGBA8 from faces, or empty (faces NULL) to render into:
 * RGBA8, or RGBA32F when is_float (the sun's disc is far beyond a half
 * float's 65504 kcd/m^2). */
int sky_texture_create_cube(sky_core *s, sky_texture_id id, sky_layer owner, const unsigned char *faces, int size,
                            int is_float, char *err, size_t err_len);
/* A texture id beyond sky_texture_id's, for a layer's own texture (kept
 * in its state, read by SKY_UTS rows): made at create, freed with the sky.
 * -1 when out of memory. */
int sky_texture_register(sky_core *s);
/* A new size for such an image; on failure the old one stays. */
int sky_texture_resize_image(sky_core *s, sky_texture_id id, int w, int h);
void sky_texture_destroy(sky_core *s, sky_texture_id id);
/* Reads an asset (override directory first, then the embedded copy) and
 * decodes it to RGBA8, checking its size. Free with sky_png_free. */
int sky_asset_load_rgba(sky_core *s, const char *name, int expect_w, int expect_h, unsigned char **rgba, char *err,
                        size_t err_len);
GLuint sky_buffer_create(sky_core *s, GLenum target, const void *data, size_t bytes, GLenum usage);
/* Replaces a buffer's contents (same target and usage as created). */
void sky_buffer_update(sky_core *s, GLenum target, GLuint buffer, const void *data, size_t bytes, GLenum usage);
/* Deletes buffers and takes them off the counts (0 names are skipped). */
void sky_buffers_destroy(sky_core *s, const GLuint *buffers, const size_t *bytes, int count);

/* ---- the host's state ----------------------------------------------------- */
/* Host GL state that sky_draw changes, saved and restored around it. */
#define SKY_ATTRIBS 3 /* a_pos, a_dir, a_color */
typedef struct sky_gl_state {
    GLint program, active_texture, array_buffer, element_buffer, vao, viewport[4];
    GLint textures[4], cube_textures[4]; /* units 0..3: 2D and cube map bindings */
    GLint array_textures[4];             /* and 2D-array ones (CORE33)          */
    GLboolean blend, depth_test, cull_face, scissor_test, stencil_test, color_mask[4];
    GLboolean depth_mask; /* with depth_func: saved only with cfg.depth set */
    GLint blend_src_rgb, blend_dst_rgb, blend_src_alpha, blend_dst_alpha, blend_eq_rgb, blend_eq_alpha, depth_func;
    GLboolean program_point_size, framebuffer_srgb;
    GLint polygon_mode[2];                /* front, back                        */
    GLint attrib_enabled[SKY_ATTRIBS], attrib_size[SKY_ATTRIBS], attrib_type[SKY_ATTRIBS], attrib_norm[SKY_ATTRIBS],
        attrib_stride[SKY_ATTRIBS], attrib_buffer[SKY_ATTRIBS];
    void *attrib_pointer[SKY_ATTRIBS];
} sky_gl_state;
void sky_gl_state_save(sky_core *s, sky_gl_state *st);
void sky_gl_state_restore(sky_core *s, const sky_gl_state *st);

/* ---- what a frame sets ------------------------------------------------------ */
/* The sky's vertex array where the context has them (caps.vertex_arrays:
 * CORE33, ES 3.0 or OES_vertex_array_object; created bound), its binding,
 * its release. */
GLuint sky_gl_vertex_array_create(sky_core *s);
void sky_gl_vertex_array_bind(sky_core *s, GLuint vao);
void sky_gl_vertex_array_destroy(sky_core *s, GLuint vao);
/* The sky's own state for drawing: no depth write (no depth test; or,
 * when it is drawn after the scene, cfg.depth's test, LEQUAL against a far
 * plane at 1 or GEQUAL at 0, with the depth mask off), no culling or
 * stencil, all colour channels, no blending, filled polygons, no sRGB
 * conversion by the framebuffer (LDR output is sRGB-encoded by the sky
 * itself, HDR output is linear), its vertex array (vao: 0 where the
 * context has none). */
void sky_gl_frame_begin(sky_core *s, GLuint vao);
/* How a layer's fragments combine with what is under them. */
typedef enum sky_blend {
    SKY_BLEND_NONE,          /* replace: the dome                            */
    SKY_BLEND_ADD,           /* light added: stars, sun                      */
    SKY_BLEND_PREMULTIPLIED  /* added, hiding what is behind by its alpha: moon */
} sky_blend;
void sky_gl_blend(sky_core *s, sky_blend mode);
/* An interleaved vertex buffer's layout on attributes 0..2: per
 * attribute its component count (0: off for this draw), type, whether
 * integers are normalised to 0..1 or -1..1, and byte offset. */
typedef struct sky_gl_attribute {
    int size;
    GLenum type;
    GLboolean normalized;
    size_t offset;
} sky_gl_attribute;
typedef struct sky_gl_layout {
    GLsizei stride;
    sky_gl_attribute attribute[3];
} sky_gl_layout;
/* Binds buffer as the array buffer with its layout, and elements as the
 * element buffer (0: that binding is left as it is). */
void sky_gl_vertices_bind(sky_core *s, GLuint buffer, GLuint elements, const sky_gl_layout *layout);
/* Draws count vertices from first of the bound arrays, or count 16-bit
 * indices from index first of the bound elements. */
void sky_gl_draw_arrays(sky_core *s, GLenum mode, int first, int count);
void sky_gl_draw_elements(sky_core *s, GLenum mode, int first, int count);
/* Points sized by the vertex shader (gl_PointSize): on around a point
 * draw, off after it. */
void sky_gl_program_point_size(sky_core *s, int on);
/* The largest point size the context draws (at least 1). */
float sky_gl_point_size_max(sky_core *s);
/* Clears the viewport's rectangle to black (the all-sky image's margin),
 * the host's scissor box and clear colour put back after it. */
void sky_gl_clear_viewport(sky_core *s, const GLint viewport[4]);
/* Waits for the GPU: per-layer timings, only when the host asked for them. */
void sky_gl_finish(sky_core *s);
/* Reads the pending GL errors until none is left, within a bound (a lost
 * context may never answer GL_NO_ERROR): GL_NO_ERROR, or the error still
 * reported after it (load.c). */
GLenum sky_gl_drain_errors(const sky_gl *gl);
/* The first GL error since the last call, GL_NO_ERROR if none. */
GLenum sky_gl_error(sky_core *s);
/* Whether a context is current (GL_VERSION answers), and whether program
 * is one in it: a foreign context, sharing nothing, has no such name.
 * Neither calls glGetError. */
int sky_gl_context_current(sky_core *s);
int sky_gl_is_program(sky_core *s, GLuint program);

/* ---- render targets (the lookup tables) ------------------------------------ */
/* Rendering into a texture: the framebuffer bindings (draw and read),
 * viewport, scissor, depth-test and rasterizer-discard state before it,
 * put back by sky_gl_target_end. Blending, depth, stencil, culling and the colour mask
 * are set here too; sky_draw and sky_create restore those with the rest
 * of the host's state. */
typedef struct sky_gl_target {
    GLint draw, read, viewport[4];
    GLboolean scissor, discard, depth_test;
} sky_gl_target;
/* The framebuffer the tables are rendered through, checked against one
 * of them (probe); 0 with a message when the context cannot render into
 * it. */
GLuint sky_gl_target_create(sky_core *s, sky_texture_id probe, char *err, size_t err_len);
void sky_gl_target_destroy(sky_core *s, GLuint fbo); /* 0: nothing */
void sky_gl_target_begin(sky_core *s, GLuint fbo, sky_texture_id target, int w, int h, sky_gl_target *t);
void sky_gl_target_end(sky_core *s, const sky_gl_target *t);
/* The host's framebuffer bindings (draw and read), and putting them back. */
void sky_gl_framebuffers_get(sky_core *s, GLint *draw, GLint *read);
void sky_gl_framebuffers_set(sky_core *s, GLint draw, GLint read);
/* A framebuffer object of its own (0 when the context makes none). */
GLuint sky_gl_framebuffer_create(sky_core *s);
/* Binds fbo with face (0..5, GL's order) of cube map texture as its
 * colour (texture 0: detaches it); the framebuffer's status. */
GLenum sky_gl_target_cube_face(sky_core *s, GLuint fbo, GLuint texture, int face);
/* The largest cube map face; the width of a cube map's +X level 0 (bound
 * on unit 0 to ask: the caller restores the host's state); copying the
 * draw buffer's size x size square at x, y into a face. */
int sky_gl_cube_size_max(sky_core *s);
int sky_gl_cube_width(sky_core *s, GLuint texture);
void sky_gl_cube_copy_face(sky_core *s, GLuint texture, int face, int x, int y, int size);
/* The viewport: read, and set. */
void sky_gl_viewport_get(sky_core *s, GLint viewport[4]);
void sky_gl_viewport_set(sky_core *s, int x, int y, int w, int h);
/* Unit 0's 3D texture binding (the froxel volume's), and setting it. */
GLuint sky_gl_volume_binding(sky_core *s);
void sky_gl_volume_bind(sky_core *s, GLuint texture);
/* Reads the w x h corner of a float texture back as RGB floats, with the
 * host's pixel-pack state set aside. Returns 0, or -1 on a GL error or
 * no memory. */
int sky_gl_read_rgb(sky_core *s, GLuint fbo, sky_texture_id source, int w, int h, float *rgb);
/* The same as RGBA, of a 2D texture (layer -1) or one layer of an array. */
int sky_gl_read_rgba(sky_core *s, GLuint fbo, sky_texture_id source, int layer, int w, int h, float *rgba);
/* A target that renders into slices first .. first + n - 1 of a volume
 * or layers of an array (colours 0 .. n - 1, n <= 8), CORE33; end
 * detaches them. */
void sky_gl_target_begin_slices(sky_core *s, GLuint fbo, sky_texture_id volume, int first, int n, int w, int h,
                                sky_gl_target *t);
void sky_gl_target_end_slices(sky_core *s, int n, const sky_gl_target *t);

#endif /* SKY_GL_H */
