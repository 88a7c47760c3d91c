/* The scene-graph half of SbfxItem (sbfx_item.h): a QSGRenderNode that owns the sbfx module and
 * draws it with Qt's OpenGL ES context current, on Qt's render thread.
 *
 * Each frame it finds the item's rectangle in the render target from Qt's matrices and viewport.
 * When the item covers the whole target, sbfx composites straight into Qt's framebuffer. When it
 * does not, the node copies the pixels Qt has drawn under the item into a target of the item's
 * size, sbfx composites there, and the node copies the result back into the item's rectangle
 * (Qt's scissor, i.e. clip: true, applies to that copy). Either way sbfx's scene colour is a copy
 * of what lies under the item (its tone map needs it) and its depth is a texture cleared to 1
 * ("no surface": nothing in a 2D interface hides particles). Items drawn after this one (above
 * it in QML) are drawn over the effect: the node sets no DepthAwareRendering, so Qt draws every
 * item in order. The node puts back the GL state it changes (sbfx does so for its own), and a GL
 * error Qt left pending is handed back, as sbfx does (include/sbfx.h). */
#ifndef SBFX_QT_RENDER_NODE_H
#define SBFX_QT_RENDER_NODE_H

#include <QtCore/QElapsedTimer>
#include <QtCore/QString>
#include <QtGui/QMatrix4x4>
#include <QtQuick/QSGRenderNode>
#include <cstdint>
#include <functional>
#include <vector>

#include "sbfx.h"

/* What the item hands its node at each sync (SbfxItem::updatePaintNode). */
struct SbfxNodeSettings {
    unsigned generation = 0;   /* bumped by every change: the node copies the settings then */
    QString scene_path;        /* empty: the built-in explosion */
    double budget_ms = 0.0;
    unsigned module_generation = 0; /* bumped when the budget changes: the module is remade */
    unsigned scene_generation = 0;  /* bumped when the scene changes or is reloaded: the live
                                       module takes it over (sbfx_set_scene) */
    bool has_quality = false;  /* quality: a level for sbfx_set_quality */
    sbfx_quality quality = {};
    unsigned quality_generation = 0;
    bool has_view = false, has_projection = false;
    float view[16] = {}, projection[16] = {};
    double fixed_step = 0.0;   /* seconds per frame; 0: the real time between frames */
    bool running = true;
    std::function<void(int width, int height, double seconds, float view[16], float projection[16])> camera_hook;
    std::function<void(bool after)> render_observer;
};

struct SbfxNodeTrigger {
    QByteArray effect;
    float position[3];
};

/* What the node reports back at the next sync. */
struct SbfxNodeStatus {
    QString error;             /* the last failure, empty while all is well */
    int particles_alive = 0;
    int triggers_fired = 0;
    int scene_reloads = 0;     /* scenes the live module took over (sbfx_counters.scene_reloads) */
    int frames = 0;            /* frames in which sbfx drew */
    bool own_target = false;   /* the last frame drew through the item's own target */
    int width = 0, height = 0; /* the item's size in the render target's pixels */
    /* the lights the fire emitted after the last update (sbfx_emitted_lights), brightest first */
    std::vector<sbfx_point_light> emitted_lights;
};

class SbfxRenderNode : public QSGRenderNode
{
public:
    SbfxRenderNode() = default;
    ~SbfxRenderNode() override;

    void sync(const SbfxNodeSettings &settings, std::vector<SbfxNodeTrigger> &triggers, const QSizeF &item_size);
    const SbfxNodeStatus &status() const { return status_; }

    void prepare() override;
    void render(const RenderState *state) override;
    void releaseResources() override;
    StateFlags changedStates() const override;
    RenderingFlags flags() const override;
    QRectF rect() const override;

private:
    struct PixelRect {
        int x, y, width, height;
    };
    bool target_rect(const RenderState *state, PixelRect *out, bool *whole) const;
    bool ensure_module();
    bool ensure_targets(int width, int height, bool own_target);
    void release_targets();
    void advance();
    void camera(int width, int height, sbfx_frame *frame) const;
    void draw(const PixelRect &r, bool whole);
    bool load_scene(sbfx_scene **out);
    void reload_scene();
    void fail(const QString &message);

    SbfxNodeSettings settings_;
    std::vector<SbfxNodeTrigger> triggers_;
    QSizeF item_size_;
    QMatrix4x4 model_view_;
    SbfxNodeStatus status_;

    sbfx *fx_ = nullptr;
    QByteArray last_logged_error_; /* sbfx's last ERROR message (its log's user pointer) */
    sbfx_scene_camera scene_camera_ = {};
    unsigned made_generation_ = ~0u, set_quality_generation_ = 0, loaded_scene_generation_ = 0;
    bool idle_draws_nothing_ = false; /* an idle frame made no pass: no copy needed while idle */
    QElapsedTimer clock_;

    /* the item's own target, and the copies sbfx reads (GL names) */
    uint32_t scene_color_ = 0, scene_depth_ = 0, scene_fbo_ = 0, out_color_ = 0, out_fbo_ = 0;
    int target_width_ = 0, target_height_ = 0;
};

#endif
