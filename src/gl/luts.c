/* The textures the particle shader samples, uploaded once at load and only for media the
 * loaded effects use: the scene's lookup tables (computed on the CPU in double,
 * scene/scene_tables.c), the detail volume (tables/detail_gen.c; stored as half floats, _Float16
 * rounds to nearest even) and lit media's smoke textures (tables/smoke_texture.c). And the
 * detail volume's public entry points: its size, its procedural values, the slices a host
 * pushes (a camera's, a clip's). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "base/float16.h"
#include "gl/gl.h"

/* ---- the scene's tables (scene/scene_tables.c builds them) ---------------------------------- */

static GLuint make_table_texture(sbfx *fx, GLenum internal, GLenum format, int w, int h, const float *texels)
{
    /* texelFetch only: NEAREST keeps the texture complete (float is not filterable in ES 3.0) */
    GLuint tex = sbfx_texture_create(fx, GL_TEXTURE_2D, GL_NEAREST, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, format, GL_FLOAT, texels);
    fx->counters.gpu_bytes += (size_t)w * h * (format == GL_RGBA ? 16 : 4);
    return tex;
}

sbfx_result sbfx_tables_upload_blackbody(sbfx *fx)
{
    fx->gl->blackbody_texture = make_table_texture(fx, GL_RGBA32F, GL_RGBA, SBFX_BLACKBODY_SIZE, 1, fx->tables->blackbody);
    return sbfx_gl_check(fx, "uploading the black-body table") ? SBFX_OK : SBFX_ERR_GL;
}

sbfx_result sbfx_tables_upload_phase(sbfx *fx)
{
    fx->gl->phase_texture = make_table_texture(fx, GL_R32F, GL_RED, SBFX_PHASE_SIZE, SBFX_MEDIUM_COUNT, fx->tables->phase);
    return sbfx_gl_check(fx, "uploading the phase-function table") ? SBFX_OK : SBFX_ERR_GL;
}

/* The textures exist when a declared level samples them; a later first use uploads them from the
 * CPU copy (gl/levels.c). */
static sbfx_result upload_tables(sbfx *fx)
{
    sbfx_result r = SBFX_OK;
    if (sbfx_declared_any(fx, sbfx_quality_uses_blackbody_table)) r = sbfx_tables_upload_blackbody(fx);
    if (r == SBFX_OK && sbfx_declared_any(fx, sbfx_quality_uses_phase_table)) r = sbfx_tables_upload_phase(fx);
    return r;
}

/* The shader's mappings (particle.frag's blackbody() and phase()): position in entries of
 * 1/T, and the coordinate of sbfx_phase_coordinate() folded into scale and offset. */
void sbfx_tables_bind(const sbfx *fx, const sbfx_program *p, sbfx_medium m)
{
    const sbfx_tables *t = fx->tables;
    /* only the tables that exist: their units are the ones the frame saves (render/frame.c) */
    if (fx->gl->phase_texture) sbfx_bind_texture(SBFX_UNIT_PHASE, GL_TEXTURE_2D, fx->gl->phase_texture, 0);
    if (fx->gl->blackbody_texture)
        sbfx_bind_texture(SBFX_UNIT_BLACKBODY, GL_TEXTURE_2D, fx->gl->blackbody_texture, 0);
    glUniform1i(p->phase_lut, SBFX_UNIT_PHASE);
    glUniform1i(p->blackbody, SBFX_UNIT_BLACKBODY);
    double lo = t->blackbody_lo > 0 ? t->blackbody_lo : 1.0, hi = t->blackbody_hi > lo ? t->blackbody_hi : 2.0 * lo;
    glUniform3f(p->blackbody_map, (float)(1.0 / hi), (float)((SBFX_BLACKBODY_SIZE - 1) / (1.0 / lo - 1.0 / hi)),
                (float)(SBFX_BLACKBODY_SIZE - 2));
    double g = fx->scene->media[m].phase_g, a = fmin(fabs(g), SBFX_PHASE_G_MAX);
    double back = (1.0 + a) * (1.0 + a), peak = (1.0 - a) * (1.0 - a);
    bool warp = a >= SBFX_PHASE_WARP_MIN_G;
    double k = warp ? 1.0 / log(peak / back) : 0.0;
    glUniform4f(p->phase_warp, g < 0.0 ? -1.0f : 1.0f, (float)peak, warp ? (float)(2.0 * a) : 0.0f, (float)k);
    glUniform2f(p->phase_shift, (float)(-log(back) * k), (float)(SBFX_PHASE_SIZE - 1));
    glUniform1i(p->phase_row, (GLint)m);
    /* the analytic phase's constants (particle.frag phase()), with g as given */
    double ga = fabs(g);
    glUniform4f(p->phase_analytic, (float)(3.0 * (1.0 - g * g) / (8.0 * M_PI * (2.0 + g * g))), (float)((1.0 - ga) * (1.0 - ga)),
                (float)(2.0 * ga), g < 0.0 ? -1.0f : 1.0f);
}

/* ---- the detail volume and the smoke textures ------------------------------------------------ */

/* The procedural volumes are made from the seed and sizes alone: a reload that keeps them takes
 * the texture over (generating 128 x 128 x 32 values is most of a load's CPU time). */
static uint64_t generated_key(const char *what, int a, int b, int c, uint32_t seed)
{
    int recipe[4] = {a, b, c, (int)seed};
    return sbfx_hash64(sbfx_hash64(0, what, strlen(what)), recipe, sizeof(recipe));
}

static bool borrow_texture(sbfx *fx, uint64_t key, GLuint *texture, size_t bytes)
{
    if (!sbfx_object_borrow(fx, SBFX_OBJECT_TEXTURE, key, texture, NULL)) return false;
    fx->counters.textures++;
    fx->counters.gpu_bytes += bytes;
    return true;
}

static sbfx_result make_detail(sbfx *fx, int size, int frames, size_t n);

/* The fire's light follows a volume the host writes (a camera's or a clip's slices): per-slice
 * statistics, kept only where the scene's detail is live or a clip and its fire emits. */
static bool wants_slice_statistics(const sbfx *fx)
{
    const sbfx_medium_params *fire = &fx->scene->media[SBFX_FIRE];
    return (sbfx_wants_live_detail(fx) || sbfx_detail_clip(fx)) && fx->scene->uses_medium[SBFX_FIRE] &&
           (fire->emissivity > 0.0f || fire->emission_scale > 0.0f);
}

/* A volume taken over from the live module on a reload holds what it was made with: so do its
 * statistics. Without the donor's quantiles (it had no fire) or per-slice ones where they are
 * wanted, it is made again. */
static bool borrow_detail(sbfx *fx, uint64_t key, size_t bytes)
{
    const sbfx *donor = fx->gl->donor;
    if (!donor || (fx->scene->uses_medium[SBFX_FIRE] && !donor->sim->fire_detail_made)) return false;
    if (fx->sim->fire_slice_histograms && !donor->sim->fire_slice_histograms) return false;
    if (!borrow_texture(fx, key, &fx->gl->detail_texture, bytes)) return false;
    memcpy(fx->sim->fire_detail, donor->sim->fire_detail, sizeof(fx->sim->fire_detail));
    fx->sim->fire_detail_made = donor->sim->fire_detail_made;
    if (fx->sim->fire_slice_histograms)
        memcpy(fx->sim->fire_slice_histograms, donor->sim->fire_slice_histograms,
               (size_t)fx->scene->desc.detail_frames * SBFX_FIRE_DETAIL_BINS * sizeof(uint16_t));
    return true;
}

static sbfx_result upload_detail(sbfx *fx)
{
    int size = fx->scene->desc.detail_size, frames = fx->scene->desc.detail_frames;
    size_t n = (size_t)size * size * frames;
    bool r32f = fx->scene->desc.detail_format == SBFX_DETAIL_R32F;
    uint64_t key = generated_key("detail", size, frames, r32f, fx->scene->desc.seed);
    if (r32f && !(fx->gl->detail_scratch = sbfx_calloc(fx, (size_t)size * size, sizeof(float))))
        return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "out of memory");
    if (wants_slice_statistics(fx) &&
        !(fx->sim->fire_slice_histograms = sbfx_calloc(fx, (size_t)frames * SBFX_FIRE_DETAIL_BINS, sizeof(uint16_t))))
        return sbfx_fail(fx, SBFX_ERR_OUT_OF_MEMORY, "out of memory");
    if (borrow_detail(fx, key, n * (r32f ? 4 : 2))) return SBFX_OK;
    sbfx_result r = make_detail(fx, size, frames, n);
    if (r == SBFX_OK) sbfx_object_note(fx, SBFX_OBJECT_TEXTURE, fx->gl->detail_texture, key, NULL);
    return r;
}

static sbfx_result make_detail(sbfx *fx, int size, int frames, size_t n)
{
    float *values = sbfx_calloc(fx, n, sizeof(float));
    uint16_t *texels = sbfx_calloc(fx, n, sizeof(uint16_t)); /* half floats' bits */
    sbfx_result r = SBFX_ERR_OUT_OF_MEMORY;
    if (values && texels) {
        sbfx_detail_generate(size, frames, fx->scene->desc.seed, values);
        if (fx->scene->uses_medium[SBFX_FIRE]) { /* what fire's light averages over: fire's alone */
            sbfx_fire_detail_levels(values, size, frames, fx->sim->fire_detail);
            fx->sim->fire_detail_made = true;
        }
        sbfx_floats_to_halves(values, texels, n);
        for (int s = 0; fx->sim->fire_slice_histograms && s < frames; s++)
            sbfx_fire_slice_histogram(&texels[(size_t)s * size * size], size,
                                      &fx->sim->fire_slice_histograms[(size_t)s * SBFX_FIRE_DETAIL_BINS]);
        if (fx->scene->desc.detail_format == SBFX_DETAIL_R32F) {
            /* R32F is not filterable in core ES 3.0: sampled NEAREST, which is its cost. */
            fx->gl->detail_texture = sbfx_texture_create(fx, GL_TEXTURE_3D, GL_NEAREST, GL_REPEAT);
            glTexImage3D(GL_TEXTURE_3D, 0, GL_R32F, size, size, frames, 0, GL_RED, GL_FLOAT, values);
            fx->counters.gpu_bytes += n * 4;
        } else {
            /* R16F: filterable in core ES 3.0, REPEAT so windows and time wrap. */
            fx->gl->detail_texture = sbfx_texture_create(fx, GL_TEXTURE_3D, GL_LINEAR, GL_REPEAT);
            glTexImage3D(GL_TEXTURE_3D, 0, GL_R16F, size, size, frames, 0, GL_RED, GL_HALF_FLOAT, texels);
            fx->counters.gpu_bytes += n * 2;
        }
        r = sbfx_gl_check(fx, "uploading the detail volume") ? SBFX_OK : SBFX_ERR_GL;
    }
    sbfx_free(fx, values);
    sbfx_free(fx, texels);
    return r;
}

/* A lit medium's smoke textures (tables.h): 2 RGBA8 layers per variant in one array, so a
 * particle picks its variant by layer, all under one binding. Made at load from the seed. */
static sbfx_result make_smoke(sbfx *fx, sbfx_medium m);

static sbfx_result upload_smoke(sbfx *fx, sbfx_medium m)
{
    const sbfx_medium_params *mp = &fx->scene->media[m];
    uint32_t seed = sbfx_smoke_texture_seed(fx->scene->desc.seed, m);
    uint64_t key = generated_key("smoke", mp->texture_size, mp->texture_variants, 0, seed);
    if (borrow_texture(fx, key, &fx->gl->smoke_texture[m], sbfx_smoke_texture_bytes(mp->texture_size,
                                                                                   mp->texture_variants)))
        return SBFX_OK;
    sbfx_result r = make_smoke(fx, m);
    if (r == SBFX_OK) sbfx_object_note(fx, SBFX_OBJECT_TEXTURE, fx->gl->smoke_texture[m], key, NULL);
    return r;
}

static sbfx_result make_smoke(sbfx *fx, sbfx_medium m)
{
    const sbfx_medium_params *mp = &fx->scene->media[m];
    int size = mp->texture_size, variants = mp->texture_variants;
    size_t bytes = sbfx_smoke_texture_bytes(size, variants);
    uint8_t *texels = sbfx_calloc(fx, bytes, 1);
    float *scratch = sbfx_calloc(fx, sbfx_smoke_scratch_floats(size), sizeof(float));
    sbfx_result r = SBFX_ERR_OUT_OF_MEMORY;
    if (texels && scratch) {
        r = SBFX_ERR_INVALID_ARGUMENT;
        if (sbfx_smoke_texture_generate(size, variants, sbfx_smoke_texture_seed(fx->scene->desc.seed, m), texels,
                                        scratch) != 0) {
            sbfx_fail(fx, r, "smoke texture %dx%d x %d variants is out of range", size, size, variants);
            goto out;
        }
        /* CLAMP_TO_EDGE: the puff's height is 0 at the border, a lit particle's rim must not
         * pick up the opposite side. Mipmapped: small particles would alias the normal map. */
        int layers = SBFX_SMOKE_LAYERS_PER_VARIANT * variants, levels = sbfx_smoke_texture_levels(size);
        fx->gl->smoke_texture[m] = sbfx_texture_create(fx, GL_TEXTURE_2D_ARRAY, GL_LINEAR, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, levels - 1);
        for (int level = 0; level < levels; level++)
            glTexImage3D(GL_TEXTURE_2D_ARRAY, level, GL_RGBA8, size >> level, size >> level, layers, 0, GL_RGBA,
                         GL_UNSIGNED_BYTE, texels + sbfx_smoke_level_offset(size, layers, level));
        fx->counters.gpu_bytes += bytes;
        r = sbfx_gl_check(fx, "uploading the smoke texture array") ? SBFX_OK : SBFX_ERR_GL;
    }
out:
    sbfx_free(fx, texels);
    sbfx_free(fx, scratch);
    return r;
}

static bool lit(const sbfx *fx, sbfx_medium m)
{
    return fx->scene->uses_medium[m] && fx->scene->media[m].lit && fx->scene->media[m].albedo > 0;
}

static bool any_detail(const sbfx *fx)
{
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
        if (fx->scene->uses_medium[m] && fx->scene->media[m].detail_strength > 0) return true;
    return false;
}

sbfx_result sbfx_luts_create(sbfx *fx)
{
    sbfx_result r = SBFX_OK;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if ((r = upload_tables(fx)) != SBFX_OK) return r;
    if (any_detail(fx) && (r = upload_detail(fx)) != SBFX_OK) return r;
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
        if (lit(fx, (sbfx_medium)m) && (r = upload_smoke(fx, (sbfx_medium)m)) != SBFX_OK) return r;
    return SBFX_OK;
}

void sbfx_luts_destroy(sbfx *fx)
{
    GLuint textures[] = {fx->gl->blackbody_texture, fx->gl->phase_texture};
    glDeleteTextures((GLsizei)ARRAY_SIZE(textures), textures);
    fx->gl->blackbody_texture = fx->gl->phase_texture = 0;
    sbfx_texture_delete(fx, &fx->gl->detail_texture);
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++) sbfx_texture_delete(fx, &fx->gl->smoke_texture[m]);
    sbfx_free(fx, fx->gl->detail_scratch);
    sbfx_free(fx, fx->sim->fire_slice_histograms);
    fx->gl->detail_scratch = NULL;
    fx->sim->fire_slice_histograms = NULL;
    fx->gl->detail_texture = 0;
}

void sbfx_detail_dimensions(const sbfx *fx, int *size, int *frames)
{
    if (size) *size = fx ? fx->scene->desc.detail_size : 0;
    if (frames) *frames = fx ? fx->scene->desc.detail_frames : 0;
}

bool sbfx_wants_live_detail(const sbfx *fx)
{
    if (!fx) return false;
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
        if (fx->scene->uses_medium[m] && fx->scene->media[m].live_detail && fx->scene->media[m].detail_strength > 0) return true;
    return false;
}

const char *sbfx_detail_clip(const sbfx *fx)
{
    if (!fx) return NULL;
    for (int m = 0; m < SBFX_MEDIUM_COUNT; m++)
        if (fx->scene->uses_medium[m] && fx->scene->media[m].detail_clip[0] && fx->scene->media[m].detail_strength > 0)
            return fx->scene->media[m].detail_clip;
    return NULL;
}

sbfx_result sbfx_detail_procedural(const sbfx *fx, float *out, size_t count)
{
    if (!fx || !out) return SBFX_ERR_INVALID_ARGUMENT;
    int size = fx->scene->desc.detail_size, frames = fx->scene->desc.detail_frames;
    if (count != (size_t)size * size * frames) return SBFX_ERR_INVALID_ARGUMENT;
    sbfx_detail_generate(size, frames, fx->scene->desc.seed, out); /* what upload_detail made */
    return SBFX_OK;
}

/* One slice of the time ring: glTexSubImage3D of size x size half floats, no allocation. */
sbfx_result sbfx_detail_push_slice(sbfx *fx, const uint16_t *half_texels, int size)
{
    if (!fx || !half_texels) return SBFX_ERR_INVALID_ARGUMENT;
    if (!fx->gl->detail_texture)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "the loaded scene uses no detail volume");
    if (size != fx->scene->desc.detail_size)
        return sbfx_fail(fx, SBFX_ERR_INVALID_ARGUMENT, "detail slice is %dx%d, the volume is %dx%d", size,
                         size, fx->scene->desc.detail_size, fx->scene->desc.detail_size);
    /* the unpack state and unit 0's 3D binding are the host's: saved, set, put back */
    const sbfx_gl_units unit0_3d = {.tex_3d = 1u};
    sbfx_gl_enter(fx);
    sbfx_gl_state saved;
    sbfx_gl_state_save(&saved, SBFX_GL_SAVE_UNPACK, &unit0_3d);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    glBindTexture(GL_TEXTURE_3D, fx->gl->detail_texture);
    if (fx->scene->desc.detail_format == SBFX_DETAIL_R32F) {
        float *row = fx->gl->detail_scratch; /* sized at load: no allocation per slice */
        for (int i = 0; i < size * size; i++) {
            sbfx_float16 h;
            memcpy(&h, &half_texels[i], sizeof(h));
            row[i] = (float)h;
        }
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, fx->gl->detail_ring_next, size, size, 1, GL_RED, GL_FLOAT, row);
    } else {
        glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, fx->gl->detail_ring_next, size, size, 1, GL_RED, GL_HALF_FLOAT,
                        half_texels);
    }
    sbfx_gl_state_restore(&saved);
    sbfx_object_forget_recipe(fx, SBFX_OBJECT_TEXTURE, fx->gl->detail_texture); /* not procedural now */
    if (fx->sim->fire_slice_histograms) { /* the fire's light follows what the volume now holds */
        sbfx_fire_slice_histogram(half_texels, size,
                                  &fx->sim->fire_slice_histograms[(size_t)fx->gl->detail_ring_next * SBFX_FIRE_DETAIL_BINS]);
        sbfx_fire_detail_levels_of_slices(fx->sim->fire_slice_histograms, fx->scene->desc.detail_frames, fx->sim->fire_detail);
    }
    fx->gl->detail_ring_next = (fx->gl->detail_ring_next + 1) % fx->scene->desc.detail_frames;
    sbfx_result r = sbfx_gl_check(fx, "writing a detail slice") ? SBFX_OK : SBFX_ERR_GL;
    sbfx_gl_leave(fx, "sbfx_detail_push_slice");
    return r;
}
