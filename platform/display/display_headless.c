/* The headless display: EGL surfaceless (egl_headless.h), an RGBA8 framebuffer object, every
 * frame read back with glReadPixels and written as DIR/frame-NNNN.png, optionally shrunk into a
 * contact sheet. The pixel buffer and the PNG writer's row table are allocated once: a frame
 * allocates nothing of the player's (libpng's own state excepted). */
#include "egl/gl_check.h"
#include "display/display.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "egl/egl_headless.h"
#include "image/png_io.h"

#define CONTACT_CELL_WIDTH 240 /* a 960-wide frame shrinks by 4 */

struct display_headless {
    struct display base;
    struct display_headless_desc desc;
    struct egl_headless egl;
    GLuint renderbuffer;
    uint8_t *pixels;
    struct png_writer png;
    struct contact_sheet sheet;
};

static struct display_headless *to_headless(struct display *d)
{
    return (struct display_headless *)d; /* base is the first member */
}

static int create_output(struct display_headless *h, char *err, size_t n)
{
    int w = h->desc.width, hgt = h->desc.height;
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
    if (w > max_size || hgt > max_size) {
        snprintf(err, n, "--size: %dx%d is larger than this GL allows (%d)", w, hgt, max_size);
        return -EINVAL;
    }
    glGenRenderbuffers(1, &h->renderbuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, h->renderbuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, hgt);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glGenFramebuffers(1, &h->base.framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, h->base.framebuffer);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, h->renderbuffer);
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    GLenum gl_err = glGetError();
    if (status != GL_FRAMEBUFFER_COMPLETE || gl_err != GL_NO_ERROR) {
        snprintf(err, n, "output framebuffer %dx%d RGBA8: status 0x%x, GL error 0x%x", w, hgt,
                 status, gl_err);
        return gl_err == GL_OUT_OF_MEMORY ? -ENOMEM : -EIO;
    }
    return 0;
}

static int headless_present(struct display *d, int index, char *err, size_t n)
{
    struct display_headless *h = to_headless(d);
    int w = d->width, hgt = d->height;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, d->framebuffer);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, w, hgt, GL_RGBA, GL_UNSIGNED_BYTE, h->pixels);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    int rc = platform_gl_check("glReadPixels of the output framebuffer", err, n);
    if (rc) return rc;
    /* A display has no alpha; written as is, viewers would show whatever the composite left
     * in alpha as transparency. */
    for (size_t i = 3; i < (size_t)w * hgt * 4; i += 4) h->pixels[i] = 255;
    char path[PATH_MAX + 32];
    snprintf(path, sizeof(path), "%s/frame-%04d.png", h->desc.out_dir, index);
    rc = png_writer_write(&h->png, path, h->pixels, true, err, n);
    if (index == 0) h->sheet.count = 0; /* a new take (sbfx-play --watch): a new sheet */
    if (rc == 0 && h->desc.contact_sheet) rc = contact_sheet_add(&h->sheet, h->pixels, true);
    if (rc == 0) d->counts.presented++;
    return rc;
}

static int headless_dispatch(struct display *d, char *err, size_t n)
{
    return 0; /* never busy */
}

static int headless_finish(struct display *d, char *err, size_t n)
{
    struct display_headless *h = to_headless(d);
    if (!h->desc.contact_sheet) return 0;
    char path[PATH_MAX + 32];
    snprintf(path, sizeof(path), "%s/contact-sheet.png", h->desc.out_dir);
    return contact_sheet_write(&h->sheet, path, err, n);
}

static void headless_destroy(struct display *d)
{
    if (!d) return;
    struct display_headless *h = to_headless(d);
    contact_sheet_free(&h->sheet);
    png_writer_free(&h->png);
    free(h->pixels);
    if (h->egl.display != EGL_NO_DISPLAY) {
        glDeleteFramebuffers(1, &d->framebuffer);
        glDeleteRenderbuffers(1, &h->renderbuffer);
    }
    egl_headless_close(&h->egl);
    free(h);
}

static int headless_reset_context(struct display *d, char *err, size_t n)
{
    struct display_headless *h = to_headless(d);
    glDeleteFramebuffers(1, &d->framebuffer); /* no-ops in a context really lost */
    glDeleteRenderbuffers(1, &h->renderbuffer);
    d->framebuffer = h->renderbuffer = 0;
    int rc = egl_headless_recreate_context(&h->egl, err, n);
    d->robust_context = h->egl.robust;
    return rc ? rc : create_output(h, err, n);
}

static const struct display_ops headless_ops = {
    .present = headless_present,
    .dispatch = headless_dispatch,
    .finish = headless_finish,
    .reset_context = headless_reset_context,
    .destroy = headless_destroy,
};

static int headless_setup(struct display_headless *h, char *err, size_t n)
{
    const struct display_headless_desc *desc = &h->desc;
    int rc = egl_headless_open_robust(&h->egl, err, n);
    if (rc == 0) rc = create_output(h, err, n);
    if (rc) return rc;
    h->pixels = malloc((size_t)desc->width * desc->height * 4);
    if (!h->pixels) {
        snprintf(err, n, "out of memory for a %dx%d frame", desc->width, desc->height);
        return -ENOMEM;
    }
    rc = png_writer_init(&h->png, desc->width, desc->height, err, n);
    if (rc == 0 && desc->contact_sheet)
        rc = contact_sheet_init(&h->sheet, desc->frames, desc->width, desc->height,
                                CONTACT_CELL_WIDTH, err, n);
    snprintf(h->base.description, sizeof(h->base.description), "EGL %s", h->egl.platform);
    h->base.robust_context = h->egl.robust;
    return rc;
}

int display_headless_create(const struct display_headless_desc *desc, struct display **out,
                            char *err, size_t n)
{
    *out = NULL;
    struct display_headless *h = calloc(1, sizeof(*h));
    if (!h) {
        snprintf(err, n, "out of memory");
        return -ENOMEM;
    }
    h->desc = *desc;
    h->egl.display = EGL_NO_DISPLAY;
    h->base = (struct display){.ops = &headless_ops, .name = "headless", .width = desc->width,
                               .height = desc->height, .fd = -1};
    int rc = headless_setup(h, err, n);
    if (rc) {
        headless_destroy(&h->base);
        return rc;
    }
    *out = &h->base;
    return 0;
}

const char *display_gl_renderer(void)
{
    const char *r = (const char *)glGetString(GL_RENDERER);
    return r ? r : "?";
}
