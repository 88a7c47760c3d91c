#include "egl/gl_check.h"
#include <GLES3/gl3.h>
#include <errno.h>
#include <stdio.h>

int platform_gl_check(const char *what, char *err, size_t n)
{
    GLenum e = glGetError(), first = e;
    while (e != GL_NO_ERROR) e = glGetError(); /* drain, so the next check starts clean */
    if (first == GL_NO_ERROR) return 0;
    snprintf(err, n, "%s: GL error 0x%x", what, first);
    return first == GL_OUT_OF_MEMORY ? -ENOMEM : -EIO;
}
