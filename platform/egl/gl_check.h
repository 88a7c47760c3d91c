/* One GL error check for the platform code: drains glGetError and, on an error, writes
 * "<what>: GL error 0x...." into err. 0, -ENOMEM (GL_OUT_OF_MEMORY) or -EIO. */
#ifndef SBFX_PLATFORM_GL_CHECK_H
#define SBFX_PLATFORM_GL_CHECK_H
#include <stddef.h>
int platform_gl_check(const char *what, char *err, size_t n);
#endif
