/* SPDX-License-Identifier: Apache-2.0 */
/* atv312d's web surface (--http): a page showing the bench live, its JSON API, the events it
 * pushes and, with --http-actions, the control commands, served by GNU libmicrohttpd inside the
 * daemon's one epoll loop (no thread). MHD's own epoll descriptor is one watched descriptor of the
 * loop and one timerfd holds both MHD's connection timeouts and the next event of the event
 * streams; it is armed only while a connection exists, so an unwatched daemon never wakes up for
 * the web. The library is loaded when the server opens (mhd_load.h), so a daemon without --http
 * does not map it. The API, the security rules and the limits: docs/web.md. */
#ifndef ATV312D_HTTP_H
#define ATV312D_HTTP_H

#include "atv312d/control_commands.h"
#include "atv312d/mhd_load.h"
#include "atv312d/options.h"

#include <netinet/in.h>
#include <stdbool.h>
#include <stddef.h>
#include <sys/socket.h>

/* Connections held at once; past them a new connection is closed at once, logged. */
#define ATV312D_HTTP_CONNECTIONS_MAX 128
/* Connections held at once from one client address (IPv4, or IPv6 whole); past them a new one
 * from that address is closed at once, logged: one machine cannot take every place. */
#define ATV312D_HTTP_PER_ADDRESS_MAX 16
/* Event streams open at once, counted apart from the connections that load the page or send
 * commands; past them a new stream is answered 503. */
#define ATV312D_HTTP_STREAMS_MAX 16
/* Each request must arrive whole, its head and its body, within this long of the connection
 * being ready for it (accepted, or its previous answer sent), however steadily its bytes come;
 * past it the connection is closed, logged. */
#define ATV312D_HTTP_REQUEST_DEADLINE_S 5
/* Memory of one connection's request and response headers (the library's pool). */
#define ATV312D_HTTP_CONNECTION_MEMORY (32 * 1024)
/* Longest request target (path and query); a longer one gets 414. */
#define ATV312D_HTTP_TARGET_MAX 2048
/* Longest request head, as sent: the request line and the headers with the empty line that ends
 * them; a longer one gets 431. Both limits lie well inside the library's pool, so that the server
 * answers them, as JSON, before the library would (docs/web.md, "Limits"). */
#define ATV312D_HTTP_HEAD_MAX (8 * 1024)
/* A connection that makes no progress for this long is closed (a client that stopped reading). */
#define ATV312D_HTTP_TIMEOUT_S 10
/* Longest body of POST /api/command; a longer one gets 413. */
#define ATV312D_HTTP_BODY_MAX 1024
/* The event streams' period: at most 4 states a second. */
#define ATV312D_HTTP_EVENT_PERIOD_MS 250
/* Longest secret of --http-token. */
#define ATV312D_HTTP_TOKEN_MAX 256
/* Longest JSON of the bench's state: 127 drives of about 600 bytes. */
#define ATV312D_HTTP_STATE_MAX (128 * 1024)

/* Reads the secret of --http-token from the file at path: its first line, of 1 to
 * ATV312D_HTTP_TOKEN_MAX characters. 0, or an exit status with a message in err. */
int atv312d_http_read_token(const char *path, char *token, size_t token_len, char *err,
                            size_t err_len);

typedef struct atv312d_http_settings {
    atv312d_http_address_t address;
    bool actions;                           /* --http-actions: POST /api/command runs */
    char token[ATV312D_HTTP_TOKEN_MAX + 1]; /* --http-token's secret; "": none required */
} atv312d_http_settings_t;

/* A request as the handler sees it: the parts of the HTTP request it looks at (NULL when a header
 * is absent) and, for a POST, its body. */
typedef struct atv312d_http_request {
    const char *method, *path;
    const char *host, *origin, *fetch_site, *content_type, *content_length, *token, *if_none_match;
    const char *body; /* NULL: the body is not read yet (the checks on the headers only) */
    size_t body_len;
    bool body_too_long; /* more than ATV312D_HTTP_BODY_MAX bytes came */
    size_t target_len;  /* the request target's length as sent, path and query; 0: unknown */
    size_t head_len;    /* the head's length as sent (ATV312D_HTTP_HEAD_MAX); 0: unknown */
    const char *peer;   /* "127.0.0.1:40422", for the log */
} atv312d_http_request_t;

/* What the handler answers: a status, a body and the headers that go with it. */
typedef struct atv312d_http_answer {
    unsigned status;
    const char *content_type;
    const void *body; /* the asset's bytes, or the handler's buffer */
    size_t body_len;
    const char *cache_control;
    const char *etag;  /* an asset's, or NULL */
    const char *allow; /* with 405 */
    bool events;       /* 200 for GET /api/events: the event stream starts */
} atv312d_http_answer_t;

/* One connection waiting for or writing an event (http.c). */
typedef struct atv312d_http_stream atv312d_http_stream_t;
/* One connection held: its address and its request's deadline (http.c). */
typedef struct atv312d_http_client atv312d_http_client_t;

typedef struct atv312d_http {
    co_linux_loop_t *loop;
    const atv312d_control_t *control;
    atv312d_http_settings_t settings;
    uint16_t port;                  /* the port bound (the one asked, or the kernel's for port 0) */
    atv312d_mhd_t mhd;              /* the library's functions, loaded by atv312d_http_open */
    struct MHD_Daemon *daemon;      /* NULL: not open */
    int mhd_fd;                     /* the library's epoll descriptor, watched by the loop */
    int timer_fd;                   /* MHD's timeouts and the next event; armed only when needed */
    atv312d_http_client_t *clients; /* the connections held */
    size_t client_count;            /* at most ATV312D_HTTP_CONNECTIONS_MAX */
    atv312d_http_stream_t *streams; /* the event streams */
    size_t stream_count;            /* at most ATV312D_HTTP_STREAMS_MAX */
    uint64_t event_sequence;        /* counts the events formatted */
    co_time_t next_event;           /* when the next event is due; CO_TIME_NEVER: no stream */
    char *event;                    /* the latest event, "event: state\ndata: {...}\n\n" */
    size_t event_len;
    char *buf;   /* the handler's answers, ATV312D_HTTP_STATE_MAX bytes */
    char *reply; /* a command's reply line, ATV312D_CONTROL_REPLY_MAX bytes */
    /* frames_per_second: the bus's frame count at a time, the rate since the one before. */
    co_time_t rate_time;
    unsigned long long rate_frames;
    double rate;
} atv312d_http_t;

/* Answers one request (no socket involved: the unit tests call it as the server does). Returns
 * true, with no answer, only for a POST /api/command that passed the checks of its headers while
 * request->body is NULL: call again with the body. Otherwise the answer is in *answer. Every
 * refusal (an answer of 400 or more that is not a command's own reply) is logged once at warn
 * with the client, the request and the reason. */
bool atv312d_http_handle(atv312d_http_t *http, const atv312d_http_request_t *request,
                         atv312d_http_answer_t *answer);

/* Prepares the handler without a server (the unit tests): buffers, settings, the drives. 0 or
 * EX_OSERR. */
int atv312d_http_init(atv312d_http_t *http, co_linux_loop_t *loop,
                      const atv312d_http_settings_t *settings, const atv312d_control_t *control);

/* atv312d_http_init, then loads the library and listens at the settings' address in the loop. 0,
 * or an exit status after logging why (EX_UNAVAILABLE: the library cannot be loaded;
 * EX_CANTCREAT: the address cannot be bound). */
int atv312d_http_open(atv312d_http_t *http, co_linux_loop_t *loop,
                      const atv312d_http_settings_t *settings, const atv312d_control_t *control);

/* Closes every connection and the listening socket, unloads the library, frees the buffers. Safe
 * when not open. */
void atv312d_http_close(atv312d_http_t *http);

#endif
