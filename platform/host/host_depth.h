/* A host's opaque depth, drawn the way a host draws it, for the tests and benchmarks that check
 * sbfx against every depth set-up (issue 10): standard or reversed-Z, 24-bit or float.
 *
 * host_depth_plane() (re)makes *texture as a w x h depth texture of `format`
 * (GL_DEPTH_COMPONENT24 or GL_DEPTH_COMPONENT32F, immutable, NEAREST) and draws into it an
 * opaque plane facing the camera at view distance `distance` over the whole frame: a vertex
 * shader evaluates the projection's depth row in float as a host's would, the buffer is cleared
 * to the convention's far value (1, or 0 when projection[14] > 0: reversed) and tested LESS or
 * GREATER; with zero_to_one the draw runs under glClipControlEXT(GL_LOWER_LEFT, GL_ZERO_TO_ONE)
 * and the clip control is put back to the default after. Leaves framebuffer 0, program 0,
 * vertex array 0 and the depth test off bound. Returns 0, -ENOTSUP (zero_to_one without
 * GL_EXT_clip_control) or -EIO (framebuffer incomplete, GL error). */
#ifndef SBFX_HOST_DEPTH_H
#define SBFX_HOST_DEPTH_H

#include <GLES3/gl3.h>
#include <stdbool.h>

/* True when the current context offers clip control: GL_EXT_clip_control on ES, OpenGL 4.5 or
 * GL_ARB_clip_control on desktop OpenGL (issue 18). */
bool host_depth_has_clip_control(void);
/* glClipControlEXT on ES, glClipControl on desktop OpenGL; NULL without clip control. */
void (*host_depth_clip_control(void))(GLenum origin, GLenum depth);

int host_depth_plane(GLuint *texture, int w, int h, GLenum format, const float projection[16], bool zero_to_one,
                     double distance);

#endif
