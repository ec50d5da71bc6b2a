/*
 * The OpenGL 2.0-3.0 functions the tests call by name (test_api.c's host
 * programs, test_main.c's fixtures), which Linux's libOSMesa exports and
 * Windows' opengl32.dll does not (it stops at OpenGL 1.1): each defined
 * here, for the Windows runner only, as a call through wglGetProcAddress
 * in the current context. The library never needs this; it asks the
 * host's loader for everything.
 */
#define GL_GLEXT_PROTOTYPES 1
#include <windows.h>

#include <GL/gl.h>
#include <GL/glext.h>

/* A test calls a function only where its context has it. (void (*)(void)
 * is the type any function pointer converts to and from without a
 * warning.) */
typedef void (*gl_entry_point)(void);
static gl_entry_point entry(const char *name) { return (gl_entry_point)wglGetProcAddress(name); }

void APIENTRY glActiveTexture(GLenum texture)
{
    ((PFNGLACTIVETEXTUREPROC)entry("glActiveTexture"))(texture);
}

void APIENTRY glAttachShader(GLuint program, GLuint shader)
{
    ((PFNGLATTACHSHADERPROC)entry("glAttachShader"))(program, shader);
}

void APIENTRY glBindAttribLocation(GLuint program, GLuint index, const GLchar *name)
{
    ((PFNGLBINDATTRIBLOCATIONPROC)entry("glBindAttribLocation"))(program, index, name);
}

void APIENTRY glBindBuffer(GLenum target, GLuint buffer)
{
    ((PFNGLBINDBUFFERPROC)entry("glBindBuffer"))(target, buffer);
}

void APIENTRY glBindFramebuffer(GLenum target, GLuint framebuffer)
{
    ((PFNGLBINDFRAMEBUFFERPROC)entry("glBindFramebuffer"))(target, framebuffer);
}

void APIENTRY glBindVertexArray(GLuint array)
{
    ((PFNGLBINDVERTEXARRAYPROC)entry("glBindVertexArray"))(array);
}

void APIENTRY glBlendEquation(GLenum mode)
{
    ((PFNGLBLENDEQUATIONPROC)entry("glBlendEquation"))(mode);
}

void APIENTRY glBlendFuncSeparate(GLenum sfactorRGB, GLenum dfactorRGB, GLenum sfactorAlpha, GLenum dfactorAlpha)
{
    ((PFNGLBLENDFUNCSEPARATEPROC)entry("glBlendFuncSeparate"))(sfactorRGB, dfactorRGB, sfactorAlpha, dfactorAlpha);
}

void APIENTRY glBufferData(GLenum target, GLsizeiptr size, const void *data, GLenum usage)
{
    ((PFNGLBUFFERDATAPROC)entry("glBufferData"))(target, size, data, usage);
}

void APIENTRY glCompileShader(GLuint shader)
{
    ((PFNGLCOMPILESHADERPROC)entry("glCompileShader"))(shader);
}

GLuint APIENTRY glCreateProgram(void)
{
    return ((PFNGLCREATEPROGRAMPROC)entry("glCreateProgram"))();
}

GLuint APIENTRY glCreateShader(GLenum type)
{
    return ((PFNGLCREATESHADERPROC)entry("glCreateShader"))(type);
}

void APIENTRY glDeleteBuffers(GLsizei n, const GLuint *buffers)
{
    ((PFNGLDELETEBUFFERSPROC)entry("glDeleteBuffers"))(n, buffers);
}

void APIENTRY glDeleteFramebuffers(GLsizei n, const GLuint *framebuffers)
{
    ((PFNGLDELETEFRAMEBUFFERSPROC)entry("glDeleteFramebuffers"))(n, framebuffers);
}

void APIENTRY glDeleteProgram(GLuint program)
{
    ((PFNGLDELETEPROGRAMPROC)entry("glDeleteProgram"))(program);
}

void APIENTRY glDeleteShader(GLuint shader)
{
    ((PFNGLDELETESHADERPROC)entry("glDeleteShader"))(shader);
}

void APIENTRY glDeleteVertexArrays(GLsizei n, const GLuint *arrays)
{
    ((PFNGLDELETEVERTEXARRAYSPROC)entry("glDeleteVertexArrays"))(n, arrays);
}

void APIENTRY glEnableVertexAttribArray(GLuint index)
{
    ((PFNGLENABLEVERTEXATTRIBARRAYPROC)entry("glEnableVertexAttribArray"))(index);
}

void APIENTRY glFramebufferTexture2D(GLenum target, GLenum attachment, GLenum textarget, GLuint texture, GLint level)
{
    ((PFNGLFRAMEBUFFERTEXTURE2DPROC)entry("glFramebufferTexture2D"))(target, attachment, textarget, texture, level);
}

void APIENTRY glGenBuffers(GLsizei n, GLuint *buffers)
{
    ((PFNGLGENBUFFERSPROC)entry("glGenBuffers"))(n, buffers);
}

void APIENTRY glGenFramebuffers(GLsizei n, GLuint *framebuffers)
{
    ((PFNGLGENFRAMEBUFFERSPROC)entry("glGenFramebuffers"))(n, framebuffers);
}

void APIENTRY glGenVertexArrays(GLsizei n, GLuint *arrays)
{
    ((PFNGLGENVERTEXARRAYSPROC)entry("glGenVertexArrays"))(n, arrays);
}

void APIENTRY glGetShaderInfoLog(GLuint shader, GLsizei bufSize, GLsizei *length, GLchar *infoLog)
{
    ((PFNGLGETSHADERINFOLOGPROC)entry("glGetShaderInfoLog"))(shader, bufSize, length, infoLog);
}

void APIENTRY glGetShaderiv(GLuint shader, GLenum pname, GLint *params)
{
    ((PFNGLGETSHADERIVPROC)entry("glGetShaderiv"))(shader, pname, params);
}

void APIENTRY glGetVertexAttribiv(GLuint index, GLenum pname, GLint *params)
{
    ((PFNGLGETVERTEXATTRIBIVPROC)entry("glGetVertexAttribiv"))(index, pname, params);
}

GLboolean APIENTRY glIsBuffer(GLuint buffer)
{
    return ((PFNGLISBUFFERPROC)entry("glIsBuffer"))(buffer);
}

GLboolean APIENTRY glIsProgram(GLuint program)
{
    return ((PFNGLISPROGRAMPROC)entry("glIsProgram"))(program);
}

GLboolean APIENTRY glIsVertexArray(GLuint array)
{
    return ((PFNGLISVERTEXARRAYPROC)entry("glIsVertexArray"))(array);
}

void APIENTRY glLinkProgram(GLuint program)
{
    ((PFNGLLINKPROGRAMPROC)entry("glLinkProgram"))(program);
}

void APIENTRY glShaderSource(GLuint shader, GLsizei count, const GLchar *const *string, const GLint *length)
{
    ((PFNGLSHADERSOURCEPROC)entry("glShaderSource"))(shader, count, string, length);
}

void APIENTRY glUseProgram(GLuint program)
{
    ((PFNGLUSEPROGRAMPROC)entry("glUseProgram"))(program);
}

void APIENTRY glVertexAttribPointer(GLuint index, GLint size, GLenum type, GLboolean normalized, GLsizei stride, const void *pointer)
{
    ((PFNGLVERTEXATTRIBPOINTERPROC)entry("glVertexAttribPointer"))(index, size, type, normalized, stride, pointer);
}
