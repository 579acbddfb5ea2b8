/*
 * renderer/huge_pages.h: memory on the system's huge pages, the one thing
 * libluz asks of the operating system beyond POSIX (threads and clocks are
 * POSIX's). The renderer's own platform pair, as io/platform.h is the
 * layers above's (the renderer cannot include io): huge_pages_linux.c
 * advises Linux's transparent huge pages (madvise MADV_HUGEPAGE);
 * huge_pages_posix.c, built on every other system, gives the same aligned
 * memory on the system's ordinary pages. Only the time differs: what is
 * stored is the same.
 */
#ifndef LUZ_RENDERER_HUGE_PAGES_H
#define LUZ_RENDERER_HUGE_PAGES_H

#include <stddef.h>

/* The size of a huge page (x86-64's and aarch64's 2 MB with 4 KB base
 * pages), which a block is aligned to and a whole number of. */
#define LUZ_HUGE_PAGE_BYTES ((size_t)2 << 20)

/* A block of bytes (a multiple of LUZ_HUGE_PAGE_BYTES) aligned to
 * LUZ_HUGE_PAGE_BYTES and advised onto huge pages where the system has
 * them, or NULL if there is no memory; freed with free(). */
void *luz_huge_pages_alloc(size_t bytes);

#endif
