// sbfx between Qt Quick items (docs/hosts/qt-quick.md): a background, the effects over it, and
// a title bar and a button drawn over the effects. Space, the button or the timer: an explosion.
import QtQuick
import Sbfx 1.0

Rectangle {
    id: root
    width: 960
    height: 540
    focus: true
    gradient: Gradient {
        GradientStop { position: 0.0; color: "#3a5f8a" }
        GradientStop { position: 0.6; color: "#1c2c40" }
        GradientStop { position: 1.0; color: "#3b3328" }
    }

    function explode() { fx.trigger(effectName, Qt.vector3d(0, 0, 0)) }
    Keys.onSpacePressed: explode()

    SbfxItem {
        id: fx
        objectName: "fx"
        anchors.fill: parent
        anchors.topMargin: 48
        scene: sceneFile
        onErrorChanged: console.warn("sbfx:", error)
    }

    Timer {
        interval: triggerEvery
        running: triggerEvery > 0
        repeat: true
        triggeredOnStart: true
        onTriggered: root.explode()
    }

    Rectangle {
        anchors { left: parent.left; right: parent.right; top: parent.top }
        height: 48
        color: "#101820"
        Text {
            anchors.verticalCenter: parent.verticalCenter
            x: 16
            color: "white"
            font.pixelSize: 18
            text: "sbfx in Qt Quick: " + fx.triggers + " explosions"
        }
    }

    Rectangle {
        id: button
        anchors { right: parent.right; bottom: parent.bottom; margins: 24 }
        width: 140
        height: 44
        radius: 6
        color: area.pressed ? "#d0d0d0" : "#f0f0f0"
        Text { anchors.centerIn: parent; text: "Explode"; font.pixelSize: 18 }
        MouseArea { id: area; anchors.fill: parent; onClicked: root.explode() }
    }
}
