/*
 * x11_display_probe.c: whether the X server that DISPLAY names answers,
 * within a deadline, before the viewer hands the display to SDL.
 *
 * In:  a DISPLAY string ([tcp/|unix/][host]:number[.screen]) and seconds.
 * Out: false, with the reason, only when something takes the connection
 *      and then does not send a whole answer to the first message of the
 *      X11 protocol within the deadline (nothing, a part of one, or the
 *      connection itself hangs), or answers with bytes that are no X11
 *      answer: the cases in which Xlib would wait forever. True otherwise:
 *      a server answered in full (with success, failure or a request to
 *      authenticate: it is alive), or nothing listens, or the connection
 *      was closed or refused. Those
 *      are Xlib's to judge, as before this probe: it fails on them at once,
 *      or succeeds where this probe cannot (an ssh -X forwarder closes a
 *      connection without its cookie, which Xlib sends; libxcb falls back
 *      from a missing local socket to TCP; bracketed IPv6 hosts).
 *
 * Why: Xlib (under SDL) connects and then waits for the server's reply to
 * its setup request with no time limit. An X server that hangs, or a TCP
 * path that drops packets, keeps the viewer waiting forever, with no
 * window and no message. This probe makes the same connection without
 * blocking: connect, send the 12-byte setup request (X Window System
 * Protocol, section 8, "Connection Setup": byte order, protocol 11.0, no
 * authorisation), and read the whole reply within the deadline: its
 * 8-byte header (a status of 0 Failed, 1 Success or 2 Authenticate, and
 * for the first two the protocol's major version, 11) and the 4-byte
 * units of data its bytes 6-7 count. Xlib reads exactly that much, with
 * no limit: a server that sends one byte of it and stalls, or a header
 * announcing data that never comes, would hold it forever (and SIGTERM
 * with it, which SDL's handler turns into an event nobody reads yet).
 * The probe says nothing of whether Xlib will then be allowed in; SDL
 * finds that out, quickly, as before.
 *
 * Local displays (no host, or "unix") are the socket /tmp/.X11-unix/X<n>,
 * which Linux's libxcb tries after the abstract socket of the same name;
 * this tries both, in that order. A host name is resolved with
 * getaddrinfo, which may itself wait on a DNS server (a numeric address
 * does not). A DISPLAY this does not understand (launchd's paths, say) is
 * left to Xlib.
 */
#include "x11_display_probe.h"

#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <stddef.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

/* The display number and the host, from [protocol/][host]:number[.screen];
 * false for a form this does not know. */
static bool parse_display(const char *display, char *host, size_t host_size, int *number,
                          bool *local)
{
    const char *text = display;
    bool tcp_only = false;
    if (strncmp(text, "tcp/", 4) == 0) {
        tcp_only = true;
        text += 4;
    } else if (strncmp(text, "unix/", 5) == 0) {
        text += 5;
    }
    if (text[0] == '/') return false;                 /* a path: launchd's */
    const char *colon = strrchr(text, ':');
    if (colon == NULL || colon - text >= (long)host_size) return false;
    if (colon > text && colon[-1] == ':') return false;   /* DECnet's "::" */
    memcpy(host, text, (size_t)(colon - text));
    host[colon - text] = '\0';
    char *end;
    errno = 0;
    long value = strtol(colon + 1, &end, 10);
    if (end == colon + 1 || errno != 0 || value < 0 || value > 59535 ||
        (*end != '\0' && *end != '.'))
        return false;
    *number = (int)value;
    *local = !tcp_only && (host[0] == '\0' || strcmp(host, "unix") == 0);
    return true;
}

static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec / 1e9;
}

/* Waits until fd is ready for events or the deadline passes: 1, or 0 for
 * the deadline, or -1 with errno. */
static int wait_for(int fd, short events, double deadline)
{
    for (;;) {
        double left = deadline - seconds_now();
        if (left <= 0.0) return 0;
        struct pollfd poll_fd = {.fd = fd, .events = events};
        int ready = poll(&poll_fd, 1, (int)(left * 1000.0) + 1);
        if (ready > 0) return 1;
        if (ready < 0 && errno != EINTR) return -1;
    }
}

/* PROBE_SILENT: no whole answer within the deadline, or one that is no X
 * server's; Xlib would wait forever. */
typedef enum probe_result { PROBE_ANSWERED, PROBE_NO_SERVER, PROBE_SILENT } probe_result;

/* Reads exactly size bytes of fd (non-blocking) into buffer (NULL: reads
 * and drops them) before the deadline. Returns the count read: size, or
 * fewer when the deadline passed (*closed false) or the peer closed the
 * connection or failed (*closed true). */
static size_t read_within(int fd, unsigned char *buffer, size_t size, double deadline,
                          bool *closed)
{
    unsigned char scratch[4096];
    size_t done = 0;
    *closed = false;
    while (done < size) {
        const int ready = wait_for(fd, POLLIN, deadline);
        if (ready == 0) return done;
        if (ready < 0) {
            *closed = true;
            return done;
        }
        size_t want = size - done;
        unsigned char *into = buffer ? buffer + done : scratch;
        if (buffer == NULL && want > sizeof scratch) want = sizeof scratch;
        const ssize_t got = recv(fd, into, want, 0);
        if (got < 0 && (errno == EINTR || errno == EAGAIN || errno == EWOULDBLOCK)) continue;
        if (got <= 0) {
            *closed = true;
            return done;
        }
        done += (size_t)got;
    }
    return done;
}

/* Reads the server's whole answer to the setup request (sent as 'l', so
 * its numbers are little-endian). */
static probe_result read_setup_reply(int fd, double deadline, char *why, size_t why_size)
{
    unsigned char header[8];
    bool closed;
    const size_t got = read_within(fd, header, sizeof header, deadline, &closed);
    if (got == 0 && closed) {
        snprintf(why, why_size, "it closed the connection without an answer");
        return PROBE_NO_SERVER;
    }
    if (got > 0 && header[0] > 2) {
        snprintf(why, why_size, "it answered with a byte no X server sends (0x%02x)", header[0]);
        return PROBE_SILENT;
    }
    if (got < sizeof header) {
        if (got == 0)
            snprintf(why, why_size, "it accepted the connection, then said nothing");
        else
            snprintf(why, why_size, "it sent %zu bytes of its answer's 8-byte header, then %s",
                     got, closed ? "closed the connection" : "nothing");
        /* a connection closed early fails Xlib at once: its to report */
        return closed ? PROBE_NO_SERVER : PROBE_SILENT;
    }
    const unsigned major = header[2] | (unsigned)header[3] << 8;
    if (header[0] != 2 && major != 11) {
        snprintf(why, why_size, "it answered for protocol version %u, not 11: no X server", major);
        return PROBE_SILENT;
    }
    /* the rest: bytes 6-7 count it in 4-byte units (at most 256 KiB) */
    const size_t rest = 4 * (size_t)(header[6] | (unsigned)header[7] << 8);
    const size_t more = read_within(fd, NULL, rest, deadline, &closed);
    if (more < rest) {
        snprintf(why, why_size, "it sent %zu of the %zu bytes its answer announced, then %s",
                 sizeof header + more, sizeof header + rest,
                 closed ? "closed the connection" : "nothing");
        return closed ? PROBE_NO_SERVER : PROBE_SILENT;
    }
    return PROBE_ANSWERED;
}

/* Connects fd to address, sends the setup request and reads the answer. */
static probe_result probe_socket(int fd, const struct sockaddr *address, socklen_t length,
                                 double deadline, char *why, size_t why_size)
{
    if (connect(fd, address, length) != 0 && errno != EINPROGRESS) {
        snprintf(why, why_size, "%s", strerror(errno));
        return PROBE_NO_SERVER;
    }
    int ready = wait_for(fd, POLLOUT, deadline);
    int error = 0;
    socklen_t error_length = sizeof error;
    if (ready == 0) {
        snprintf(why, why_size, "no connection");
        return PROBE_SILENT;
    }
    if (ready < 0 || getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &error_length) != 0 ||
        error != 0) {
        snprintf(why, why_size, "%s", strerror(ready < 0 ? errno : error));
        return PROBE_NO_SERVER;
    }
    /* 'l': little-endian, then pad, protocol 11.0, no authorisation name
     * or data, pad. The server answers with a status byte. */
    static const unsigned char setup[12] = {'l', 0, 11, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    if (send(fd, setup, sizeof setup, MSG_NOSIGNAL) != (ssize_t)sizeof setup) {
        snprintf(why, why_size, "%s", strerror(errno));
        return PROBE_NO_SERVER;
    }
    return read_setup_reply(fd, deadline, why, why_size);
}

static probe_result probe_address(int family, const struct sockaddr *address,
                                  socklen_t length, double deadline, char *why,
                                  size_t why_size)
{
    int fd = socket(family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) {
        snprintf(why, why_size, "%s", strerror(errno));
        return PROBE_NO_SERVER;
    }
    probe_result result = probe_socket(fd, address, length, deadline, why, why_size);
    close(fd);
    return result;
}

static probe_result probe_local(int number, double deadline, char *why, size_t why_size)
{
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    /* The abstract socket: a NUL, then the path (not NUL-terminated). */
    int length = snprintf(address.sun_path + 1, sizeof address.sun_path - 1,
                          "/tmp/.X11-unix/X%d", number);
    probe_result result =
        probe_address(AF_UNIX, (const struct sockaddr *)&address,
                      (socklen_t)(offsetof(struct sockaddr_un, sun_path) + 1 + (size_t)length),
                      deadline, why, why_size);
    if (result != PROBE_NO_SERVER) return result;
    snprintf(address.sun_path, sizeof address.sun_path, "/tmp/.X11-unix/X%d", number);
    return probe_address(AF_UNIX, (const struct sockaddr *)&address, sizeof address, deadline,
                         why, why_size);
}

static probe_result probe_tcp(const char *host, int number, double deadline, char *why,
                              size_t why_size)
{
    char port[16];
    snprintf(port, sizeof port, "%d", 6000 + number);
    struct addrinfo hints = {.ai_socktype = SOCK_STREAM, .ai_flags = AI_NUMERICSERV};
    struct addrinfo *addresses = NULL;
    int resolved = getaddrinfo(host, port, &hints, &addresses);
    if (resolved != 0) {
        snprintf(why, why_size, "%s", gai_strerror(resolved));
        return PROBE_NO_SERVER;
    }
    probe_result result = PROBE_NO_SERVER;
    for (struct addrinfo *a = addresses; a != NULL && result == PROBE_NO_SERVER; a = a->ai_next)
        result = probe_address(a->ai_family, a->ai_addr, a->ai_addrlen, deadline, why, why_size);
    freeaddrinfo(addresses);
    return result;
}

bool luz_x11_display_answers(const char *display, double seconds, char *why, size_t why_size)
{
    char host[256];
    int number;
    bool local;
    if (display == NULL || !parse_display(display, host, sizeof host, &number, &local))
        return true;   /* Xlib's to judge */
    const double deadline = seconds_now() + seconds;
    char reason[256] = "";
    probe_result result = local ? probe_local(number, deadline, reason, sizeof reason)
                                : probe_tcp(host[0] ? host : "localhost", number, deadline,
                                            reason, sizeof reason);
    if (result != PROBE_SILENT) return true;
    snprintf(why, why_size, "the X display %s did not answer as an X server within %g s: %s",
             display, seconds, reason);
    return false;
}
