/* SbfxItem: sbfx inside a Qt Quick scene, between other QML items (docs/hosts/qt-quick.md).
 *
 *   import Sbfx 1.0
 *   SbfxItem { id: fx; anchors.fill: parent; scene: "scenes/barrage.cfg"; quality: "exact/4/nd" }
 *   ... fx.trigger("explosion", Qt.vector3d(0, 0, 0))
 *
 * Needs Qt Quick's OpenGL scene graph on an OpenGL ES 3.0 context: before QGuiApplication exists,
 * QSurfaceFormat::setDefaultFormat with OpenGLES 3.0 and QQuickWindow::setGraphicsApi(OpenGL)
 * (examples/qt-quick/main.cpp); then SbfxItem::registerQmlType().
 *
 * The item draws sbfx's effects over what lies under it in its rectangle; items above it in QML
 * are drawn over the effects. It renders into its own target of its size when it does not cover
 * the window, straight into Qt's framebuffer when it does (sbfx_render_node.h). It runs the
 * simulation on Qt's render thread, one sbfx_update per frame, and while `running` it asks for a
 * new frame after each. */
#ifndef SBFX_QT_ITEM_H
#define SBFX_QT_ITEM_H

#include <QtCore/QVariantList>
#include <QtGui/QMatrix4x4>
#include <QtGui/QVector3D>
#include <QtQuick/QQuickItem>
#include <functional>
#include <vector>

#include "sbfx_render_node.h"

class SbfxItem : public QQuickItem
{
    Q_OBJECT
    /* A scene file (docs/scene-format.md): a path or a file: URL; empty: the built-in explosion.
     * Changing it replaces the live module's scene (sbfx_set_scene): what both scenes use the
     * same way is kept (a change of numbers compiles no shader), the clock goes on, live effects
     * end and the new timeline starts. A file that does not load leaves the old scene playing,
     * the reason in `error`. (The budget's change makes the module again.) */
    Q_PROPERTY(QString scene READ scene WRITE setScene NOTIFY sceneChanged)
    /* A quality level (sbfx_quality_parse: "exact/4/nd", "spherical/8/bl/lod256"); empty: the
     * scene's. Switched between frames without losing the simulation. */
    Q_PROPERTY(QString quality READ quality WRITE setQuality NOTIFY qualityChanged)
    /* Frame budget in milliseconds of GPU time (docs/quality-and-budgets.md); 0: none. */
    Q_PROPERTY(double budget READ budget WRITE setBudget NOTIFY budgetChanged)
    /* World -> view and the perspective projection (column-major as OpenGL; QMatrix4x4 is).
     * Unset: the scene's camera (its `camera` group, else sbfx-play's default orbit) at the item's
     * aspect. A C++ camera hook (setCameraHook) takes precedence over both. */
    Q_PROPERTY(QMatrix4x4 viewMatrix READ viewMatrix WRITE setViewMatrix NOTIFY viewMatrixChanged)
    Q_PROPERTY(QMatrix4x4 projectionMatrix READ projectionMatrix WRITE setProjectionMatrix NOTIFY projectionMatrixChanged)
    /* Seconds of simulation per frame; 0 (default): the real time between frames. */
    Q_PROPERTY(double fixedStep READ fixedStep WRITE setFixedStep NOTIFY fixedStepChanged)
    /* false: the simulation stands still and the item asks for no frames of its own. */
    Q_PROPERTY(bool running READ running WRITE setRunning NOTIFY runningChanged)
    /* The last failure (scene, module, trigger, GL), empty while all is well. */
    Q_PROPERTY(QString error READ error NOTIFY errorChanged)
    /* Effect instances started since the module was made (sbfx_counters.triggers_fired). */
    Q_PROPERTY(int triggers READ triggers NOTIFY triggersChanged)
    /* The point lights the fire emitted in the last frame (sbfx_emitted_lights, brightest first),
     * for lighting the rest of the scene (docs/embedding.md "Fire lights your scene"): a list of
     * { position: vector3d (world), color: vector3d (I / pi, the scene's linear units), radius }.
     * Empty without live fire. One frame behind the picture (taken at the next sync). */
    Q_PROPERTY(QVariantList emittedLights READ emittedLights NOTIFY emittedLightsChanged)

public:
    explicit SbfxItem(QQuickItem *parent = nullptr);

    /* Registers the type as "import Sbfx 1.0" / SbfxItem. */
    static void registerQmlType();

    /* Starts an effect at a world position at the next frame (QML: trigger("explosion",
     * Qt.vector3d(0, 0, 0))). An unknown effect is reported in `error`; a trigger the full
     * particle pool refuses only in sbfx's log (qWarning), as sbfx_trigger does. */
    Q_INVOKABLE void trigger(const QString &effect, const QVector3D &position = QVector3D());
    /* Reads the scene file again into the live module (an editor saved it): as setting `scene`. */
    Q_INVOKABLE void reloadScene();

    /* Called on Qt's render thread before every frame with the item's size in pixels and
     * sbfx_time(): fills view and projection (column-major, include/sbfx.h conventions). */
    using CameraHook = std::function<void(int width, int height, double seconds, float view[16], float projection[16])>;
    void setCameraHook(CameraHook hook);
    /* Called on the render thread right before (after = false) and right after (true) the item's
     * GL work in each frame, with Qt's context current: checks and measurements (the tests). */
    using RenderObserver = std::function<void(bool after)>;
    void setRenderObserver(RenderObserver observer);
    /* What the render node reported at the last sync (particles alive, frames drawn, own target). */
    SbfxNodeStatus status() const { return status_; }

    QString scene() const { return settings_.scene_path; }
    void setScene(const QString &scene);
    QString quality() const { return quality_; }
    void setQuality(const QString &quality);
    double budget() const { return settings_.budget_ms; }
    void setBudget(double ms);
    QMatrix4x4 viewMatrix() const { return view_; }
    void setViewMatrix(const QMatrix4x4 &view);
    QMatrix4x4 projectionMatrix() const { return projection_; }
    void setProjectionMatrix(const QMatrix4x4 &projection);
    double fixedStep() const { return settings_.fixed_step; }
    void setFixedStep(double seconds);
    bool running() const { return settings_.running; }
    void setRunning(bool running);
    QString error() const { return error_; }
    int triggers() const { return status_.triggers_fired; }
    QVariantList emittedLights() const;
    /* The same for C++ hosts, as sbfx gives them. */
    const std::vector<sbfx_point_light> &emittedPointLights() const { return status_.emitted_lights; }

signals:
    void sceneChanged();
    void qualityChanged();
    void budgetChanged();
    void viewMatrixChanged();
    void projectionMatrixChanged();
    void fixedStepChanged();
    void runningChanged();
    void errorChanged();
    void triggersChanged();
    void emittedLightsChanged();

protected:
    QSGNode *updatePaintNode(QSGNode *node, UpdatePaintNodeData *) override;

private:
    void setError(const QString &error);
    void settings_changed();

    SbfxNodeSettings settings_;
    std::vector<SbfxNodeTrigger> triggers_;
    QString quality_, error_;
    QMatrix4x4 view_, projection_;
    SbfxNodeStatus status_;
};

#endif
