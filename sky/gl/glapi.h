/*
 * The slice of OpenGL that libsky uses, loaded through the host's
 * getProcAddress into a per-sky function table (no global state, no system
 * GL header, no loader library of our choosing).
 */
#ifndef SKY_GLAPI_H
#define SKY_GLAPI_H

#include <stddef.h>
#include <stdint.h>

typedef unsigned int GLenum;
typedef unsigned int GLuint;
typedef int GLint;
typedef int GLsizei;
typedef unsigned char GLboolean;
typedef unsigned int GLbitfield;
typedef float GLfloat;
typedef char GLchar;
typedef unsigned char GLubyte;
typedef ptrdiff_t GLsizeiptr;
typedef ptrdiff_t GLintptr;

#if defined(_WIN32) && !defined(__CYGWIN__)
#define SKY_APIENTRY __stdcall
#else
#define SKY_APIENTRY
#endif

/* Enumerants, values from the Khronos registry (gl.xml). */
#define GL_NO_ERROR 0
#define GL_FALSE 0
#define GL_TRUE 1
#define GL_POINTS 0x0000
#define GL_TRIANGLES 0x0004
#define GL_PROGRAM_POINT_SIZE 0x8642
#define GL_ALIASED_POINT_SIZE_RANGE 0x846D
#define GL_TRIANGLE_STRIP 0x0005
#define GL_ZERO 0
#define GL_ONE 1
#define GL_SRC_ALPHA 0x0302
#define GL_ONE_MINUS_SRC_ALPHA 0x0303
#define GL_FUNC_ADD 0x8006
#define GL_BLEND_EQUATION_RGB 0x8009
#define GL_BLEND_EQUATION_ALPHA 0x883D
#define GL_BLEND_DST_RGB 0x80C8
#define GL_BLEND_SRC_RGB 0x80C9
#define GL_BLEND_DST_ALPHA 0x80CA
#define GL_BLEND_SRC_ALPHA 0x80CB
#define GL_CULL_FACE 0x0B44
#define GL_DEPTH_TEST 0x0B71
#define GL_DEPTH_FUNC 0x0B74
#define GL_LEQUAL 0x0203
#define GL_GEQUAL 0x0206
#define GL_DEPTH_WRITEMASK 0x0B72
#define GL_STENCIL_TEST 0x0B90
#define GL_VIEWPORT 0x0BA2
#define GL_BLEND 0x0BE2
#define GL_SCISSOR_TEST 0x0C11
#define GL_COLOR_WRITEMASK 0x0C23
#define GL_UNPACK_ALIGNMENT 0x0CF5
#define GL_PACK_ALIGNMENT 0x0D05
#define GL_MAX_TEXTURE_SIZE 0x0D33
#define GL_TEXTURE_2D 0x0DE1
#define GL_UNSIGNED_BYTE 0x1401
#define GL_SHORT 0x1402
#define GL_FLOAT 0x1406
#define GL_RGBA 0x1908
#define GL_RGB 0x1907
#define GL_VENDOR 0x1F00
#define GL_RENDERER 0x1F01
#define GL_VERSION 0x1F02
#define GL_EXTENSIONS 0x1F03
#define GL_NEAREST 0x2600
#define GL_LINEAR 0x2601
#define GL_LINEAR_MIPMAP_LINEAR 0x2703
#define GL_TEXTURE_MAG_FILTER 0x2800
#define GL_TEXTURE_MIN_FILTER 0x2801
#define GL_TEXTURE_WRAP_S 0x2802
#define GL_TEXTURE_WRAP_T 0x2803
#define GL_REPEAT 0x2901
#define GL_CLAMP_TO_EDGE 0x812F
#define GL_TEXTURE_MAX_LEVEL 0x813D
#define GL_RGBA8 0x8058
#define GL_RGB8 0x8051
#define GL_RGBA32F 0x8814
#define GL_RGB32F 0x8815
#define GL_TEXTURE0 0x84C0
#define GL_ACTIVE_TEXTURE 0x84E0
#define GL_MAX_TEXTURE_IMAGE_UNITS 0x8872
#define GL_TEXTURE_BINDING_2D 0x8069
#define GL_TEXTURE_2D_ARRAY 0x8C1A
#define GL_TEXTURE_BINDING_2D_ARRAY 0x8C1D
#define GL_TEXTURE_3D 0x806F
#define GL_TEXTURE_BINDING_3D 0x806A
#define GL_TEXTURE_WRAP_R 0x8072
#define GL_RGBA16F 0x881A
#define GL_HALF_FLOAT 0x140B
#define GL_TEXTURE_CUBE_MAP 0x8513
#define GL_TEXTURE_BINDING_CUBE_MAP 0x8514
#define GL_TEXTURE_CUBE_MAP_POSITIVE_X 0x8515
#define GL_MAX_CUBE_MAP_TEXTURE_SIZE 0x851C
#define GL_TEXTURE_WIDTH 0x1000
#define GL_ARRAY_BUFFER 0x8892
#define GL_ELEMENT_ARRAY_BUFFER 0x8893
#define GL_ARRAY_BUFFER_BINDING 0x8894
#define GL_ELEMENT_ARRAY_BUFFER_BINDING 0x8895
#define GL_UNSIGNED_SHORT 0x1403
#define GL_SCISSOR_BOX 0x0C10
#define GL_COLOR_CLEAR_VALUE 0x0C22
#define GL_STATIC_DRAW 0x88E4
#define GL_DYNAMIC_DRAW 0x88E8
#define GL_VERTEX_ATTRIB_ARRAY_ENABLED 0x8622
#define GL_VERTEX_ATTRIB_ARRAY_SIZE 0x8623
#define GL_VERTEX_ATTRIB_ARRAY_STRIDE 0x8624
#define GL_VERTEX_ATTRIB_ARRAY_TYPE 0x8625
#define GL_VERTEX_ATTRIB_ARRAY_NORMALIZED 0x886A
#define GL_VERTEX_ATTRIB_ARRAY_POINTER 0x8645
#define GL_VERTEX_ATTRIB_ARRAY_BUFFER_BINDING 0x889F
#define GL_FRAGMENT_SHADER 0x8B30
#define GL_VERTEX_SHADER 0x8B31
#define GL_COMPILE_STATUS 0x8B81
#define GL_LINK_STATUS 0x8B82
#define GL_INFO_LOG_LENGTH 0x8B84
#define GL_CURRENT_PROGRAM 0x8B8D
#define GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS 0x8B4D
#define GL_SHADING_LANGUAGE_VERSION 0x8B8C
#define GL_VERTEX_ARRAY_BINDING 0x85B5
#define GL_FRAMEBUFFER 0x8D40
#define GL_FRAMEBUFFER_BINDING 0x8CA6
#define GL_READ_FRAMEBUFFER 0x8CA8
#define GL_DRAW_FRAMEBUFFER 0x8CA9
#define GL_READ_FRAMEBUFFER_BINDING 0x8CAA
#define GL_RASTERIZER_DISCARD 0x8C89
#define GL_PACK_ROW_LENGTH 0x0D02
#define GL_PACK_SKIP_ROWS 0x0D03
#define GL_PACK_SKIP_PIXELS 0x0D04
#define GL_PIXEL_PACK_BUFFER 0x88EB
#define GL_PIXEL_PACK_BUFFER_BINDING 0x88ED
#define GL_UNPACK_ROW_LENGTH 0x0CF2
#define GL_UNPACK_SKIP_ROWS 0x0CF3
#define GL_UNPACK_SKIP_PIXELS 0x0CF4
#define GL_PIXEL_UNPACK_BUFFER 0x88EC
#define GL_PIXEL_UNPACK_BUFFER_BINDING 0x88EF
#define GL_FRAMEBUFFER_SRGB 0x8DB9
#define GL_POLYGON_MODE 0x0B40
#define GL_FRONT 0x0404
#define GL_BACK 0x0405
#define GL_FRONT_AND_BACK 0x0408
#define GL_FILL 0x1B02
#define GL_COLOR_ATTACHMENT0 0x8CE0
#define GL_COLOR_ATTACHMENT1 0x8CE1
#define GL_FRAMEBUFFER_COMPLETE 0x8CD5
#define GL_NUM_EXTENSIONS 0x821D
#define GL_MAJOR_VERSION 0x821B
#define GL_MINOR_VERSION 0x821C
#define GL_CONTEXT_PROFILE_MASK 0x9126
#define GL_CONTEXT_CORE_PROFILE_BIT 0x00000001
#define GL_COLOR_BUFFER_BIT 0x00004000
#define GL_HIGH_FLOAT 0x8DF2

/* X-macro list: return type, name, parameters. GL 2.0 entry points first;
 * the GL 3.x ones are loaded only for CORE33 (or for the host's FBO use). */
#define SKY_GL_FUNCS_20(X)                                                                    \
    X(GLenum, glGetError, (void))                                                             \
    X(const GLubyte *, glGetString, (GLenum name))                                            \
    X(void, glGetIntegerv, (GLenum pname, GLint *data))                                       \
    X(void, glGetBooleanv, (GLenum pname, GLboolean *data))                                   \
    X(GLboolean, glIsEnabled, (GLenum cap))                                                   \
    X(void, glEnable, (GLenum cap))                                                           \
    X(void, glDisable, (GLenum cap))                                                          \
    X(void, glBlendFunc, (GLenum s, GLenum d))                                                \
    X(void, glBlendFuncSeparate, (GLenum sr, GLenum dr, GLenum sa, GLenum da))                \
    X(void, glBlendEquation, (GLenum mode))                                                   \
    X(void, glBlendEquationSeparate, (GLenum rgb, GLenum alpha))                              \
    X(void, glDepthMask, (GLboolean flag))                                                    \
    X(void, glDepthFunc, (GLenum func))                                                       \
    X(void, glColorMask, (GLboolean r, GLboolean g, GLboolean b, GLboolean a))                \
    X(void, glViewport, (GLint x, GLint y, GLsizei w, GLsizei h))                             \
    X(void, glClearColor, (GLfloat r, GLfloat g, GLfloat b, GLfloat a))                       \
    X(void, glClear, (GLbitfield mask))                                                       \
    X(void, glFinish, (void))                                                                 \
    X(void, glPixelStorei, (GLenum pname, GLint param))                                       \
    X(void, glReadPixels, (GLint x, GLint y, GLsizei w, GLsizei h, GLenum f, GLenum t, void *p)) \
    X(void, glGenTextures, (GLsizei n, GLuint *t))                                            \
    X(void, glDeleteTextures, (GLsizei n, const GLuint *t))                                   \
    X(void, glBindTexture, (GLenum target, GLuint t))                                         \
    X(void, glActiveTexture, (GLenum unit))                                                   \
    X(void, glTexParameteri, (GLenum target, GLenum pname, GLint param))                      \
    X(void, glTexImage2D, (GLenum target, GLint level, GLint ifmt, GLsizei w, GLsizei h,      \
                           GLint border, GLenum fmt, GLenum type, const void *pixels))        \
    X(void, glCopyTexSubImage2D, (GLenum target, GLint level, GLint xoff, GLint yoff, GLint x, GLint y,       \
                                  GLsizei w, GLsizei h))                                        \
    X(void, glTexSubImage2D, (GLenum target, GLint level, GLint x, GLint y, GLsizei w,        \
                              GLsizei h, GLenum fmt, GLenum type, const void *pixels))        \
    X(void, glGenBuffers, (GLsizei n, GLuint *b))                                             \
    X(void, glDeleteBuffers, (GLsizei n, const GLuint *b))                                    \
    X(void, glBindBuffer, (GLenum target, GLuint b))                                          \
    X(void, glBufferData, (GLenum target, GLsizeiptr size, const void *data, GLenum usage))   \
    X(void, glVertexAttribPointer, (GLuint i, GLint size, GLenum type, GLboolean norm,        \
                                    GLsizei stride, const void *ptr))                        \
    X(void, glEnableVertexAttribArray, (GLuint i))                                            \
    X(void, glDisableVertexAttribArray, (GLuint i))                                           \
    X(void, glGetVertexAttribiv, (GLuint i, GLenum pname, GLint *v))                          \
    X(void, glGetVertexAttribPointerv, (GLuint i, GLenum pname, void **p))                    \
    X(void, glDrawArrays, (GLenum mode, GLint first, GLsizei count))                          \
    X(void, glDrawElements, (GLenum mode, GLsizei count, GLenum type, const void *indices))   \
    X(void, glScissor, (GLint x, GLint y, GLsizei w, GLsizei h))                              \
    X(void, glGetFloatv, (GLenum pname, GLfloat *data))                                       \
    X(GLuint, glCreateShader, (GLenum type))                                                  \
    X(void, glShaderSource, (GLuint sh, GLsizei n, const GLchar *const *src, const GLint *len)) \
    X(void, glCompileShader, (GLuint sh))                                                     \
    X(void, glGetShaderiv, (GLuint sh, GLenum pname, GLint *v))                               \
    X(void, glGetShaderInfoLog, (GLuint sh, GLsizei max, GLsizei *len, GLchar *log))          \
    X(void, glDeleteShader, (GLuint sh))                                                      \
    X(GLuint, glCreateProgram, (void))                                                        \
    X(void, glAttachShader, (GLuint p, GLuint sh))                                            \
    X(void, glBindAttribLocation, (GLuint p, GLuint i, const GLchar *name))                   \
    X(void, glLinkProgram, (GLuint p))                                                        \
    X(void, glGetProgramiv, (GLuint p, GLenum pname, GLint *v))                               \
    X(void, glGetProgramInfoLog, (GLuint p, GLsizei max, GLsizei *len, GLchar *log))          \
    X(void, glDeleteProgram, (GLuint p))                                                      \
    X(void, glUseProgram, (GLuint p))                                                         \
    X(GLboolean, glIsProgram, (GLuint p))                                                     \
    X(GLint, glGetUniformLocation, (GLuint p, const GLchar *name))                            \
    X(void, glUniform1i, (GLint loc, GLint v))                                                \
    X(void, glUniform1f, (GLint loc, GLfloat v))                                              \
    X(void, glUniform2f, (GLint loc, GLfloat a, GLfloat b))                                   \
    X(void, glUniform3f, (GLint loc, GLfloat a, GLfloat b, GLfloat c))                        \
    X(void, glUniform4f, (GLint loc, GLfloat a, GLfloat b, GLfloat c, GLfloat d))             \
    X(void, glUniform1fv, (GLint loc, GLsizei n, const GLfloat *v))                           \
    X(void, glUniform3fv, (GLint loc, GLsizei n, const GLfloat *v))                           \
    X(void, glUniformMatrix4fv, (GLint loc, GLsizei n, GLboolean tr, const GLfloat *v))

/* Desktop GL's, absent from OpenGL ES 2.0: required on desktop contexts,
 * never called on ES ones. */
#define SKY_GL_FUNCS_DESKTOP(X)                                                               \
    X(void, glPolygonMode, (GLenum face, GLenum mode))                                        \
    X(void, glGetTexLevelParameteriv, (GLenum target, GLint level, GLenum pname, GLint *v))

#define SKY_GL_FUNCS_30(X)                                                                    \
    X(const GLubyte *, glGetStringi, (GLenum name, GLuint i))                                 \
    X(void, glGenVertexArrays, (GLsizei n, GLuint *a))                                        \
    X(void, glDeleteVertexArrays, (GLsizei n, const GLuint *a))                               \
    X(void, glBindVertexArray, (GLuint a))                                                    \
    X(void, glGenFramebuffers, (GLsizei n, GLuint *f))                                        \
    X(void, glDeleteFramebuffers, (GLsizei n, const GLuint *f))                               \
    X(void, glBindFramebuffer, (GLenum target, GLuint f))                                     \
    X(void, glFramebufferTexture2D, (GLenum target, GLenum att, GLenum textarget, GLuint t,   \
                                     GLint level))                                            \
    X(GLenum, glCheckFramebufferStatus, (GLenum target))                                     \
    X(void, glFramebufferTextureLayer, (GLenum target, GLenum att, GLuint t, GLint level,     \
                                        GLint layer))                                         \
    X(void, glDrawBuffers, (GLsizei n, const GLenum *bufs))                                   \
    X(void, glBindFragDataLocation, (GLuint p, GLuint color, const GLchar *name))             \
    X(void, glTexImage3D, (GLenum target, GLint level, GLint ifmt, GLsizei w, GLsizei h,      \
                           GLsizei d, GLint border, GLenum fmt, GLenum type, const void *data))   \
    X(void, glGetShaderPrecisionFormat, (GLenum stage, GLenum precision, GLint *range, GLint *bits))

typedef struct sky_gl {
#define SKY_GL_MEMBER(ret, name, params) ret(SKY_APIENTRY *name) params;
    SKY_GL_FUNCS_20(SKY_GL_MEMBER)
    SKY_GL_FUNCS_DESKTOP(SKY_GL_MEMBER)
    SKY_GL_FUNCS_30(SKY_GL_MEMBER)
#undef SKY_GL_MEMBER
} sky_gl;

/* What a context offers beyond OpenGL 2.0 that the sky uses (gl/load.c). */
typedef struct sky_gl_caps {
    int render_to_rgba8;       /* framebuffer objects (3.0, ARB or EXT)     */
    int separate_framebuffers; /* draw and read bindings apart (3.0, ARB, EXT_blit) */
    int npot;                  /* non-power-of-two textures (3.0 or ARB)   */
    int pixel_buffers;         /* PIXEL_UNPACK_BUFFER exists (2.1 or ARB)  */
    int framebuffer_srgb;      /* GL_FRAMEBUFFER_SRGB exists (3.0 or ARB/EXT) */
    int es;                    /* an OpenGL ES context (the ES20 profile):
                                  no polygon mode, no program-point-size
                                  switch (always on), unsized texture
                                  formats below ES 3.0                      */
    int unpack_rows;           /* UNPACK_ROW_LENGTH and the skips (desktop, ES 3.0) */
    int rasterizer_discard;    /* GL_RASTERIZER_DISCARD (3.0, ES 3.0)       */
    int derivatives;           /* fwidth in fragment shaders (desktop; ES
                                  through OES_standard_derivatives)         */
    int fragment_highp;        /* highp floats in the fragment stage (desktop
                                  always; ES where glGetShaderPrecisionFormat
                                  says so): without them the shaders run at
                                  mediump, within 2^14                      */
    int vertex_arrays;         /* a VAO of the sky's own (CORE33; ES 3.0 or
                                  OES_vertex_array_object): the host's
                                  attribute state is then one binding to
                                  save, not 21 queries (in a browser each
                                  one costs)                               */
} sky_gl_caps;

#endif /* SKY_GLAPI_H */
