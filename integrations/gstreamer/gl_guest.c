/* The element's blits, clears and read-backs, each inside one save and restore (gl_guest.h). */
#include "gl_guest.h"

#include <stdio.h>
#include <string.h>

/* What a blit or a clear depends on and what binding them changes. */
struct saved_state {
    GLint read_fbo, draw_fbo;
    GLboolean scissor, discard;
    bool texture;               /* the parts below were saved */
    GLint texture_2d;
    GLfloat depth_clear;
    GLboolean depth_mask;
    bool pack;
    GLint pack_buffer, pack_row_length, pack_skip_rows, pack_skip_pixels, pack_alignment;
};

static void save(struct saved_state *s, bool texture, bool pack)
{
    memset(s, 0, sizeof(*s));
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_fbo);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_fbo);
    s->scissor = glIsEnabled(GL_SCISSOR_TEST);
    s->discard = glIsEnabled(GL_RASTERIZER_DISCARD);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_RASTERIZER_DISCARD);
    if ((s->texture = texture)) {
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &s->texture_2d);
        glGetFloatv(GL_DEPTH_CLEAR_VALUE, &s->depth_clear);
        glGetBooleanv(GL_DEPTH_WRITEMASK, &s->depth_mask);
    }
    if ((s->pack = pack)) {
        glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &s->pack_buffer);
        glGetIntegerv(GL_PACK_ROW_LENGTH, &s->pack_row_length);
        glGetIntegerv(GL_PACK_SKIP_ROWS, &s->pack_skip_rows);
        glGetIntegerv(GL_PACK_SKIP_PIXELS, &s->pack_skip_pixels);
        glGetIntegerv(GL_PACK_ALIGNMENT, &s->pack_alignment);
        glPixelStorei(GL_PACK_ROW_LENGTH, 0);
        glPixelStorei(GL_PACK_SKIP_ROWS, 0);
        glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
    }
}

static void set_enabled(GLenum cap, GLboolean on)
{
    if (on) glEnable(cap);
    else glDisable(cap);
}

/* Puts everything back; returns 0, or -1 when GL reported an error meanwhile. */
static int restore(const struct saved_state *s)
{
    GLenum error = glGetError();
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_fbo);
    set_enabled(GL_SCISSOR_TEST, s->scissor);
    set_enabled(GL_RASTERIZER_DISCARD, s->discard);
    if (s->texture) {
        glBindTexture(GL_TEXTURE_2D, (GLuint)s->texture_2d);
        glClearDepthf(s->depth_clear);
        glDepthMask(s->depth_mask);
    }
    if (s->pack) {
        glBindBuffer(GL_PIXEL_PACK_BUFFER, (GLuint)s->pack_buffer);
        glPixelStorei(GL_PACK_ROW_LENGTH, s->pack_row_length);
        glPixelStorei(GL_PACK_SKIP_ROWS, s->pack_skip_rows);
        glPixelStorei(GL_PACK_SKIP_PIXELS, s->pack_skip_pixels);
        glPixelStorei(GL_PACK_ALIGNMENT, s->pack_alignment);
    }
    return error == GL_NO_ERROR ? 0 : -1;
}

static GLuint texture_2d(GLenum format, int width, int height)
{
    GLuint t = 0;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, width, height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

/* The depth texture cleared to `depth`: drawn through draw_fbo, which keeps nothing attached. */
static bool clear_depth(struct gl_guest *g, float depth)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, g->draw_fbo);
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, g->depth_texture, 0);
    bool complete = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    if (complete) {
        glDepthMask(GL_TRUE);
        glClearDepthf(depth);
        glClear(GL_DEPTH_BUFFER_BIT);
    }
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
    return complete;
}

int gl_guest_targets(struct gl_guest *g, int width, int height, float depth, char *err, size_t n)
{
    if (g->width == width && g->height == height && g->depth_value == depth && g->depth_texture) return 0;
    struct saved_state s;
    save(&s, true, false);
    if (!g->read_fbo) glGenFramebuffers(1, &g->read_fbo);
    if (!g->draw_fbo) glGenFramebuffers(1, &g->draw_fbo);
    if (g->width != width || g->height != height || !g->depth_texture) {
        glDeleteTextures(1, &g->depth_texture);
        g->depth_texture = texture_2d(GL_DEPTH_COMPONENT32F, width, height);
    }
    bool complete = clear_depth(g, depth);
    int rc = restore(&s);
    if (!complete || rc) {
        snprintf(err, n, "the %dx%d depth texture of the video (DEPTH_COMPONENT32F) could not be %s", width, height,
                 complete ? "made (a GL error)" : "drawn into (framebuffer incomplete)");
        return -1;
    }
    g->width = width, g->height = height, g->depth_value = depth;
    return 0;
}

/* Attaches a colour texture to a framebuffer target (0: detaches). */
static void attach(GLenum target, GLuint fbo, GLuint texture)
{
    glBindFramebuffer(target, fbo);
    glFramebufferTexture2D(target, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
}

int gl_guest_copy(struct gl_guest *g, GLuint input, GLuint output)
{
    struct saved_state s;
    save(&s, false, false);
    attach(GL_READ_FRAMEBUFFER, g->read_fbo, input);
    attach(GL_DRAW_FRAMEBUFFER, g->draw_fbo, output);
    glBlitFramebuffer(0, 0, g->width, g->height, 0, 0, g->width, g->height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    attach(GL_READ_FRAMEBUFFER, g->read_fbo, 0); /* the input texture is upstream's: hold no reference */
    return restore(&s); /* sbfx composites into draw_fbo, the output attached (gl_guest_detach) */
}

void gl_guest_detach(struct gl_guest *g)
{
    GLint draw = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    attach(GL_DRAW_FRAMEBUFFER, g->draw_fbo, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)draw);
}

static void release_detail(struct gl_guest *g)
{
    glDeleteTextures(g->detail_levels, g->detail_textures);
    glDeleteBuffers(2, g->pack_buffers);
    memset(g->detail_textures, 0, sizeof(g->detail_textures));
    memset(g->pack_buffers, 0, sizeof(g->pack_buffers));
    g->detail_levels = g->detail_size = 0;
    g->pack_pending[0] = g->pack_pending[1] = false;
}

/* Sides of the levels: the centred square halved while it is over twice the slice, then the
 * slice itself (each halving blit is an exact 2 x 2 box: LINEAR sampling between four texels). */
static int plan_levels(int side, int size, int *sides)
{
    int n = 0;
    while (side > 2 * size && n < GL_GUEST_DETAIL_LEVELS - 1) sides[n++] = side /= 2;
    sides[n++] = size;
    return n;
}

int gl_guest_detail_targets(struct gl_guest *g, int size, char *err, size_t n)
{
    struct saved_state s;
    save(&s, true, true);
    release_detail(g);
    if (size > 0) {
        int side = g->width < g->height ? g->width : g->height;
        g->detail_size = size;
        g->detail_levels = plan_levels(side, size, g->detail_sides);
        for (int i = 0; i < g->detail_levels; i++)
            g->detail_textures[i] = texture_2d(GL_RGBA8, g->detail_sides[i], g->detail_sides[i]);
        glGenBuffers(2, g->pack_buffers);
        for (int i = 0; i < 2; i++) {
            glBindBuffer(GL_PIXEL_PACK_BUFFER, g->pack_buffers[i]);
            glBufferData(GL_PIXEL_PACK_BUFFER, (GLsizeiptr)size * size * 4, NULL, GL_STREAM_READ);
        }
    }
    if (restore(&s)) {
        snprintf(err, n, "the detail read-back targets (%d levels down to %dx%d RGBA8) could not be made",
                 g->detail_levels, size, size);
        release_detail(g);
        return -1;
    }
    return 0;
}

/* The picture's centred square through the levels into the last one, LINEAR at each step. */
static void box_down(struct gl_guest *g, GLuint input)
{
    int side = g->width < g->height ? g->width : g->height;
    int x0 = (g->width - side) / 2, y0 = (g->height - side) / 2, from = side;
    GLuint source = input;
    for (int i = 0; i < g->detail_levels; i++) {
        int to = g->detail_sides[i];
        attach(GL_READ_FRAMEBUFFER, g->read_fbo, source);
        attach(GL_DRAW_FRAMEBUFFER, g->draw_fbo, g->detail_textures[i]);
        glBlitFramebuffer(x0, y0, x0 + from, y0 + from, 0, 0, to, to, GL_COLOR_BUFFER_BIT, GL_LINEAR);
        source = g->detail_textures[i];
        x0 = y0 = 0;
        from = to;
    }
}

/* The read-back waiting in pack buffer `i`, mapped, to `take`. */
static bool take_pending(struct gl_guest *g, int i, void (*take)(const uint8_t *, void *), void *user)
{
    if (!g->pack_pending[i]) return false;
    g->pack_pending[i] = false;
    GLsizeiptr bytes = (GLsizeiptr)g->detail_size * g->detail_size * 4;
    glBindBuffer(GL_PIXEL_PACK_BUFFER, g->pack_buffers[i]);
    const uint8_t *rgba = glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, bytes, GL_MAP_READ_BIT);
    if (!rgba) return false;
    take(rgba, user);
    glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
    return true;
}

int gl_guest_detail(struct gl_guest *g, GLuint input, void (*take)(const uint8_t *rgba, void *user), void *user)
{
    if (!g->detail_levels) return 0;
    struct saved_state s;
    save(&s, false, true);
    box_down(g, input);
    int now = g->pack_next, before = 1 - now;
    bool taken = take_pending(g, before, take, user);
    attach(GL_READ_FRAMEBUFFER, g->read_fbo, g->detail_textures[g->detail_levels - 1]);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, g->pack_buffers[now]);
    glReadPixels(0, 0, g->detail_size, g->detail_size, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    g->pack_pending[now] = true;
    g->pack_next = before;
    attach(GL_READ_FRAMEBUFFER, g->read_fbo, 0);
    attach(GL_DRAW_FRAMEBUFFER, g->draw_fbo, 0);
    return restore(&s) ? -1 : taken ? 1 : 0;
}

void gl_guest_release(struct gl_guest *g)
{
    release_detail(g);
    glDeleteTextures(1, &g->depth_texture);
    glDeleteFramebuffers(1, &g->read_fbo);
    glDeleteFramebuffers(1, &g->draw_fbo);
    memset(g, 0, sizeof(*g));
}
