#version 300 es
// Early termination (src/render/terminate.c; docs/gpus.md "Front to back, and early
// termination"): at a checkpoint of the particles' front-to-back draw, over the particles'
// tiles at the particle target's resolution, writes depth 0 where the transmittance accumulated
// so far is below u_epsilon. The later particles are drawn at window depth 0.5 or 0 with GL_LESS
// against the target's depth (cleared to 1): there they fail the early depth test and are never
// shaded. Elsewhere nothing is written (discard). Drawn into a framebuffer that holds only that
// depth, so reading the particles' colour is no feedback loop.
precision highp float;
precision highp sampler2D;

uniform mediump sampler2D u_particles;   // low-res: premultiplied light, transmittance
uniform float u_epsilon;                 // what may be left behind (terminate.c derives it)

void main()
{
    mediump float transmittance = texelFetch(u_particles, ivec2(gl_FragCoord.xy), 0).a;
    if (!(transmittance < u_epsilon)) discard;   // NaN or enough light through: keep drawing
    gl_FragDepth = 0.0;
}
