/*
 * luz/api.h: what libluz exports.
 *
 * libluz is compiled with every symbol hidden (-fvisibility=hidden); the
 * functions of its public headers are marked LUZ_API, so the shared
 * library exports exactly them, and the pipeline's stages stay internal
 * (tests reach them through the static build of the same objects).
 */
#ifndef LUZ_API_H
#define LUZ_API_H

#if defined(__GNUC__)
#define LUZ_API __attribute__((visibility("default")))
#else
#define LUZ_API
#endif

#endif
