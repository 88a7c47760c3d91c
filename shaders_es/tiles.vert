#version 300 es
// One rectangle of screen tiles per instance (src/render/tiles.c): the composite, the depth
// downsample, the low-res corners and, where sbfx owns the scene, the copy of the scene outside
// the tiles draw only the tiles a frame's particles can change. The rectangle is given in tiles
// (end exclusive); a tile is u_tile_size pixels of the target drawn into, and the grid's last
// column and row end at the target's edge, whatever is left of it there. Rectangles do not
// overlap: the composite blends. Passes need only gl_FragCoord: nothing is interpolated.
precision highp float;

layout(location = 0) in vec4 a_rect;  // first column, first row, end column, end row
uniform vec2 u_tile_size;             // a tile's side in the target's pixels
uniform vec2 u_tile_grid;             // columns, rows
uniform vec2 u_tile_target;           // the target's size in pixels

void main()
{
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec2 tile = mix(a_rect.xy, a_rect.zw, corner);
    vec2 pixel = vec2(tile.x < u_tile_grid.x ? tile.x * u_tile_size.x : u_tile_target.x,
                      tile.y < u_tile_grid.y ? tile.y * u_tile_size.y : u_tile_target.y);
    gl_Position = vec4(pixel / u_tile_target * 2.0 - 1.0, 0.0, 1.0);
}
