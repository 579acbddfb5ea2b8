/*
 * huge_pages_linux.c: renderer/huge_pages.h on Linux, whose transparent
 * huge pages back an aligned block with 2 MB pages when asked
 * (MADV_HUGEPAGE), whatever the system's default ("madvise" or
 * "always"; "never" leaves 4 KB pages).
 *
 * In:  a size, a multiple of LUZ_HUGE_PAGE_BYTES.
 * Out: a block that free() releases, aligned to a huge page.
 */
#define _DEFAULT_SOURCE   /* madvise's MADV_HUGEPAGE */
#include <stdlib.h>
#include <sys/mman.h>

#include "renderer/huge_pages.h"

void *luz_huge_pages_alloc(size_t bytes)
{
    void *block = aligned_alloc(LUZ_HUGE_PAGE_BYTES, bytes);
    if (!block) return NULL;
#ifdef MADV_HUGEPAGE
    (void)madvise(block, bytes, MADV_HUGEPAGE);   /* advice: without it, 4 KB pages */
#endif
    return block;
}
