/* The element's own GL work in GstGL's context, beside what sbfx does (docs/hosts/gstreamer.md,
 * "A guest in GstGL's context"): the frame's picture copied into the output texture, the depth
 * texture sbfx reads the video's depth from, and the input's luma for detail-from-input, all by
 * framebuffer blits and clears (no program, no vertex array, no texture unit). Each entry point
 * saves what it changes in one block of glGet calls and puts it back: the read and draw
 * framebuffers, the scissor test and rasterizer discard (they apply to blits and clears), and
 * where it needs them the 2D texture binding of the active unit, the depth clear value and mask,
 * the pixel pack buffer and pack store. OpenGL ES 3.0 or desktop OpenGL 3.3 calls only. */
#ifndef SBFX_GST_GL_GUEST_H
#define SBFX_GST_GL_GUEST_H

#include <GLES3/gl3.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define GL_GUEST_DETAIL_LEVELS 16 /* halvings of the picture on its way to a detail slice */

struct gl_guest {
    int width, height;          /* the frame size the targets are for (0: none yet) */
    GLuint read_fbo, draw_fbo;  /* textures are attached to these as each frame needs */
    GLuint depth_texture;       /* width x height DEPTH_COMPONENT32F, one value everywhere */
    float depth_value;          /* ... this window depth */
    /* detail-from-input: the centred square of the picture halved level by level, then blitted
     * to detail_size x detail_size and read back through two pixel pack buffers (one frame late) */
    int detail_size, detail_levels;
    GLuint detail_textures[GL_GUEST_DETAIL_LEVELS];
    int detail_sides[GL_GUEST_DETAIL_LEVELS];
    GLuint pack_buffers[2];
    int pack_next;              /* the buffer this frame's read-back goes into */
    bool pack_pending[2];       /* a read-back waits in that buffer */
};

/* Makes (or remakes, for a new size or depth) the framebuffers and the depth texture of a
 * width x height frame whose every pixel is at window depth `depth`. 0, or -1 with a message. */
int gl_guest_targets(struct gl_guest *g, int width, int height, float depth, char *err, size_t n);
/* The detail read-back of a width x height frame into size x size slices (size 0: none). */
int gl_guest_detail_targets(struct gl_guest *g, int size, char *err, size_t n);
/* The input texture's picture, unchanged, into the output texture (both width x height RGBA).
 * Leaves draw_fbo with the output attached, for sbfx to composite into. 0, or -1 on a GL error. */
int gl_guest_copy(struct gl_guest *g, GLuint input, GLuint output);
/* Takes the output off draw_fbo once sbfx has drawn (the texture goes back to the pool). */
void gl_guest_detach(struct gl_guest *g);
/* This frame's centred square, box-filtered down, read back (into the next pack buffer); the
 * previous frame's read-back, if one is waiting, mapped and handed to `take` as size x size RGBA
 * bytes, row 0 the picture's top row (GstGL's textures hold the picture's first row at t = 0).
 * `take` only reads: it makes no GL call. Returns 1 when `take` was called, 0 when nothing
 * waited, -1 on a GL error. */
int gl_guest_detail(struct gl_guest *g, GLuint input, void (*take)(const uint8_t *rgba, void *user), void *user);
/* Deletes every object (with the context current). */
void gl_guest_release(struct gl_guest *g);

#endif
