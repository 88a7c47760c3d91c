/* tests/vm helper, LD_PRELOAD'ed into sbfx-play: counts malloc, calloc and realloc calls made
 * directly from the program's own code (the player and libsbfx.a, linked in; not Mesa, libdrm,
 * libpng or libc internals) and prints "alloc-count: program N, all M" on stderr at exit.
 * Two runs that differ only in their frame count must print the same N: the loop allocates
 * nothing per frame. */
#define _GNU_SOURCE
#include <link.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

void *__libc_malloc(size_t size);
void *__libc_calloc(size_t count, size_t size);
void *__libc_realloc(void *ptr, size_t size);

static uintptr_t text_start, text_end;
static unsigned long from_program, from_all;

/* The first object dl_iterate_phdr reports is the executable: its executable segment. */
static int find_text(struct dl_phdr_info *info, size_t size, void *data)
{
    for (int i = 0; i < info->dlpi_phnum; i++) {
        const ElfW(Phdr) *ph = &info->dlpi_phdr[i];
        if (ph->p_type != PT_LOAD || !(ph->p_flags & PF_X)) continue;
        text_start = info->dlpi_addr + ph->p_vaddr;
        text_end = text_start + ph->p_memsz;
    }
    return 1;
}

static void count(const void *caller)
{
    from_all++;
    if (!text_start) dl_iterate_phdr(find_text, NULL);
    if ((uintptr_t)caller >= text_start && (uintptr_t)caller < text_end) from_program++;
}

void *malloc(size_t size)
{
    count(__builtin_return_address(0));
    return __libc_malloc(size);
}

void *calloc(size_t n, size_t size)
{
    count(__builtin_return_address(0));
    return __libc_calloc(n, size);
}

void *realloc(void *ptr, size_t size)
{
    count(__builtin_return_address(0));
    return __libc_realloc(ptr, size);
}

__attribute__((destructor)) static void report(void)
{
    char line[96];
    int len = snprintf(line, sizeof(line), "alloc-count: program %lu, all %lu\n", from_program, from_all);
    if (len > 0 && write(STDERR_FILENO, line, (size_t)len) < 0) return;
}
