/*
 * The system's own GL library on Windows: opengl32.dll exports the OpenGL
 * 1.1 functions, which wglGetProcAddress (a bare host loader) does not
 * return. Not a loader of the library's choosing: the host's loader comes
 * first (gl/load.c's gl_proc), this only where it answers nothing.
 */
#include "gl.h"

#if defined(_WIN32)
/* kernel32's module functions, declared here rather than through
 * windows.h, whose macros (near, far, min, max) would reach the code after
 * it in one translation unit (make amalgamation). GetProcAddress's FARPROC
 * is a function pointer like sky_gl_proc. */
__declspec(dllimport) void *__stdcall GetModuleHandleA(const char *name);
__declspec(dllimport) void *__stdcall LoadLibraryA(const char *name);
__declspec(dllimport) sky_gl_proc __stdcall GetProcAddress(void *module, const char *name);

sky_gl_proc sky_gl_system_proc(const char *name)
{
    void *gl = GetModuleHandleA("opengl32.dll");
    if (!gl) gl = LoadLibraryA("opengl32.dll");
    return gl ? GetProcAddress(gl, name) : NULL;
}
#else
sky_gl_proc sky_gl_system_proc(const char *name)
{
    (void)name;
    return NULL;
}
#endif
