/* PNG files of RGBA8 images through libpng, and contact sheets of many frames.
 *
 * Pixels are tightly packed RGBA8 rows (width * 4 bytes). GL reads the framebuffer bottom row
 * first, so every writer takes `bottom_up`: true means the first row in memory is the bottom
 * row of the picture (glReadPixels order), false means it is the top row.
 * Functions return 0 or a negative errno code with a message in err (which names the file). */
#ifndef SBFX_PNG_IO_H
#define SBFX_PNG_IO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

int png_write_rgba(const char *path, const uint8_t *rgba, int width, int height, bool bottom_up,
                   char *err, size_t n);

/* A writer for many images of one size (a headless run's frames): its table of row pointers is
 * made once, so writing a frame allocates nothing of the caller's (libpng and zlib allocate
 * their own state per file). */
struct png_writer {
    const uint8_t **rows;            /* height pointers, set for each image */
    int width, height;
};
int png_writer_init(struct png_writer *w, int width, int height, char *err, size_t n);
int png_writer_write(struct png_writer *w, const char *path, const uint8_t *rgba, bool bottom_up, char *err,
                     size_t n);
void png_writer_free(struct png_writer *w);

/* Reads any PNG converted to RGBA8, top row first, into a malloc'ed buffer (*out, free() it). */
int png_read_rgba(const char *path, uint8_t **out, int *width, int *height, char *err, size_t n);

/* A grid of frames, each downscaled with a box filter, filled frame by frame so that a long
 * run never holds all its frames in memory. Cells are laid out left to right, top to bottom,
 * in the order frames are added, with a small dark gap between them. */
struct contact_sheet {
    uint8_t *pixels;                 /* RGBA8, top row first */
    int width, height;               /* of the whole sheet */
    int columns, rows;
    int cell_width, cell_height;     /* of one downscaled frame */
    int frame_width, frame_height;   /* of the frames added */
    int count, capacity;             /* frames added so far, frames planned */
};

/* Plans a sheet for `frames` frames of frame_width x frame_height: about square in cells,
 * each frame shrunk by an integer factor so a cell is at most max_cell_width wide and the
 * whole sheet stays within 4096 x 4096 pixels. */
int contact_sheet_init(struct contact_sheet *sheet, int frames, int frame_width, int frame_height,
                       int max_cell_width, char *err, size_t n);
/* Adds the next frame (frame_width x frame_height). -ENOSPC once the planned count is full. */
int contact_sheet_add(struct contact_sheet *sheet, const uint8_t *rgba, bool bottom_up);
int contact_sheet_write(const struct contact_sheet *sheet, const char *path, char *err, size_t n);
void contact_sheet_free(struct contact_sheet *sheet);

/* All in one: count frames of width x height written as one contact sheet PNG. */
int png_write_contact_sheet(const char *path, const uint8_t *const *frames, int count, int width,
                            int height, bool bottom_up, int max_cell_width, char *err, size_t n);

#endif
