/*
 * huge_pages_posix.c: renderer/huge_pages.h on systems other than Linux
 * (macOS, the BSDs): POSIX has no call that asks for huge pages, so the
 * block is aligned as on Linux and lies on whatever pages the system
 * gives (FreeBSD's superpages may back it without being asked).
 *
 * In:  a size, a multiple of LUZ_HUGE_PAGE_BYTES.
 * Out: a block that free() releases, aligned to a huge page.
 */
#include <stdlib.h>

#include "renderer/huge_pages.h"

void *luz_huge_pages_alloc(size_t bytes)
{
    return aligned_alloc(LUZ_HUGE_PAGE_BYTES, bytes);
}
