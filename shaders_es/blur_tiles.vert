#version 300 es
// The velocity blur's blocks of one class (tile_class.frag), one instance a block, in rows: the
// gather draws the moving blocks, a copy the still ones, and each pixel of the output is drawn
// once. A block of the other class collapses to a point outside the view: it shades nothing.
// The grid's last column and row end at the output's edge. Passes need only gl_FragCoord.
precision highp float;
precision highp sampler2D;

uniform sampler2D u_classes;     // a texel a block: 0 still, 1 moving
uniform float u_class;           // the class this draw covers
uniform int u_block_columns;
uniform float u_block_size;      // a block's side in pixels
uniform vec2 u_target;           // the output's size in pixels

void main()
{
    ivec2 block = ivec2(gl_InstanceID % u_block_columns, gl_InstanceID / u_block_columns);
    if (abs(texelFetch(u_classes, block, 0).r - u_class) > 0.25) {
        gl_Position = vec4(2.0, 2.0, 0.0, 1.0);
        return;
    }
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec2 pixel = min((vec2(block) + corner) * u_block_size, u_target);
    gl_Position = vec4(pixel / u_target * 2.0 - 1.0, 0.0, 1.0);
}
