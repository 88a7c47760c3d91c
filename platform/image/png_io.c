/* PNG writing and reading with libpng; contact sheets. See png_io.h. */
#include "image/png_io.h"

#include <errno.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define SHEET_MAX_SIZE 4096 /* per side: bounds the sheet's memory (64 MiB) for any run */
#define SHEET_GAP 2          /* pixels between cells */
static const uint8_t sheet_background[4] = {24, 24, 24, 255};

/* Where libpng's error callback leaves its message before it jumps back to our setjmp. */
struct png_error_sink {
    char *err;
    size_t n;
    const char *path;
};

static void on_png_error(png_structp png, png_const_charp message)
{
    struct png_error_sink *sink = png_get_error_ptr(png);
    if (sink && sink->err && sink->n)
        snprintf(sink->err, sink->n, "%s: libpng: %s", sink->path, message);
    png_longjmp(png, 1);
}

static void on_png_warning(png_structp png, png_const_charp message)
{
    (void)png;
    (void)message; /* warnings (e.g. about ancillary chunks) do not make a file unusable */
}

/* Row pointers are set up before setjmp so nothing that libpng may jump over needs to be
 * volatile. */
static void point_rows(const uint8_t **rows, const uint8_t *rgba, int width, int height, bool bottom_up)
{
    size_t stride = (size_t)width * 4;
    for (int y = 0; y < height; y++) {
        int src = bottom_up ? height - 1 - y : y;
        rows[y] = rgba + (size_t)src * stride;
    }
}

static int encode(FILE *f, const uint8_t **rows, int width, int height, struct png_error_sink *sink)
{
    png_infop info = NULL;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, sink, on_png_error,
                                              on_png_warning);
    if (!png) goto err_png;
    info = png_create_info_struct(png);
    if (!info) goto err_info;
    if (setjmp(png_jmpbuf(png))) goto err_info; /* the sink holds libpng's message */
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8, PNG_COLOR_TYPE_RGB_ALPHA,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    /* Level 3 is much faster than zlib's default and barely larger on rendered frames, and
     * the player's per-frame time includes this. */
    png_set_compression_level(png, 3);
    png_write_info(png, info);
    png_write_image(png, (png_bytepp)rows); /* libpng only reads them */
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return 0;

err_info:
    png_destroy_write_struct(&png, &info);
    return -EIO;
err_png:
    snprintf(sink->err, sink->n, "%s: libpng: out of memory", sink->path);
    return -ENOMEM;
}

/* Leaves no truncated image behind; only ever a regular file, never a device node such as
 * /dev/full that the caller may have named. */
static void remove_partial(const char *path)
{
    struct stat st;
    if (stat(path, &st) == 0 && S_ISREG(st.st_mode)) remove(path);
}

int png_writer_init(struct png_writer *w, int width, int height, char *err, size_t n)
{
    *w = (struct png_writer){.width = width, .height = height};
    if (width <= 0 || height <= 0) {
        snprintf(err, n, "png_writer_init: invalid size %dx%d", width, height);
        return -EINVAL;
    }
    w->rows = malloc((size_t)height * sizeof(*w->rows));
    if (!w->rows) {
        snprintf(err, n, "PNG writer for %dx%d: out of memory", width, height);
        return -ENOMEM;
    }
    return 0;
}

void png_writer_free(struct png_writer *w)
{
    free(w->rows);
    w->rows = NULL;
}

int png_writer_write(struct png_writer *w, const char *path, const uint8_t *rgba, bool bottom_up, char *err,
                     size_t n)
{
    if (!path || !rgba || !w->rows) {
        snprintf(err, n, "png_writer_write: invalid arguments");
        return -EINVAL;
    }
    struct png_error_sink sink = {err, n, path};
    point_rows(w->rows, rgba, w->width, w->height, bottom_up);
    FILE *f = fopen(path, "wb");
    if (!f) {
        int rc = -errno;
        snprintf(err, n, "%s: cannot create: %s", path, strerror(errno));
        return rc;
    }
    int rc = encode(f, w->rows, w->width, w->height, &sink);
    if (fclose(f) != 0 && rc == 0) { /* a full disk shows up here, at the last flush */
        rc = -errno;
        snprintf(err, n, "%s: write failed: %s", path, strerror(errno));
    }
    if (rc) remove_partial(path);
    return rc;
}

int png_write_rgba(const char *path, const uint8_t *rgba, int width, int height, bool bottom_up,
                   char *err, size_t n)
{
    if (!path || !rgba || width <= 0 || height <= 0) {
        snprintf(err, n, "png_write_rgba: invalid arguments (%dx%d)", width, height);
        return -EINVAL;
    }
    struct png_writer w;
    int rc = png_writer_init(&w, width, height, err, n);
    if (rc == 0) rc = png_writer_write(&w, path, rgba, bottom_up, err, n);
    png_writer_free(&w);
    return rc;
}

int png_read_rgba(const char *path, uint8_t **out, int *width, int *height, char *err, size_t n)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        int rc = -errno;
        snprintf(err, n, "%s: cannot open: %s", path, strerror(errno));
        return rc;
    }
    png_image image;
    memset(&image, 0, sizeof(image));
    image.version = PNG_IMAGE_VERSION;
    int rc = 0;
    uint8_t *pixels = NULL;
    if (!png_image_begin_read_from_stdio(&image, f)) {
        snprintf(err, n, "%s: libpng: %s", path, image.message);
        rc = -EIO;
        goto err_file;
    }
    image.format = PNG_FORMAT_RGBA;
    pixels = malloc(PNG_IMAGE_SIZE(image));
    if (!pixels) {
        snprintf(err, n, "%s: out of memory", path);
        rc = -ENOMEM;
        goto err_image;
    }
    if (!png_image_finish_read(&image, NULL, pixels, 0, NULL)) {
        snprintf(err, n, "%s: libpng: %s", path, image.message);
        rc = -EIO;
        goto err_pixels;
    }
    *out = pixels;
    *width = (int)image.width;
    *height = (int)image.height;
    fclose(f);
    return 0;

err_pixels:
    free(pixels);
err_image:
    png_image_free(&image);
err_file:
    fclose(f);
    return rc;
}

/* ---- contact sheet -------------------------------------------------------------------- */

/* The widest cell that lets `cells` cells and their gaps fit in SHEET_MAX_SIZE. */
static int cell_fit(int cells)
{
    int fit = (SHEET_MAX_SIZE - SHEET_GAP * (cells + 1)) / cells;
    return fit > 0 ? fit : 1;
}

int contact_sheet_init(struct contact_sheet *sheet, int frames, int frame_width, int frame_height,
                       int max_cell_width, char *err, size_t n)
{
    memset(sheet, 0, sizeof(*sheet));
    if (frames < 1 || frame_width < 1 || frame_height < 1 || max_cell_width < 1) {
        snprintf(err, n, "contact sheet: invalid plan (%d frames of %dx%d)", frames, frame_width,
                 frame_height);
        return -EINVAL;
    }
    int columns = (int)ceil(sqrt((double)frames));
    int rows = (frames + columns - 1) / columns;
    int fit_width = max_cell_width < cell_fit(columns) ? max_cell_width : cell_fit(columns);
    /* An integer factor makes every box the same size: no moiré in the grid pattern. */
    int factor = (frame_width + fit_width - 1) / fit_width;
    int factor_h = (frame_height + cell_fit(rows) - 1) / cell_fit(rows);
    if (factor_h > factor) factor = factor_h;
    sheet->cell_width = frame_width / factor > 0 ? frame_width / factor : 1;
    sheet->cell_height = frame_height / factor > 0 ? frame_height / factor : 1;
    sheet->columns = columns;
    sheet->rows = rows;
    sheet->width = columns * sheet->cell_width + (columns + 1) * SHEET_GAP;
    sheet->height = rows * sheet->cell_height + (rows + 1) * SHEET_GAP;
    sheet->frame_width = frame_width;
    sheet->frame_height = frame_height;
    sheet->capacity = frames;
    size_t bytes = (size_t)sheet->width * (size_t)sheet->height * 4;
    sheet->pixels = malloc(bytes);
    if (!sheet->pixels) {
        snprintf(err, n, "contact sheet: out of memory (%zu bytes)", bytes);
        return -ENOMEM;
    }
    for (size_t i = 0; i < bytes; i += 4) memcpy(sheet->pixels + i, sheet_background, 4);
    return 0;
}

/* Mean of the source pixels whose box maps onto cell pixel (cx, cy). */
static void box_average(const struct contact_sheet *sheet, const uint8_t *rgba, bool bottom_up,
                        int cx, int cy, uint8_t out[4])
{
    int fw = sheet->frame_width, fh = sheet->frame_height;
    int x0 = (int)((long long)cx * fw / sheet->cell_width);
    int x1 = (int)((long long)(cx + 1) * fw / sheet->cell_width);
    int y0 = (int)((long long)cy * fh / sheet->cell_height);
    int y1 = (int)((long long)(cy + 1) * fh / sheet->cell_height);
    if (x1 <= x0) x1 = x0 + 1;
    if (y1 <= y0) y1 = y0 + 1;
    unsigned long sum[4] = {0, 0, 0, 0};
    for (int y = y0; y < y1; y++) {
        int row = bottom_up ? fh - 1 - y : y;
        const uint8_t *p = rgba + ((size_t)row * fw + x0) * 4;
        for (int x = x0; x < x1; x++, p += 4)
            for (int c = 0; c < 4; c++) sum[c] += p[c];
    }
    unsigned long count = (unsigned long)(x1 - x0) * (unsigned long)(y1 - y0);
    for (int c = 0; c < 4; c++) out[c] = (uint8_t)((sum[c] + count / 2) / count);
}

int contact_sheet_add(struct contact_sheet *sheet, const uint8_t *rgba, bool bottom_up)
{
    if (!sheet->pixels || !rgba) return -EINVAL;
    if (sheet->count >= sheet->capacity) return -ENOSPC;
    int column = sheet->count % sheet->columns, row = sheet->count / sheet->columns;
    int left = SHEET_GAP + column * (sheet->cell_width + SHEET_GAP);
    int top = SHEET_GAP + row * (sheet->cell_height + SHEET_GAP);
    for (int cy = 0; cy < sheet->cell_height; cy++) {
        uint8_t *dst = sheet->pixels + ((size_t)(top + cy) * sheet->width + left) * 4;
        for (int cx = 0; cx < sheet->cell_width; cx++, dst += 4)
            box_average(sheet, rgba, bottom_up, cx, cy, dst);
    }
    sheet->count++;
    return 0;
}

int contact_sheet_write(const struct contact_sheet *sheet, const char *path, char *err, size_t n)
{
    if (!sheet->pixels) {
        snprintf(err, n, "%s: contact sheet was not initialised", path);
        return -EINVAL;
    }
    return png_write_rgba(path, sheet->pixels, sheet->width, sheet->height, false, err, n);
}

void contact_sheet_free(struct contact_sheet *sheet)
{
    if (!sheet) return;
    free(sheet->pixels);
    memset(sheet, 0, sizeof(*sheet));
}

int png_write_contact_sheet(const char *path, const uint8_t *const *frames, int count, int width,
                            int height, bool bottom_up, int max_cell_width, char *err, size_t n)
{
    struct contact_sheet sheet;
    int rc = contact_sheet_init(&sheet, count, width, height, max_cell_width, err, n);
    if (rc) return rc;
    for (int i = 0; i < count && rc == 0; i++) {
        rc = contact_sheet_add(&sheet, frames[i], bottom_up);
        if (rc) snprintf(err, n, "%s: frame %d: cannot add to the contact sheet", path, i);
    }
    if (rc == 0) rc = contact_sheet_write(&sheet, path, err, n);
    contact_sheet_free(&sheet);
    return rc;
}
