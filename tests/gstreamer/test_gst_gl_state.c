/* The element as a guest in GstGL's context (issue 34; docs/hosts/gstreamer.md): around each
 * buffer that goes through sbfx, on GstGL's thread, a "hostile" state is set before the element
 * sees the buffer (everything gl_snapshot.h holds that GL allows to change here, none at its
 * default) and the whole snapshot taken; after the element has pushed the buffer on, the
 * snapshot must be the same, entry by entry (the input's texture uploaded first: GstGL's lazy
 * upload is not the element's doing). Frames with live particles, with detail from the
 * input (its blits and read-backs) and idle frames; on desktop OpenGL and OpenGL ES (tests/run.sh
 * runs it with GST_GL_API unset and =gles2). The state goes back to GL's defaults before the
 * buffer goes on, so the elements after see what they expect. */
#include <GLES3/gl3.h>
#include <stdbool.h>

#include "gst_harness.h"
#include "gl_snapshot.h"

#define WARM_UP 4 /* frames before the check: GstGL's pool has made its textures by then */

typedef struct hostile {
    GLuint fbo[2], texture[3], buffer[3], vao, sampler;
    bool made;
} hostile;

typedef struct state_check {
    GstElement *fx;
    int frames, checked, differing;
    char first[64];
    hostile h;
    snapshot before, after;
} state_check;

static void make_objects(hostile *h)
{
    glGenTextures(3, h->texture);
    for (int i = 0; i < 3; i++) {
        glBindTexture(GL_TEXTURE_2D, h->texture[i]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 8, 8, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
    }
    glBindTexture(GL_TEXTURE_2D, 0);
    glGenFramebuffers(2, h->fbo);
    for (int i = 0; i < 2; i++) {
        glBindFramebuffer(GL_FRAMEBUFFER, h->fbo[i]);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, h->texture[i], 0);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glGenBuffers(3, h->buffer);
    for (int i = 0; i < 3; i++) {
        glBindBuffer(GL_COPY_WRITE_BUFFER, h->buffer[i]);
        glBufferData(GL_COPY_WRITE_BUFFER, 4096, NULL, GL_STATIC_DRAW);
    }
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    glGenVertexArrays(1, &h->vao);
    glGenSamplers(1, &h->sampler);
    h->made = true;
}

static void set_on(GLenum cap, bool on)
{
    if (on) glEnable(cap);
    else glDisable(cap);
}

/* Every state below either hostile or at GL's default. */
static void state(const hostile *h, bool on)
{
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, on ? h->fbo[0] : 0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, on ? h->fbo[1] : 0);
    glBindVertexArray(on ? h->vao : 0);
    glBindBuffer(GL_ARRAY_BUFFER, on ? h->buffer[0] : 0);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, on ? h->buffer[1] : 0);
    glBindBuffer(GL_UNIFORM_BUFFER, on ? h->buffer[2] : 0);
    for (GLuint u = 0; u < 8; u++) {
        glActiveTexture(GL_TEXTURE0 + u);
        glBindTexture(GL_TEXTURE_2D, on ? h->texture[2] : 0);
        glBindSampler(u, on ? h->sampler : 0);
    }
    glActiveTexture(on ? GL_TEXTURE5 : GL_TEXTURE0);
    set_on(GL_BLEND, on);
    glBlendFuncSeparate(on ? GL_DST_COLOR : GL_ONE, on ? GL_SRC_ALPHA : GL_ZERO, on ? GL_ZERO : GL_ONE,
                        on ? GL_ONE : GL_ZERO);
    glBlendEquation(on ? GL_FUNC_REVERSE_SUBTRACT : GL_FUNC_ADD);
    glBlendColor(on ? 0.25f : 0.0f, 0.0f, on ? 0.5f : 0.0f, 0.0f);
    set_on(GL_DEPTH_TEST, on);
    glDepthFunc(on ? GL_GREATER : GL_LESS);
    glDepthMask(on ? GL_FALSE : GL_TRUE);
    glClearDepthf(on ? 0.25f : 1.0f);
    set_on(GL_STENCIL_TEST, on);
    glStencilFunc(on ? GL_NEVER : GL_ALWAYS, on ? 3 : 0, on ? 0x0f : 0xffffffffu);
    glStencilOp(on ? GL_INCR : GL_KEEP, on ? GL_DECR : GL_KEEP, on ? GL_INVERT : GL_KEEP);
    set_on(GL_CULL_FACE, on);
    glCullFace(on ? GL_FRONT_AND_BACK : GL_BACK);
    glFrontFace(on ? GL_CW : GL_CCW);
    set_on(GL_SCISSOR_TEST, on);
    glScissor(on ? 3 : 0, on ? 4 : 0, on ? 5 : W, on ? 6 : H);
    glViewport(on ? 7 : 0, on ? 8 : 0, on ? 9 : W, on ? 10 : H);
    glColorMask(!on, on, !on, on);
    glClearColor(on ? 0.5f : 0.0f, on ? 0.25f : 0.0f, 0.0f, on ? 0.75f : 0.0f);
    set_on(GL_POLYGON_OFFSET_FILL, on);
    glPolygonOffset(on ? 2.0f : 0.0f, on ? 3.0f : 0.0f);
    set_on(GL_RASTERIZER_DISCARD, on);
    set_on(GL_DITHER, !on);
    set_on(GL_SAMPLE_ALPHA_TO_COVERAGE, on);
    glPixelStorei(GL_PACK_ALIGNMENT, on ? 1 : 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, on ? 17 : 0);
    glPixelStorei(GL_PACK_SKIP_ROWS, on ? 2 : 0);
    glPixelStorei(GL_PACK_SKIP_PIXELS, on ? 3 : 0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, on ? 2 : 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, on ? 19 : 0);
}

static void drain_errors(void)
{
    for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; i++) {}
}

static void before_element(GstGLContext *context, gpointer user)
{
    state_check *c = user;
    if (!c->h.made) make_objects(&c->h);
    state(&c->h, true);
    drain_errors();
    snapshot_take(&c->before, false);
    drain_errors(); /* a query the profile lacks (the core profile's mipmap hint) */
}

static void after_element(GstGLContext *context, gpointer user)
{
    state_check *c = user;
    snapshot_take(&c->after, false);
    char first[64];
    int n = snapshot_diff(&c->before, &c->after, "after sbfx", first, sizeof(first));
    if (n && !c->differing) snprintf(c->first, sizeof(c->first), "%s", first);
    c->differing += n;
    c->checked++;
    state(&c->h, false);
    drain_errors();
}

static void on_gl(state_check *c, GstGLContextThreadFunc fn)
{
    GstGLContext *context = NULL;
    g_object_get(c->fx, "context", &context, NULL);
    if (!context) return;
    gst_gl_context_thread_add(context, fn, c);
    gst_object_unref(context);
}

/* GstGL uploads lazily: glupload's memory gets its texture when first mapped for GL, by whoever
 * maps it (GstGL's upload sets the active unit's 2D binding and the unpack row length, and does
 * not put them back). Mapped here first, so that what is compared is the element's own work. */
static void upload_now(GstBuffer *buffer)
{
    GstMapInfo map;
    for (guint i = 0; i < gst_buffer_n_memory(buffer); i++) {
        GstMemory *m = gst_buffer_peek_memory(buffer, i);
        if (gst_memory_map(m, &map, GST_MAP_READ | GST_MAP_GL)) gst_memory_unmap(m, &map);
    }
}

static GstPadProbeReturn sink_side(GstPad *pad, GstPadProbeInfo *info, gpointer user)
{
    state_check *c = user;
    if (++c->frames <= WARM_UP) return GST_PAD_PROBE_OK;
    upload_now(GST_PAD_PROBE_INFO_BUFFER(info));
    on_gl(c, before_element);
    return GST_PAD_PROBE_OK;
}

static GstPadProbeReturn src_side(GstPad *pad, GstPadProbeInfo *info, gpointer user)
{
    state_check *c = user;
    if (c->frames > WARM_UP) on_gl(c, after_element);
    return GST_PAD_PROBE_OK;
}

static void add_probe(GstElement *e, const char *pad, GstPadProbeCallback fn, void *user)
{
    GstPad *p = gst_element_get_static_pad(e, pad);
    gst_pad_add_probe(p, GST_PAD_PROBE_TYPE_BUFFER, fn, user, NULL);
    gst_object_unref(p);
}

/* 16 frames of sbfx with `properties`, the state checked around the last 12. */
static void check_state(const char *properties, const char *source)
{
    gst_start();
    char d[768];
    snprintf(d, sizeof(d), "videotestsrc pattern=%s num-buffers=16 ! video/x-raw,width=96,height=64,framerate=30/1 "
             "! glupload ! sbfx name=fx %s ! gldownload ! fakesink", source, properties);
    GstElement *p = pipeline_of(d);
    state_check *c = calloc(1, sizeof(*c));
    c->fx = by_name(p, "fx");
    add_probe(c->fx, "sink", sink_side, c);
    add_probe(c->fx, "src", src_side, c);
    gst_element_set_state(p, GST_STATE_PLAYING);
    GstMessage *m = gst_bus_timed_pop_filtered(GST_ELEMENT_BUS(p), 60 * GST_SECOND,
                                               GST_MESSAGE_EOS | GST_MESSAGE_ERROR);
    run r = {0};
    keep_stats(p, &r);
    CHECK(m && GST_MESSAGE_TYPE(m) == GST_MESSAGE_EOS, "the run did not end with EOS");
    if (m) gst_message_unref(m);
    gst_element_set_state(p, GST_STATE_NULL);
    printf("# %s: %d frames checked (%llu rendered, %llu forwarded), %d entries of %d differ\n", properties,
           c->checked, (unsigned long long)stat_u64(&r, "frames-rendered"),
           (unsigned long long)stat_u64(&r, "frames-forwarded"), c->differing, c->before.count);
    CHECK(c->checked == 16 - WARM_UP && c->differing == 0, "%d frames checked, %d entries differ (first: %s)",
          c->checked, c->differing, c->first);
    run_free(&r);
    gst_object_unref(c->fx);
    gst_object_unref(p);
    free(c);
}

CHECK_TEST(live_particles_leave_the_state_as_found)
{
    check_state("scene=scenes/explosion.cfg", "colors");
}

CHECK_TEST(detail_from_input_leaves_the_state_as_found)
{
    check_state("scene=scenes/explosion.cfg detail-from-input=true", "ball");
}

CHECK_TEST(post_effects_leave_the_state_as_found)
{
    check_state("scene=scenes/post.cfg", "colors");
}

CHECK_TEST(idle_frames_leave_the_state_as_found)
{
    check_state("scene=scenes/explosion.cfg timeline=false detail-from-input=true", "ball");
    check_state("scene=scenes/explosion.cfg timeline=false", "colors");
}

int main(int argc, char **argv) { return check_main_args(argc, argv); }
