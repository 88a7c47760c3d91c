/* The scene-graph half of SbfxItem: sbfx_render_node.h. */
#include "sbfx_render_node.h"

#include <GLES3/gl3.h>
#include <QtCore/QDebug>
#include <QtGui/QMatrix4x4>
#include <QtGui/QVector3D>
#include <cmath>
#include <cstring>

namespace {

/* sbfx's log to Qt's; the last error kept in *user (sbfx_create has no module to ask after a
 * failure: its reason comes only through the log). */
void log_sbfx(sbfx_log_level level, const char *message, void *user)
{
    if (level == SBFX_LOG_INFO) qDebug("sbfx: %s", message);
    else qWarning("sbfx: %s", message);
    if (level == SBFX_LOG_ERROR) *static_cast<QByteArray *>(user) = message;
}

/* GL errors Qt left pending (Qt 6.4 leaves GL_INVALID_OPERATION from glPolygonMode on ES each
 * frame): read off before the node's own work so that its check sees only its own, and posted
 * again afterwards as sbfx does (include/sbfx.h "GL errors the host left pending"). */
struct HostErrors {
    GLenum codes[8];
    int count = 0;
    void take()
    {
        for (GLenum e = glGetError(); e != GL_NO_ERROR && count < 8; e = glGetError()) codes[count++] = e;
    }
    void give_back() const
    {
        for (int i = 0; i < count; i++) {
            if (codes[i] == GL_INVALID_ENUM) glEnable(GL_NONE);
            else if (codes[i] == GL_INVALID_VALUE) glLineWidth(0.0f);
            else if (codes[i] == GL_INVALID_OPERATION) glBeginQuery(GL_ANY_SAMPLES_PASSED, 0);
        }
    }
};

GLuint make_texture(GLenum format, int width, int height)
{
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, width, height);
    return texture;
}

GLuint make_framebuffer(GLuint color, GLuint depth)
{
    GLuint framebuffer = 0;
    glGenFramebuffers(1, &framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color, 0);
    if (depth) glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth, 0);
    return framebuffer;
}

void blit(GLuint from, int fx, int fy, GLuint to, int tx, int ty, int width, int height)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, from);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, to);
    glBlitFramebuffer(fx, fy, fx + width, fy + height, tx, ty, tx + width, ty + height, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
}

} // namespace

SbfxRenderNode::~SbfxRenderNode() { releaseResources(); }

void SbfxRenderNode::releaseResources()
{
    release_targets();
    sbfx_destroy(fx_);
    fx_ = nullptr;
    made_generation_ = ~0u;
}

void SbfxRenderNode::sync(const SbfxNodeSettings &settings, std::vector<SbfxNodeTrigger> &triggers,
                          const QSizeF &item_size)
{
    if (settings.generation != settings_.generation) settings_ = settings; /* both start from the defaults */
    triggers_.insert(triggers_.end(), triggers.begin(), triggers.end());
    triggers.clear();
    item_size_ = item_size;
    markDirty(QSGNode::DirtyMaterial);
}

/* The node puts back what it changes and sbfx does so for its own state (tests/hosts/
 * test_qt_quick.cpp compares the whole GL state before and after): nothing for Qt to reset. */
QSGRenderNode::StateFlags SbfxRenderNode::changedStates() const { return {}; }

QSGRenderNode::RenderingFlags SbfxRenderNode::flags() const { return BoundedRectRendering; }

QRectF SbfxRenderNode::rect() const { return QRectF(QPointF(0, 0), item_size_); }

void SbfxRenderNode::fail(const QString &message)
{
    if (message != status_.error) qWarning("SbfxItem: %s", qPrintable(message));
    status_.error = message;
}

/* Qt 6.4's matrix() points at a matrix that is gone by the time render() runs: kept here. */
void SbfxRenderNode::prepare() { model_view_ = *matrix(); }

void SbfxRenderNode::render(const RenderState *state)
{
    if (settings_.render_observer) settings_.render_observer(false);
    HostErrors host;
    host.take();
    PixelRect r;
    bool whole = false;
    if (target_rect(state, &r, &whole) && ensure_module()) {
        advance();
        draw(r, whole);
    }
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) fail(QString::asprintf("the item's GL work failed with GL error 0x%04x", e));
    host.give_back();
    if (settings_.render_observer) settings_.render_observer(true);
}

/* The item's rectangle in the render target's pixels (its bounding box: the effect itself is not
 * rotated with the item), from Qt's matrices and the viewport Qt set for the target. */
bool SbfxRenderNode::target_rect(const RenderState *state, PixelRect *out, bool *whole) const
{
    const QMatrix4x4 m = *state->projectionMatrix() * model_view_;
    const QVector3D a = m.map(QVector3D(0, 0, 0));
    const QVector3D b = m.map(QVector3D(float(item_size_.width()), float(item_size_.height()), 0));
    GLint vp[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_VIEWPORT, vp);
    auto to_x = [&](float ndc) { return std::lround(vp[0] + (ndc + 1.0) * 0.5 * vp[2]); };
    auto to_y = [&](float ndc) { return std::lround(vp[1] + (ndc + 1.0) * 0.5 * vp[3]); };
    long x0 = std::max<long>(std::min(to_x(a.x()), to_x(b.x())), vp[0]);
    long x1 = std::min<long>(std::max(to_x(a.x()), to_x(b.x())), vp[0] + vp[2]);
    long y0 = std::max<long>(std::min(to_y(a.y()), to_y(b.y())), vp[1]);
    long y1 = std::min<long>(std::max(to_y(a.y()), to_y(b.y())), vp[1] + vp[3]);
    if (x1 - x0 < 1 || y1 - y0 < 1) return false;
    *out = {int(x0), int(y0), int(x1 - x0), int(y1 - y0)};
    *whole = x0 == 0 && y0 == 0 && vp[0] == 0 && vp[1] == 0 && x1 == vp[2] && y1 == vp[3];
    return true;
}

/* The item's scene file parsed (*out stays NULL without one: the built-in explosion); false, with
 * the reason in `error`, when it does not parse. */
bool SbfxRenderNode::load_scene(sbfx_scene **out)
{
    char err[512] = "";
    const QByteArray path = settings_.scene_path.toLocal8Bit();
    if (!path.isEmpty() && sbfx_scene_load(path.constData(), out, err, sizeof(err)) != SBFX_OK) {
        fail(QString::fromLocal8Bit(err));
        return false;
    }
    return true;
}

/* A new scene (or the same file again) in the live module: what it shares with the old one is
 * kept (no shader compiled for a change of numbers), the clock goes on, its timeline starts now.
 * A scene that does not load or build leaves the old one playing, the reason in `error`. */
void SbfxRenderNode::reload_scene()
{
    loaded_scene_generation_ = settings_.scene_generation;
    sbfx_scene *scene = nullptr;
    if (!load_scene(&scene)) return;
    if (sbfx_set_scene(fx_, scene) == SBFX_OK) {
        sbfx_scene_camera_get(scene, &scene_camera_);
        set_quality_generation_ = 0; /* the item's quality level, again over the new scene's */
        idle_draws_nothing_ = false;
        status_.error.clear();
    } else {
        fail(QStringLiteral("sbfx_set_scene: %1").arg(QString::fromLocal8Bit(sbfx_last_error(fx_))));
    }
    sbfx_scene_free(scene);
}

/* The module, made again when the budget changed (or while there is none: a failure is not
 * retried until the scene or the budget change); a new scene goes into the live module. */
bool SbfxRenderNode::ensure_module()
{
    bool scene_changed = loaded_scene_generation_ != settings_.scene_generation;
    if (made_generation_ == settings_.module_generation && !(scene_changed && !fx_)) {
        if (scene_changed) reload_scene();
        return fx_ != nullptr;
    }
    releaseResources();
    made_generation_ = settings_.module_generation;
    loaded_scene_generation_ = settings_.scene_generation;
    sbfx_scene *scene = nullptr;
    if (!load_scene(&scene)) return false;
    sbfx_scene_camera_get(scene, &scene_camera_);
    sbfx_desc desc = {};
    desc.scene = scene;
    desc.frame_budget_ms = float(settings_.budget_ms);
    desc.log = log_sbfx;
    desc.log_user = &last_logged_error_;
    last_logged_error_.clear();
    sbfx_result r = sbfx_create(&desc, &fx_);
    sbfx_scene_free(scene);
    if (r != SBFX_OK) {
        const QByteArray why = last_logged_error_.isEmpty() ? QByteArray(sbfx_result_string(r)) : last_logged_error_;
        fail(QStringLiteral("sbfx_create: %1").arg(QString::fromLocal8Bit(why)));
        return false;
    }
    set_quality_generation_ = 0;
    idle_draws_nothing_ = false;
    status_.error.clear();
    clock_.invalidate();
    return true;
}

/* Triggers, quality and the simulation step of this frame. */
void SbfxRenderNode::advance()
{
    for (const SbfxNodeTrigger &t : triggers_) {
        sbfx_result r = sbfx_trigger(fx_, t.effect.constData(), t.position);
        /* a full pool refuses a trigger by design (sbfx logs it, triggers_refused counts it) */
        if (r != SBFX_OK && r != SBFX_ERR_POOL_FULL)
            fail(QStringLiteral("trigger(\"%1\"): %2").arg(QString::fromUtf8(t.effect), sbfx_last_error(fx_)));
    }
    triggers_.clear();
    if (settings_.has_quality && set_quality_generation_ != settings_.quality_generation) {
        set_quality_generation_ = settings_.quality_generation;
        if (sbfx_set_quality(fx_, &settings_.quality) != SBFX_OK)
            fail(QStringLiteral("quality: %1").arg(sbfx_last_error(fx_)));
    }
    double dt = settings_.fixed_step;
    double real = clock_.isValid() ? double(clock_.nsecsElapsed()) * 1e-9 : 0.0;
    clock_.start();
    if (dt <= 0.0) dt = real;
    if (settings_.running && sbfx_update(fx_, dt) != SBFX_OK) fail(QString::fromLocal8Bit(sbfx_last_error(fx_)));
    /* the fire's lights for the host's own scene (SbfxItem::emittedLights): a fixed array, no
     * allocation once the vector has grown to its largest */
    sbfx_point_light lights[SBFX_MAX_POINT_LIGHTS];
    int n = sbfx_emitted_lights(fx_, lights, SBFX_MAX_POINT_LIGHTS);
    status_.emitted_lights.assign(lights, lights + (n > 0 ? n : 0));
}

/* The C++ hook, else the scene's camera (its `camera` group, else sbfx-play's default orbit) with
 * the view and projection properties in place of its own where they are set. */
void SbfxRenderNode::camera(int width, int height, sbfx_frame *frame) const
{
    if (settings_.camera_hook) {
        settings_.camera_hook(width, height, sbfx_time(fx_), frame->view, frame->projection);
        return;
    }
    const sbfx_scene_camera &c = scene_camera_;
    double degrees = std::fmod(c.azimuth + c.orbit * sbfx_elapsed(fx_), 360.0);
    double angle = degrees * M_PI / 180.0;
    const float eye[3] = {c.target[0] + c.distance * float(std::sin(angle)), c.height,
                          c.target[2] + c.distance * float(std::cos(angle))};
    const float up[3] = {0.0f, 1.0f, 0.0f};
    sbfx_look_at(frame->view, eye, c.target, up);
    sbfx_perspective(frame->projection, c.fov * float(M_PI) / 180.0f, float(width) / float(height), 0.1f, 200.0f);
    if (settings_.has_view) std::memcpy(frame->view, settings_.view, sizeof(frame->view));
    if (settings_.has_projection) std::memcpy(frame->projection, settings_.projection, sizeof(frame->projection));
}

void SbfxRenderNode::release_targets()
{
    GLuint framebuffers[] = {scene_fbo_, out_fbo_}, textures[] = {scene_color_, scene_depth_, out_color_};
    if (scene_fbo_ || out_fbo_) glDeleteFramebuffers(2, framebuffers);
    if (scene_color_ || scene_depth_ || out_color_) glDeleteTextures(3, textures);
    scene_color_ = scene_depth_ = scene_fbo_ = out_color_ = out_fbo_ = 0;
    target_width_ = target_height_ = 0;
}

/* sbfx's inputs at the item's size: a copy of the pixels under the item and a depth of 1
 * everywhere (one framebuffer), and with its own target a second colour texture sbfx composites
 * into. Made when the size changes; the caller saved and restores the framebuffer bindings and
 * has the scissor test off. */
bool SbfxRenderNode::ensure_targets(int width, int height, bool own_target)
{
    if (width == target_width_ && height == target_height_ && (!own_target || out_fbo_)) return true;
    GLint texture = 0;
    GLboolean depth_mask = GL_TRUE;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask);
    release_targets();
    scene_color_ = make_texture(GL_RGBA8, width, height);
    scene_depth_ = make_texture(GL_DEPTH_COMPONENT24, width, height);
    scene_fbo_ = make_framebuffer(scene_color_, scene_depth_);
    bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    const GLfloat far_depth = 1.0f;
    glDepthMask(GL_TRUE);
    glClearBufferfv(GL_DEPTH, 0, &far_depth);
    glDepthMask(depth_mask);
    if (own_target) {
        out_color_ = make_texture(GL_RGBA8, width, height);
        out_fbo_ = make_framebuffer(out_color_, 0);
        complete = complete && glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    }
    glBindTexture(GL_TEXTURE_2D, GLuint(texture));
    target_width_ = width;
    target_height_ = height;
    if (!complete) {
        fail(QStringLiteral("the item's %1x%2 RGBA8 + DEPTH_COMPONENT24 framebuffers are incomplete").arg(width).arg(height));
        release_targets();
    }
    return complete;
}

void SbfxRenderNode::draw(const PixelRect &r, bool whole)
{
    sbfx_counters c;
    sbfx_stats(fx_, &c);
    status_.particles_alive = c.particles_alive;
    status_.triggers_fired = c.triggers_fired;
    status_.scene_reloads = c.scene_reloads;
    status_.width = r.width;
    status_.height = r.height;
    if (c.particles_alive == 0 && idle_draws_nothing_) return; /* sbfx would draw nothing */
    GLint qt_draw = 0, qt_read = 0, samples = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &qt_draw);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &qt_read);
    glGetIntegerv(GL_SAMPLE_BUFFERS, &samples);
    if (samples > 0) {
        fail(QStringLiteral("Qt's render target is multisampled: the item copies pixels with glBlitFramebuffer, "
                            "which needs a single-sampled window (QSurfaceFormat::setSamples(0))"));
        return;
    }
    const GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    glDisable(GL_SCISSOR_TEST);
    bool drawn = false;
    if (ensure_targets(r.width, r.height, !whole)) {
        sbfx_frame frame = {};
        camera(r.width, r.height, &frame);
        frame.scene_color_texture = scene_color_;
        frame.scene_depth_texture = scene_depth_;
        frame.width = r.width;
        frame.height = r.height;
        /* sbfx's scene colour: what lies under the item; its own target starts from the same */
        blit(GLuint(qt_draw), r.x, r.y, scene_fbo_, 0, 0, r.width, r.height);
        if (!whole) blit(GLuint(qt_draw), r.x, r.y, out_fbo_, 0, 0, r.width, r.height);
        frame.out_framebuffer = whole ? GLuint(qt_draw) : out_fbo_;
        if (sbfx_render(fx_, &frame) == SBFX_OK) drawn = true;
        else fail(QString::fromLocal8Bit(sbfx_last_error(fx_)));
        if (scissor) glEnable(GL_SCISSOR_TEST); /* Qt's clip applies to the copy back */
        if (drawn && !whole) blit(out_fbo_, 0, 0, GLuint(qt_draw), r.x, r.y, r.width, r.height);
    }
    if (scissor) glEnable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(qt_read));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(qt_draw));
    sbfx_stats(fx_, &c);
    idle_draws_nothing_ = c.particles_alive == 0 && c.passes == 0;
    status_.own_target = !whole;
    status_.frames += drawn && c.passes > 0;
}
