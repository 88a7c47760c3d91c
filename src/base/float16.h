/* The compiler's IEEE half float, for the files that convert to and from it (round to nearest
 * even): _Float16 (GCC; clang on ARM). Clang 14 for WebAssembly (Debian 12's emscripten, make
 * web: docs/web.md) has no _Float16 and converts its storage-only __fp16 the same way. */
#ifndef SBFX_BASE_FLOAT16_H
#define SBFX_BASE_FLOAT16_H
#if defined(__wasm__)
typedef __fp16 sbfx_float16;
#else
typedef _Float16 sbfx_float16;
#endif
#endif
