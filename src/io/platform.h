/*
 * io/platform.h: what luz asks of the operating system beyond POSIX, each
 * in one place (issue 28), so that libluz and luz-render build on macOS
 * and the BSDs as well as on Linux.
 *
 * platform_linux.c answers with Linux's calls (pipe2, prctl, openat2,
 * /proc); platform_posix.c, built everywhere else, with POSIX alone and
 * what a system has beyond it where luz can tell at compile time (macOS's
 * F_GETPATH, FreeBSD's O_RESOLVE_BENEATH), or says it cannot (errno
 * ENOSYS), and the caller does without. The model importer's confinement
 * is Linux's too (model_confine.c: Landlock, seccomp); elsewhere
 * model_confine_none.c confines nothing and luz says so once per model.
 * tests/portable_build.sh compiles every other file of libluz and
 * luz-render with POSIX's headers alone and no Linux header.
 */
#ifndef LUZ_IO_PLATFORM_H
#define LUZ_IO_PLATFORM_H

#include <stddef.h>
#include <stdint.h>

/* pipe(2) with both ends close-on-exec: 0, or -1 with errno. (Without
 * pipe2, a thread of the program that forks and execs at that very moment
 * may take an end into its child.) */
int luz_platform_pipe(int ends[2]);

/* Asks the kernel to kill this process (SIGKILL) when its parent ends:
 * 0, or -1 with errno (ENOSYS: the system cannot; a child then outlives
 * its parent until its own limits end it). */
int luz_platform_die_with_parent(void);

/* This process's address space now, in bytes; 0 if the system cannot
 * tell. */
uint64_t luz_platform_address_space(void);

/* A descriptor for luz_platform_peak_address_space, opened before the
 * process is confined; -1 if the system cannot tell. */
int luz_platform_peak_address_space_open(void);

/* The largest address space this process has had, in bytes, read through
 * that descriptor with async-signal-safe calls only (a crash handler
 * calls it); 0 if it cannot be told. */
uint64_t luz_platform_peak_address_space(int descriptor);

/* Flags for open(2) of a file to look at it without reading it (Linux's
 * O_PATH: a FIFO or a device is not opened); elsewhere a read-only open
 * that cannot block. Add O_DIRECTORY, O_CLOEXEC as needed. */
int luz_platform_path_flags(void);

/* openat(directory_fd, name, flags) resolved by the kernel within the
 * directory: an absolute name, a `..` above it or a symbolic link out is
 * refused (errno EXDEV). -1 with errno ENOSYS (or EPERM, a filter's)
 * where the kernel cannot: the caller then checks the file it opened with
 * luz_platform_descriptor_path. */
int luz_platform_open_beneath(int directory_fd, const char *name, int flags);

/* The absolute path, without symbolic links, of the file open as fd
 * (opened with luz_platform_path_flags), into path (size bytes): 0, or -1
 * with errno (ENOSYS: the system cannot tell). */
int luz_platform_descriptor_path(int fd, char *path, size_t size);

/* The file open as fd (with luz_platform_path_flags), opened again for
 * reading with flags (O_RDONLY | O_NONBLOCK | ...): a descriptor, or -1
 * with errno. */
int luz_platform_reopen(int fd, int flags);

/* The path of the running program, into path (size bytes): 0, or -1 if
 * the system cannot tell. */
int luz_platform_executable_path(char *path, size_t size);

#endif
