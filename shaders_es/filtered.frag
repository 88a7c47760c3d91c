#version 300 es
// Texture filtering in the shader, with the weights rounded to FILTER_BITS fractional bits the
// way a GPU's fixed-point filter rounds them (DESIGN §9: NVIDIA documents 8; Vulkan's
// subTexelPrecisionBits is at least 4). A diagnostic (SBFX_FILTER_BITS=N, src/gl/precision.c):
// src/gl/gl_util.c inserts this file, with FILTER_LIBRARY defined, ahead of a fragment shader's body;
// the shaders then call filtered_2d / filtered_3d_repeat / filtered_array_lod where they would
// have left a fetch to the texture unit. Without FILTER_BITS each shader defines those names as
// the plain texture() / textureLod() calls: default builds compile none of this.
// Rounding: w = floor(f 2^N + 0.5) / 2^N on each axis's fraction (and the mip levels' fraction);
// 1 - w is then exact too. The neighbours are read with texelFetch and mixed in highp.
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler3D;
precision highp sampler2DArray;

#ifndef FILTER_BITS
#define FILTER_BITS 8   // validated on its own (tests/run.sh): the diagnostic's usual value
#endif

float filter_weight(float f)
{
    const float scale = float(1 << FILTER_BITS);
    return floor(f * scale + 0.5) / scale;
}

// CLAMP_TO_EDGE: the lower texel's index and the rounded weights of one level.
vec4 bilinear_level(sampler2D s, vec2 uv, int level)
{
    ivec2 size = textureSize(s, level);
    vec2 p = uv * vec2(size) - 0.5;
    vec2 i = floor(p);
    vec2 w = vec2(filter_weight(p.x - i.x), filter_weight(p.y - i.y));
    ivec2 a = clamp(ivec2(i), ivec2(0), size - 1), b = clamp(ivec2(i) + 1, ivec2(0), size - 1);
    vec4 low = mix(texelFetch(s, a, level), texelFetch(s, ivec2(b.x, a.y), level), w.x);
    vec4 high = mix(texelFetch(s, ivec2(a.x, b.y), level), texelFetch(s, b, level), w.x);
    return mix(low, high, w.y);
}

vec4 filtered_2d(sampler2D s, vec2 uv)
{
    return bilinear_level(s, uv, 0);
}

// REPEAT: i mod n for the small integers a coordinate gives (i + 0.5 keeps the quotient off
// the integers, so the division's rounding cannot move the floor).
vec3 repeat_index(vec3 i, vec3 n)
{
    return i - n * floor((i + 0.5) / n);
}

vec4 filtered_3d_repeat(sampler3D s, vec3 uvw)
{
    vec3 n = vec3(textureSize(s, 0));
    vec3 p = uvw * n - 0.5;
    vec3 i = floor(p);
    vec3 w = vec3(filter_weight(p.x - i.x), filter_weight(p.y - i.y), filter_weight(p.z - i.z));
    ivec3 a = ivec3(repeat_index(i, n)), b = ivec3(repeat_index(i + 1.0, n));
    vec4 c00 = mix(texelFetch(s, a, 0), texelFetch(s, ivec3(b.x, a.y, a.z), 0), w.x);
    vec4 c10 = mix(texelFetch(s, ivec3(a.x, b.y, a.z), 0), texelFetch(s, ivec3(b.x, b.y, a.z), 0), w.x);
    vec4 c01 = mix(texelFetch(s, ivec3(a.x, a.y, b.z), 0), texelFetch(s, ivec3(b.x, a.y, b.z), 0), w.x);
    vec4 c11 = mix(texelFetch(s, ivec3(a.x, b.y, b.z), 0), texelFetch(s, b, 0), w.x);
    return mix(mix(c00, c10, w.y), mix(c01, c11, w.y), w.z);
}

vec4 bilinear_layer(sampler2DArray s, vec2 uv, int layer, int level)
{
    ivec2 size = textureSize(s, level).xy;
    vec2 p = uv * vec2(size) - 0.5;
    vec2 i = floor(p);
    vec2 w = vec2(filter_weight(p.x - i.x), filter_weight(p.y - i.y));
    ivec2 a = clamp(ivec2(i), ivec2(0), size - 1), b = clamp(ivec2(i) + 1, ivec2(0), size - 1);
    vec4 low = mix(texelFetch(s, ivec3(a, layer), level), texelFetch(s, ivec3(b.x, a.y, layer), level), w.x);
    vec4 high = mix(texelFetch(s, ivec3(a.x, b.y, layer), level), texelFetch(s, ivec3(b, layer), level), w.x);
    return mix(low, high, w.y);
}

// LINEAR_MIPMAP_LINEAR, CLAMP_TO_EDGE, an explicit level of detail; the chain is complete
// (src/tables/smoke_texture.c: down to 1 x 1), so its last level is log2 of the base size.
vec4 filtered_array_lod(sampler2DArray s, vec3 uvl, float lod)
{
    ivec2 base = textureSize(s, 0).xy;
    float last = floor(log2(float(max(base.x, base.y))) + 0.5);
    float l = clamp(lod, 0.0, last);
    float l0 = floor(l), w = filter_weight(l - l0);
    int layer = int(floor(uvl.z + 0.5));
    vec4 c = bilinear_layer(s, uvl.xy, layer, int(l0));
    return w > 0.0 ? mix(c, bilinear_layer(s, uvl.xy, layer, int(min(l0 + 1.0, last))), w) : c;
}

#ifndef FILTER_LIBRARY
// Standalone (glslangValidator): every function used once.
uniform sampler2D u_a;
uniform sampler3D u_b;
uniform sampler2DArray u_c;
in vec2 v_uv;
out vec4 o_color;
void main()
{
    o_color = filtered_2d(u_a, v_uv) + filtered_3d_repeat(u_b, vec3(v_uv, 0.5)) +
              filtered_array_lod(u_c, vec3(v_uv, 1.0), 1.5);
}
#endif
