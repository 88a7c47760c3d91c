/* The screen tiles a frame's particles can change (render/render.h says what the room is for;
 * tiles.c; issue 33). Outside them the composite writes "no change" (transmittance 1, no light,
 * no shimmer offset), so the composite, the depth downsample and the low-res corners draw only
 * them: instanced rectangles of tiles (tiles.vert) from a buffer made at load. Where sbfx owns
 * the scene (post effects follow the composite), the scene is copied to the rest.
 *
 * A tile is SBFX_TILE_SIZE pixels square (docs/gpus.md, "Tiles": measured); a frame wider or
 * taller than SBFX_TILE_GRID of them takes tiles twice as large, as often as it must. The
 * particles' footprints are their quads as particle.vert draws them, bounded on the CPU in
 * double with a margin for the GPU's float; the tiles are those footprints grown by what the
 * composite's upsampling reads (the low-res texel beside each pixel) and what the corners
 * need of the depth downsample (one texel more). */
#ifndef SBFX_RENDER_TILES_H
#define SBFX_RENDER_TILES_H

#include <GLES3/gl3.h>
#include <stdbool.h>
#include <stdint.h>

#define SBFX_TILE_SIZE 32    /* pixels, a power of two: a multiple of every target divisor (1, 2, 4, 8) */
#define SBFX_TILE_GRID 256   /* tiles per axis at most */
#define SBFX_TILE_RECTS 2048 /* rectangles per frame, the composite's and the copy's together */

/* A rectangle of tiles: first column and row, end column and row (exclusive). */
typedef struct sbfx_tile_rect {
    uint16_t x0, y0, x1, y1;
} sbfx_tile_rect;

typedef struct sbfx_tiles {
    /* settings (tests and the bench; never a public mode) */
    bool full_screen;        /* the frame as before tiles: the composite and the depth passes over
                                every tile, each particle's whole rectangle (particle.vert), the
                                velocity blur's gather over every block (post.c): the
                                picture's control, the bench's "before" */
    int size_wanted;         /* pixels per tile (0: SBFX_TILE_SIZE), rounded up to a power of two >= 8 */
    /* the frame's */
    int size, shift;         /* pixels per tile, its log2 */
    int columns, rows;       /* the grid over the output */
    int marked;              /* tiles marked */
    long long pixels;        /* output pixels the composite covers */
    int inside, outside;     /* rects[0, inside): the composite's; then the scene copy's */
    uint8_t mask[SBFX_TILE_GRID * SBFX_TILE_GRID];
    sbfx_tile_rect rects[SBFX_TILE_RECTS];
    /* GL objects made at load */
    GLuint vao, buffer;
} sbfx_tiles;

#endif
