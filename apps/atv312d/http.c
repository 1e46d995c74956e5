/* SPDX-License-Identifier: Apache-2.0 */
/* The web surface (http.h): the address and token of the command line, the handler of requests
 * (the bench, its state, the assets, the commands and their checks) and its server on
 * libmicrohttpd in the daemon's loop, whose functions it calls through http->mhd (mhd_load.h). */
#include "atv312d/http.h"

#include "atv312d/web_assets.h"
#include "cli/json.h"
#include "co_linux/log.h"

#include <arpa/inet.h>
#include <errno.h>
#include <microhttpd.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/timerfd.h>
#include <sysexits.h>
#include <time.h>
#include <unistd.h>

#define TOKEN_HEADER "X-Atv312d-Token"
#define EVENT_PREFIX "event: state\ndata: "
#define EVENT_SUFFIX "\n\n"
#define EVENT_MAX (ATV312D_HTTP_STATE_MAX + sizeof EVENT_PREFIX + sizeof EVENT_SUFFIX)
/* The block the library asks the event stream for at most at once. */
#define EVENT_BLOCK (16 * 1024)
#define US_PER_MS 1000

/* ---- the command line's token ---- */

int atv312d_http_read_token(const char *path, char *token, size_t token_len, char *err,
                            size_t err_len)
{
    FILE *f = fopen(path, "re");
    if (!f) {
        snprintf(err, err_len, "--http-token %s: cannot be read: %s", path, strerror(errno));
        return EX_NOINPUT;
    }
    char line[ATV312D_HTTP_TOKEN_MAX + 2];
    bool read = fgets(line, sizeof line, f) != NULL;
    fclose(f);
    size_t len = read ? strcspn(line, "\r\n") : 0;
    bool whole = read && (line[len] != '\0' || len < sizeof line - 1);
    if (len == 0 || !whole || len >= token_len) {
        snprintf(err, err_len,
                 "--http-token %s: the secret must be the file's first line, 1..%d characters",
                 path, ATV312D_HTTP_TOKEN_MAX);
        return EX_DATAERR;
    }
    memcpy(token, line, len);
    token[len] = '\0';
    return 0;
}

/* ---- the bench and its state ---- */

static bool devicenet(const atv312d_http_t *http)
{
    return http->control->count > 0 && http->control->nodes[0].devicenet != NULL;
}

/* The JSON answers' lengths are 0 when the answer does not fit in the buffer: never, it holds
 * 127 drives' state. */

/* GET /api/bench: the interface, the protocol, what the web may do, and each drive's fixed data. */
static size_t format_bench(const atv312d_http_t *http, char *buf, size_t len)
{
    cli_json_t json;
    cli_json_init(&json, buf, len);
    cli_json_begin_object(&json, NULL);
    cli_json_str(&json, "interface", http->loop->iface);
    cli_json_str(&json, "protocol", devicenet(http) ? "devicenet" : "canopen");
    cli_json_bool(&json, "actions", http->settings.actions);
    cli_json_bool(&json, "token_required", http->settings.token[0] != '\0');
    cli_json_begin_array(&json, "drives");
    for (size_t i = 0; i < http->control->count; i++)
        atv312d_bench_drive_json(&json, &http->control->nodes[i]);
    cli_json_end_array(&json);
    cli_json_end_object(&json);
    return cli_json_finish(&json);
}

/* Frames per second on the bus, received and sent: over the time since the count before,
 * taken again once a second or more has passed (between two readings the rate stays). */
static double frame_rate(atv312d_http_t *http, co_time_t now)
{
    const co_linux_stats_t *stats = &http->loop->stats;
    unsigned long long frames = stats->rx + stats->tx;
    if (now >= http->rate_time + 1000000) {
        http->rate = (double)(frames - http->rate_frames) * 1e6 / (double)(now - http->rate_time);
        http->rate_time = now;
        http->rate_frames = frames;
    }
    return http->rate;
}

/* GET /api/state and each event: the bus, then each drive's view as `json state` gives it. */
static size_t format_state(atv312d_http_t *http, char *buf, size_t len)
{
    const co_linux_loop_t *loop = http->loop;
    cli_json_t json;
    cli_json_init(&json, buf, len);
    cli_json_begin_object(&json, NULL);
    cli_json_bool(&json, "ok", true);
    cli_json_uint(&json, "time_ms", (unsigned long long)(loop->now / US_PER_MS));
    cli_json_begin_object(&json, "bus");
    cli_json_str(&json, "state", atv312d_can_state(loop));
    cli_json_uint(&json, "frames_received", loop->stats.rx);
    cli_json_uint(&json, "frames_sent", loop->stats.tx);
    cli_json_number(&json, "frames_per_second", "%.1f", frame_rate(http, loop->now));
    cli_json_end_object(&json);
    cli_json_begin_array(&json, "nodes");
    for (size_t i = 0; i < http->control->count; i++)
        atv312d_state_json(&json, &http->control->nodes[i]);
    cli_json_end_array(&json);
    cli_json_end_object(&json);
    return cli_json_finish(&json);
}

/* ---- answers ---- */

static void answer_json(atv312d_http_t *http, atv312d_http_answer_t *answer, unsigned status,
                        size_t len)
{
    *answer = (atv312d_http_answer_t){.status = status,
                                      .content_type = "application/json",
                                      .body = http->buf,
                                      .body_len = len,
                                      .cache_control = "no-store"};
}

/* A request's text shown in an error: short, printable, or "(unprintable)". */
static const char *shown(const char *text)
{
    if (!text)
        return "(none)";
    size_t n = 0;
    for (; text[n]; n++) {
        if (text[n] < 0x20 || text[n] > 0x7E || text[n] == '"' || text[n] == '\\')
            return "(unprintable)";
    }
    return n <= 100 ? text : "(too long)";
}

static void answer_error(atv312d_http_t *http, const atv312d_http_request_t *request,
                         atv312d_http_answer_t *answer, unsigned status, const char *format, ...)
    __attribute__((format(printf, 5, 6)));

/* {"ok":false,"error":"..."} with the status, and the refusal's one line at warn. */
static void answer_error(atv312d_http_t *http, const atv312d_http_request_t *request,
                         atv312d_http_answer_t *answer, unsigned status, const char *format, ...)
{
    char message[512];
    va_list args;
    va_start(args, format);
    vsnprintf(message, sizeof message, format, args);
    va_end(args);
    cli_json_t json;
    cli_json_init(&json, http->buf, ATV312D_HTTP_STATE_MAX);
    cli_json_begin_object(&json, NULL);
    cli_json_bool(&json, "ok", false);
    cli_json_str(&json, "error", message);
    cli_json_end_object(&json);
    answer_json(http, answer, status, cli_json_finish(&json));
    co_log(CO_LOG_WARN, "http %s: %s %s: refused, %u: %s", request->peer ? request->peer : "?",
           shown(request->method), shown(request->path), status, message);
}

/* ---- who may ask ---- */

/* The name in a Host header ("localhost:8080", "[::1]:8080") names this machine. */
static bool host_is_loopback(const char *host)
{
    char name[INET6_ADDRSTRLEN + 1];
    size_t len;
    if (host[0] == '[') {
        len = strcspn(host + 1, "]");
        if (host[1 + len] != ']' || len >= sizeof name)
            return false;
        memcpy(name, host + 1, len);
    } else {
        len = strcspn(host, ":");
        if (len >= sizeof name)
            return false;
        memcpy(name, host, len);
    }
    name[len] = '\0';
    struct in_addr v4;
    struct in6_addr v6;
    if (strcmp(name, "localhost") == 0)
        return true;
    if (inet_pton(AF_INET, name, &v4) == 1)
        return (ntohl(v4.s_addr) >> 24) == 127;
    return inet_pton(AF_INET6, name, &v6) == 1 && IN6_IS_ADDR_LOOPBACK(&v6);
}

/* Compares the whole secret whatever differs first: the time says nothing of the secret. */
static bool token_matches(const char *expected, const char *given)
{
    size_t expected_len = strlen(expected), given_len = strlen(given);
    unsigned char diff = expected_len != given_len;
    for (size_t i = 0; i < expected_len; i++)
        diff |= (unsigned char)(expected[i] ^ (i < given_len ? given[i] : 0));
    return diff == 0;
}

/* The request comes from another site: an Origin other than this server's ("http://" and the
 * Host it was asked by), or the browser's Sec-Fetch-Site saying so. */
static bool cross_site(const atv312d_http_request_t *request)
{
    if (request->fetch_site && strcmp(request->fetch_site, "same-origin") != 0 &&
        strcmp(request->fetch_site, "none") != 0)
        return true;
    if (!request->origin)
        return false;
    if (!request->host || strncmp(request->origin, "http://", 7) != 0)
        return true;
    return strcmp(request->origin + 7, request->host) != 0;
}

/* "application/json", with parameters ("; charset=utf-8") or not. */
static bool is_json(const char *content_type)
{
    const char *type = "application/json";
    size_t n = strlen(type);
    return content_type && strncasecmp(content_type, type, n) == 0 &&
           (content_type[n] == '\0' || content_type[n] == ';' || content_type[n] == ' ');
}

/* ---- POST /api/command ---- */

static const char *skip_space(const char *p, const char *end)
{
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n'))
        p++;
    return p;
}

/* A JSON string at p into out (printable ASCII and tabs: a command line); the position after
 * it, or NULL. */
static const char *parse_string(const char *p, const char *end, char *out, size_t cap)
{
    if (p >= end || *p++ != '"')
        return NULL;
    size_t n = 0;
    while (p < end && *p != '"') {
        unsigned c = (unsigned char)*p++;
        if (c == '\\' && p < end) {
            char e = *p++;
            if (e == 'u' && end - p >= 4) {
                char hex[5] = {p[0], p[1], p[2], p[3], '\0'};
                char *hex_end;
                c = (unsigned)strtoul(hex, &hex_end, 16);
                if (*hex_end != '\0')
                    return NULL;
                p += 4;
            } else if (e == '"' || e == '\\' || e == '/')
                c = (unsigned char)e;
            else if (e == 't')
                c = '\t';
            else
                return NULL;
        }
        if ((c < 0x20 && c != '\t') || c > 0x7E || n + 1 >= cap)
            return NULL;
        out[n++] = (char)c;
    }
    if (p >= end)
        return NULL;
    out[n] = '\0';
    return p + 1;
}

/* The body {"command":"fault 4 OHF"} (spaces allowed between the tokens): the command. */
static bool parse_command_body(const char *body, size_t len, char *command, size_t cap)
{
    const char *end = body + len;
    char key[16];
    const char *p = skip_space(body, end);
    if (p >= end || *p++ != '{')
        return false;
    p = parse_string(skip_space(p, end), end, key, sizeof key);
    if (!p || strcmp(key, "command") != 0)
        return false;
    p = skip_space(p, end);
    if (p >= end || *p++ != ':')
        return false;
    p = parse_string(skip_space(p, end), end, command, cap);
    if (!p)
        return false;
    p = skip_space(p, end);
    if (p >= end || *p++ != '}')
        return false;
    return skip_space(p, end) == end;
}

/* The command's checks on the headers: 403, 415 or 413 with the reason, or true. */
static bool command_allowed(atv312d_http_t *http, const atv312d_http_request_t *request,
                            atv312d_http_answer_t *answer)
{
    const atv312d_http_settings_t *settings = &http->settings;
    if (!settings->actions)
        answer_error(http, request, answer, 403,
                     "actions are off: start atv312d with --http-actions to allow them");
    else if (settings->token[0] && !request->token)
        answer_error(http, request, answer, 403,
                     "this server needs its token: send the secret of --http-token in the "
                     "header " TOKEN_HEADER);
    else if (settings->token[0] && !token_matches(settings->token, request->token))
        answer_error(http, request, answer, 403, "wrong token in " TOKEN_HEADER);
    else if (cross_site(request))
        answer_error(http, request, answer, 403,
                     "cross-site request refused: Origin %s is not this server (http://%s)",
                     shown(request->origin), shown(request->host));
    else if (!is_json(request->content_type))
        answer_error(http, request, answer, 415,
                     "Content-Type %s: send application/json, {\"command\":\"...\"}",
                     shown(request->content_type));
    else if (request->body_too_long ||
             (request->content_length &&
              strtoull(request->content_length, NULL, 10) > ATV312D_HTTP_BODY_MAX))
        answer_error(http, request, answer, 413, "the body is longer than %d bytes",
                     ATV312D_HTTP_BODY_MAX);
    else
        return true;
    return false;
}

/* Runs the body's command as `atv312d ctl` would: {"ok":true,"reply":"ok ..."} or 400 with
 * {"ok":false,"error":"...","reply":"error: ..."}. */
static void run_command(atv312d_http_t *http, const atv312d_http_request_t *request,
                        atv312d_http_answer_t *answer)
{
    char command[ATV312D_CONTROL_LINE_MAX];
    if (!parse_command_body(request->body, request->body_len, command, sizeof command)) {
        answer_error(http, request, answer, 400,
                     "the body must be {\"command\":\"...\"}: one command line of printable "
                     "characters, at most %d",
                     ATV312D_CONTROL_LINE_MAX - 1);
        return;
    }
    if (strncmp(command, ATV312D_CONTROL_JSON_PREFIX, strlen(ATV312D_CONTROL_JSON_PREFIX)) == 0) {
        answer_error(http, request, answer, 400,
                     "give the command without 'json ': its reply is a line");
        return;
    }
    bool ok =
        atv312d_control_execute(http->control, command, http->reply, ATV312D_CONTROL_REPLY_MAX);
    co_log(CO_LOG_INFO, "http %s: %s: %s", request->peer ? request->peer : "?", command,
           http->reply);
    const char *error = "error: ";
    cli_json_t json;
    cli_json_init(&json, http->buf, ATV312D_HTTP_STATE_MAX);
    cli_json_begin_object(&json, NULL);
    cli_json_bool(&json, "ok", ok);
    if (!ok)
        cli_json_str(&json, "error",
                     strncmp(http->reply, error, strlen(error)) == 0 ? http->reply + strlen(error)
                                                                     : http->reply);
    cli_json_str(&json, "reply", http->reply);
    cli_json_end_object(&json);
    answer_json(http, answer, ok ? 200 : 400, cli_json_finish(&json));
}

/* ---- routes ---- */

static bool method_is(const atv312d_http_request_t *request, const char *method)
{
    return strcmp(request->method, method) == 0;
}

static bool readable_method(const atv312d_http_request_t *request)
{
    return method_is(request, "GET") || method_is(request, "HEAD");
}

static void answer_method_not_allowed(atv312d_http_t *http, const atv312d_http_request_t *request,
                                      atv312d_http_answer_t *answer, const char *allow)
{
    answer_error(http, request, answer, 405, "%s %s: this path takes %s", shown(request->method),
                 shown(request->path), allow);
    answer->allow = allow;
}

static const atv312d_web_asset_t *find_asset(const char *path)
{
    if (strcmp(path, "/") == 0)
        path = "/index.html";
    for (size_t i = 0; i < atv312d_web_asset_count; i++) {
        if (strcmp(atv312d_web_assets[i].path, path) == 0)
            return &atv312d_web_assets[i];
    }
    return NULL;
}

static void answer_asset(const atv312d_web_asset_t *asset, const atv312d_http_request_t *request,
                         atv312d_http_answer_t *answer)
{
    bool fresh = request->if_none_match && strcmp(request->if_none_match, asset->etag) == 0;
    *answer = (atv312d_http_answer_t){.status = fresh ? 304 : 200,
                                      .content_type = asset->content_type,
                                      .body = fresh ? NULL : asset->data,
                                      .body_len = fresh ? 0 : asset->size,
                                      .cache_control = "no-cache",
                                      .etag = asset->etag};
}

static bool handle_api(atv312d_http_t *http, const atv312d_http_request_t *request,
                       atv312d_http_answer_t *answer)
{
    const char *path = request->path;
    if (strcmp(path, "/api/command") == 0) {
        if (!method_is(request, "POST"))
            answer_method_not_allowed(http, request, answer, "POST");
        else if (command_allowed(http, request, answer)) {
            if (!request->body)
                return true;
            run_command(http, request, answer);
        }
        return false;
    }
    bool bench = strcmp(path, "/api/bench") == 0, state = strcmp(path, "/api/state") == 0;
    bool events = strcmp(path, "/api/events") == 0;
    if (!bench && !state && !events)
        answer_error(http, request, answer, 404, "no such path: %s (the API: docs/web.md)",
                     shown(path));
    else if (events && !method_is(request, "GET"))
        answer_method_not_allowed(http, request, answer, "GET");
    else if (events && http->stream_count >= ATV312D_HTTP_STREAMS_MAX)
        answer_error(http, request, answer, 503,
                     "busy: %d event streams are open, the most at once; try again in a few "
                     "seconds (the page and the API still answer)",
                     ATV312D_HTTP_STREAMS_MAX);
    else if (!events && !readable_method(request))
        answer_method_not_allowed(http, request, answer, "GET, HEAD");
    else if (bench)
        answer_json(http, answer, 200, format_bench(http, http->buf, ATV312D_HTTP_STATE_MAX));
    else if (state)
        answer_json(http, answer, 200, format_state(http, http->buf, ATV312D_HTTP_STATE_MAX));
    else
        *answer = (atv312d_http_answer_t){.status = 200,
                                          .content_type = "text/event-stream",
                                          .cache_control = "no-store",
                                          .events = true};
    return false;
}

bool atv312d_http_handle(atv312d_http_t *http, const atv312d_http_request_t *request,
                         atv312d_http_answer_t *answer)
{
    if (request->target_len > ATV312D_HTTP_TARGET_MAX) {
        answer_error(http, request, answer, 414,
                     "the request target is %zu bytes, longer than %d: no path of this server is",
                     request->target_len, ATV312D_HTTP_TARGET_MAX);
        return false;
    }
    if (request->head_len > ATV312D_HTTP_HEAD_MAX) {
        answer_error(http, request, answer, 431,
                     "the request head is %zu bytes, longer than %d: send fewer or shorter "
                     "headers (cookies?)",
                     request->head_len, ATV312D_HTTP_HEAD_MAX);
        return false;
    }
    /* On loopback the server answers only to its names: a page of another site that renamed
     * itself to 127.0.0.1 (DNS rebinding) still sends its own name as Host. */
    if (http->settings.address.loopback && request->host && !host_is_loopback(request->host)) {
        answer_error(http, request, answer, 403,
                     "Host %s is not this server: it answers on loopback as http://%s/",
                     shown(request->host), http->settings.address.text);
        return false;
    }
    if (strncmp(request->path, "/api/", 5) == 0)
        return handle_api(http, request, answer);
    const atv312d_web_asset_t *asset = find_asset(request->path);
    if (!asset)
        answer_error(http, request, answer, 404, "no such page: %s", shown(request->path));
    else if (!readable_method(request))
        answer_method_not_allowed(http, request, answer, "GET, HEAD");
    else
        answer_asset(asset, request, answer);
    return false;
}

/* ---- the event streams ---- */

struct atv312d_http_stream {
    atv312d_http_t *http;
    struct MHD_Connection *connection;
    char *text; /* the event being written */
    size_t len, sent;
    uint64_t sequence; /* of the event in text */
    bool suspended;    /* waiting for the next event */
    atv312d_http_stream_t *next;
};

/* "event: state\ndata: {...}\n\n" into buf (EVENT_MAX bytes). */
static size_t format_event(atv312d_http_t *http, char *buf)
{
    size_t prefix = strlen(EVENT_PREFIX);
    memcpy(buf, EVENT_PREFIX, prefix);
    size_t len = prefix + format_state(http, buf + prefix, ATV312D_HTTP_STATE_MAX);
    memcpy(buf + len, EVENT_SUFFIX, strlen(EVENT_SUFFIX));
    return len + strlen(EVENT_SUFFIX);
}

/* The library asks for the stream's next bytes: the rest of its event, then the latest event
 * when there is a newer one (a slow client skips those it had no time for), else the connection
 * waits, suspended, for the next one. */
static ssize_t stream_read(void *cls, uint64_t pos, char *buf, size_t max)
{
    (void)pos;
    atv312d_http_stream_t *stream = cls;
    atv312d_http_t *http = stream->http;
    if (stream->sent == stream->len) {
        if (stream->sequence == http->event_sequence) {
            http->mhd.suspend_connection(stream->connection);
            stream->suspended = true;
            return 0;
        }
        memcpy(stream->text, http->event, http->event_len);
        stream->len = http->event_len;
        stream->sent = 0;
        stream->sequence = http->event_sequence;
    }
    size_t n = stream->len - stream->sent < max ? stream->len - stream->sent : max;
    memcpy(buf, stream->text + stream->sent, n);
    stream->sent += n;
    return (ssize_t)n;
}

/* The connection closed: the stream ends; with the last one the events stop. */
static void stream_free(void *cls)
{
    atv312d_http_stream_t *stream = cls;
    atv312d_http_t *http = stream->http;
    for (atv312d_http_stream_t **p = &http->streams; *p; p = &(*p)->next) {
        if (*p == stream) {
            *p = stream->next;
            break;
        }
    }
    if (--http->stream_count == 0)
        http->next_event = CO_TIME_NEVER;
    free(stream->text);
    free(stream);
}

/* A new stream: its first event at once, the next with everyone's. */
static struct MHD_Response *stream_start(atv312d_http_t *http, struct MHD_Connection *connection)
{
    atv312d_http_stream_t *stream = calloc(1, sizeof *stream);
    char *text = malloc(EVENT_MAX);
    struct MHD_Response *response =
        stream && text ? http->mhd.create_response_from_callback(MHD_SIZE_UNKNOWN, EVENT_BLOCK,
                                                                 stream_read, stream, stream_free)
                       : NULL;
    if (!response) {
        free(text);
        free(stream);
        return NULL;
    }
    *stream = (atv312d_http_stream_t){.http = http,
                                      .connection = connection,
                                      .text = text,
                                      .sequence = http->event_sequence,
                                      .next = http->streams};
    stream->len = format_event(http, text);
    http->streams = stream;
    if (http->stream_count++ == 0)
        http->next_event = http->loop->now + ATV312D_HTTP_EVENT_PERIOD_MS * US_PER_MS;
    return response;
}

/* Every period while a stream is open: the state formatted once, every waiting stream
 * resumed. */
static void publish_event(atv312d_http_t *http, co_time_t now)
{
    http->event_len = format_event(http, http->event);
    http->event_sequence++;
    for (atv312d_http_stream_t *s = http->streams; s; s = s->next) {
        if (s->suspended) {
            s->suspended = false;
            http->mhd.resume_connection(s->connection);
        }
    }
    http->next_event += ATV312D_HTTP_EVENT_PERIOD_MS * US_PER_MS;
    if (http->next_event <= now)
        http->next_event = now + ATV312D_HTTP_EVENT_PERIOD_MS * US_PER_MS;
}

/* ---- the server in the loop ---- */

struct atv312d_http_client {
    struct MHD_Connection *connection;
    struct sockaddr_storage addr;
    char peer[INET6_ADDRSTRLEN + 8]; /* "127.0.0.1:40422", for the log */
    /* When its request must have arrived whole; CO_TIME_NEVER while an answer is written (the
     * silence limit then applies) or a stream is open. */
    co_time_t deadline;
    bool request_started; /* its request line came: a request is under way */
    bool answered_before; /* an answer was sent on it: idle now, kept alive */
    atv312d_http_client_t *next;
};

static co_time_t request_deadline(void)
{
    return co_linux_now() + (co_time_t)ATV312D_HTTP_REQUEST_DEADLINE_S * 1000000;
}

/* "127.0.0.1:40422", "[::1]:40422". */
static void format_peer(const struct sockaddr *addr, char *peer, size_t len)
{
    char host[INET6_ADDRSTRLEN] = "?";
    if (addr->sa_family == AF_INET) {
        const struct sockaddr_in *v4 = (const struct sockaddr_in *)(const void *)addr;
        inet_ntop(AF_INET, &v4->sin_addr, host, sizeof host);
        snprintf(peer, len, "%s:%u", host, ntohs(v4->sin_port));
    } else if (addr->sa_family == AF_INET6) {
        const struct sockaddr_in6 *v6 = (const struct sockaddr_in6 *)(const void *)addr;
        inet_ntop(AF_INET6, &v6->sin6_addr, host, sizeof host);
        snprintf(peer, len, "[%s]:%u", host, ntohs(v6->sin6_port));
    } else
        snprintf(peer, len, "?");
}

/* The same client address, whatever the port. */
static bool same_address(const struct sockaddr *a, const struct sockaddr *b)
{
    if (a->sa_family != b->sa_family)
        return false;
    if (a->sa_family == AF_INET)
        return ((const struct sockaddr_in *)(const void *)a)->sin_addr.s_addr ==
               ((const struct sockaddr_in *)(const void *)b)->sin_addr.s_addr;
    return a->sa_family == AF_INET6 &&
           memcmp(&((const struct sockaddr_in6 *)(const void *)a)->sin6_addr,
                  &((const struct sockaddr_in6 *)(const void *)b)->sin6_addr,
                  sizeof(struct in6_addr)) == 0;
}

/* The library asks before it takes a connection: past the connections held at once, or past
 * those of one address, the new one is closed at once (the library closes it), logged. */
static enum MHD_Result accept_policy(void *cls, const struct sockaddr *addr, socklen_t addrlen)
{
    (void)addrlen;
    const atv312d_http_t *http = cls;
    size_t from_address = 0;
    for (const atv312d_http_client_t *c = http->clients; c; c = c->next)
        from_address += same_address((const struct sockaddr *)&c->addr, addr);
    char peer[INET6_ADDRSTRLEN + 8];
    format_peer(addr, peer, sizeof peer);
    if (http->client_count >= ATV312D_HTTP_CONNECTIONS_MAX)
        co_log(CO_LOG_WARN, "http %s: refused, closed: %d connections are held, the most at once",
               peer, ATV312D_HTTP_CONNECTIONS_MAX);
    else if (from_address >= ATV312D_HTTP_PER_ADDRESS_MAX)
        co_log(CO_LOG_WARN,
               "http %s: refused, closed: %zu connections from its address, the most for one", peer,
               from_address);
    else
        return MHD_YES;
    return MHD_NO;
}

static void on_connection(void *cls, struct MHD_Connection *connection, void **socket_context,
                          enum MHD_ConnectionNotificationCode code)
{
    atv312d_http_t *http = cls;
    atv312d_http_client_t *client = *socket_context;
    if (code == MHD_CONNECTION_NOTIFY_STARTED) {
        const union MHD_ConnectionInfo *info =
            http->mhd.get_connection_info(connection, MHD_CONNECTION_INFO_CLIENT_ADDRESS);
        client = calloc(1, sizeof *client);
        if (!client || !info) {
            free(client); /* no request of it is served: on_request closes it */
            return;
        }
        client->connection = connection;
        memcpy(&client->addr, info->client_addr,
               info->client_addr->sa_family == AF_INET6 ? sizeof(struct sockaddr_in6)
                                                        : sizeof(struct sockaddr_in));
        format_peer(info->client_addr, client->peer, sizeof client->peer);
        client->deadline = request_deadline();
        client->next = http->clients;
        http->clients = client;
        http->client_count++;
        *socket_context = client;
    } else if (client) {
        for (atv312d_http_client_t **p = &http->clients; *p; p = &(*p)->next) {
            if (*p == client) {
                *p = client->next;
                break;
            }
        }
        http->client_count--;
        free(client);
        *socket_context = NULL;
    }
}

static atv312d_http_client_t *client_of(const atv312d_http_t *http,
                                        struct MHD_Connection *connection)
{
    const union MHD_ConnectionInfo *info =
        http->mhd.get_connection_info(connection, MHD_CONNECTION_INFO_SOCKET_CONTEXT);
    return info ? info->socket_context : NULL;
}

/* Closes the connections whose request has not arrived whole by its deadline: shut down, the
 * library finds them ended at its next run and closes them. */
static void enforce_deadlines(atv312d_http_t *http, co_time_t now)
{
    for (atv312d_http_client_t *c = http->clients; c; c = c->next) {
        if (c->deadline > now)
            continue;
        c->deadline = CO_TIME_NEVER;
        if (c->request_started || !c->answered_before)
            co_log(CO_LOG_WARN, "http %s: refused, closed: %s within %d s", c->peer,
                   c->request_started ? "its request did not arrive whole" : "no request came",
                   ATV312D_HTTP_REQUEST_DEADLINE_S);
        else
            co_log(CO_LOG_DEBUG, "http %s: closed: idle %d s after its answer", c->peer,
                   ATV312D_HTTP_REQUEST_DEADLINE_S);
        const union MHD_ConnectionInfo *info =
            http->mhd.get_connection_info(c->connection, MHD_CONNECTION_INFO_CONNECTION_FD);
        if (info)
            shutdown(info->connect_fd, SHUT_RDWR);
    }
}

/* The earliest deadline of a request, or CO_TIME_NEVER. */
static co_time_t next_deadline(const atv312d_http_t *http)
{
    co_time_t next = CO_TIME_NEVER;
    for (const atv312d_http_client_t *c = http->clients; c; c = c->next)
        next = c->deadline < next ? c->deadline : next;
    return next;
}

/* One request being read, from its request line (the URI callback) to its answer. */
typedef struct request_state {
    size_t target_len;
    bool headers_seen; /* the handler's first call, with the whole head, came */
    bool reads_body;   /* a POST /api/command whose headers passed: its body is kept */
    char body[ATV312D_HTTP_BODY_MAX];
    size_t body_len;
    bool body_too_long;
} request_state_t;

/* The request line came whole: the request is under way, and its target's length is known
 * before the library cuts the query off and decodes the path. */
static void *on_request_line(void *cls, const char *uri, struct MHD_Connection *connection)
{
    atv312d_http_client_t *client = client_of(cls, connection);
    if (client)
        client->request_started = true;
    request_state_t *state = calloc(1, sizeof *state);
    if (state)
        state->target_len = strlen(uri);
    return state;
}

static void on_completed(void *cls, struct MHD_Connection *connection, void **req_cls,
                         enum MHD_RequestTerminationCode code)
{
    atv312d_http_client_t *client = client_of(cls, connection);
    free(*req_cls);
    *req_cls = NULL;
    if (client && code == MHD_REQUEST_TERMINATED_COMPLETED_OK) {
        client->request_started = false;
        client->answered_before = true;
        client->deadline = request_deadline();
    }
}

/* The part of a body that fits; the rest is counted as too long and dropped. */
static void keep_body(request_state_t *state, const char *upload, size_t size)
{
    if (!state->reads_body)
        return;
    size_t room = sizeof state->body - state->body_len;
    size_t n = size < room ? size : room;
    memcpy(state->body + state->body_len, upload, n);
    state->body_len += n;
    state->body_too_long |= n < size;
}

static const char *header(const atv312d_http_t *http, struct MHD_Connection *connection,
                          const char *name)
{
    return http->mhd.lookup_connection_value(connection, MHD_HEADER_KIND, name);
}

/* Headers every answer carries: no sniffing, no framing, no referrer. A page is held to its own
 * origin's scripts, styles and images (inline styles allowed), and may connect only there. */
static void add_common_headers(const atv312d_http_t *http, struct MHD_Response *response,
                               const atv312d_http_answer_t *answer)
{
    const atv312d_mhd_t *mhd = &http->mhd;
    mhd->add_response_header(response, "X-Content-Type-Options", "nosniff");
    mhd->add_response_header(response, "X-Frame-Options", "DENY");
    mhd->add_response_header(response, "Referrer-Policy", "no-referrer");
    mhd->add_response_header(response, "Content-Security-Policy",
                             "default-src 'self'; style-src 'self' 'unsafe-inline'; img-src "
                             "'self' data:; frame-ancestors 'none'");
    if (answer->content_type)
        mhd->add_response_header(response, MHD_HTTP_HEADER_CONTENT_TYPE, answer->content_type);
    if (answer->cache_control)
        mhd->add_response_header(response, MHD_HTTP_HEADER_CACHE_CONTROL, answer->cache_control);
    if (answer->etag)
        mhd->add_response_header(response, MHD_HTTP_HEADER_ETAG, answer->etag);
    if (answer->allow)
        mhd->add_response_header(response, MHD_HTTP_HEADER_ALLOW, answer->allow);
}

static enum MHD_Result queue_answer(atv312d_http_t *http, struct MHD_Connection *connection,
                                    const atv312d_http_answer_t *answer)
{
    struct MHD_Response *response;
    if (answer->events)
        response = stream_start(http, connection);
    else if (answer->body == http->buf)
        response = http->mhd.create_response_from_buffer(answer->body_len, http->buf,
                                                         MHD_RESPMEM_MUST_COPY);
    else
        response = http->mhd.create_response_from_buffer(answer->body_len, (void *)answer->body,
                                                         MHD_RESPMEM_PERSISTENT);
    if (!response)
        return MHD_NO;
    add_common_headers(http, response, answer);
    if (answer->status == 503) {
        http->mhd.add_response_header(response, MHD_HTTP_HEADER_CONNECTION, "close");
        http->mhd.add_response_header(response, MHD_HTTP_HEADER_RETRY_AFTER, "5");
    }
    enum MHD_Result result = http->mhd.queue_response(connection, answer->status, response);
    http->mhd.destroy_response(response);
    return result;
}

/* The head's length as the library read it, once it has read it whole. */
static size_t head_length(const atv312d_http_t *http, struct MHD_Connection *connection)
{
    const union MHD_ConnectionInfo *info =
        http->mhd.get_connection_info(connection, MHD_CONNECTION_INFO_REQUEST_HEADER_SIZE);
    return info ? info->header_size : 0;
}

static enum MHD_Result on_request(void *cls, struct MHD_Connection *connection, const char *url,
                                  const char *method, const char *version, const char *upload,
                                  size_t *upload_size, void **req_cls)
{
    (void)version;
    atv312d_http_t *http = cls;
    request_state_t *state = *req_cls;
    atv312d_http_client_t *client = client_of(http, connection);
    if (!state || !client)
        return MHD_NO; /* out of memory: the connection is closed */
    if (!state->headers_seen) {
        state->headers_seen = true;
        /* The answer comes with the last call, after the body (answered on the first call the
         * library would close the connection); only a POST is checked on its headers first. */
        if (strcmp(method, MHD_HTTP_METHOD_POST) != 0)
            return MHD_YES;
    } else if (*upload_size > 0) {
        keep_body(state, upload, *upload_size);
        *upload_size = 0;
        return MHD_YES;
    }
    atv312d_http_request_t request = {
        .method = method,
        .path = url,
        .host = header(http, connection, MHD_HTTP_HEADER_HOST),
        .origin = header(http, connection, "Origin"),
        .fetch_site = header(http, connection, "Sec-Fetch-Site"),
        .content_type = header(http, connection, MHD_HTTP_HEADER_CONTENT_TYPE),
        .content_length = header(http, connection, MHD_HTTP_HEADER_CONTENT_LENGTH),
        .token = header(http, connection, TOKEN_HEADER),
        .if_none_match = header(http, connection, MHD_HTTP_HEADER_IF_NONE_MATCH),
        .body = state->reads_body ? state->body : NULL,
        .body_len = state->body_len,
        .body_too_long = state->body_too_long,
        .target_len = state->target_len,
        .head_len = head_length(http, connection),
        .peer = client->peer,
    };
    atv312d_http_answer_t answer;
    /* A POST is checked on its headers first: refused, its body is never read. */
    if (atv312d_http_handle(http, &request, &answer)) {
        state->reads_body = true;
        return MHD_YES;
    }
    co_log(CO_LOG_DEBUG, "http %s: %s %s: %u", client->peer, method, url, answer.status);
    client->deadline = CO_TIME_NEVER;
    return queue_answer(http, connection, &answer);
}

/* The library's own lines at debug, but its refusals (a request it cannot parse or hold:
 * docs/web.md, "Limits") at warn: it does not say to which connection. */
static void log_library(void *cls, const char *format, va_list args)
{
    (void)cls;
    char message[512];
    vsnprintf(message, sizeof message, format, args);
    message[strcspn(message, "\n")] = '\0';
    unsigned status;
    if (sscanf(message, "Error processing request (HTTP response code is %u", &status) == 1)
        co_log(CO_LOG_WARN, "http: refused by the library, %u: its own answer, in HTML", status);
    else
        co_log(CO_LOG_DEBUG, "http: %s", message);
}

/* The timer to the earliest of MHD's next timeout and the next request's deadline (only while a
 * connection exists) and the next event (only while a stream is open); disarmed when none. */
static void arm_timer(atv312d_http_t *http)
{
    co_time_t deadline = next_deadline(http);
    if (http->next_event < deadline)
        deadline = http->next_event;
    MHD_UNSIGNED_LONG_LONG timeout_ms;
    if (http->mhd.get_timeout(http->daemon, &timeout_ms) == MHD_YES) {
        co_time_t due = co_linux_now() + (co_time_t)timeout_ms * US_PER_MS;
        if (due < deadline)
            deadline = due;
    }
    struct itimerspec spec = {0};
    if (deadline != CO_TIME_NEVER) {
        /* 0 would disarm: a deadline at 0 is the first instant instead, passed already. */
        spec.it_value.tv_sec = (time_t)(deadline / 1000000);
        spec.it_value.tv_nsec = (long)(deadline % 1000000) * 1000 + (deadline == 0);
    }
    if (timerfd_settime(http->timer_fd, TFD_TIMER_ABSTIME, &spec, NULL) != 0)
        co_log(CO_LOG_ERROR, "http: timerfd_settime: %s", strerror(errno));
}

static void run_library(atv312d_http_t *http)
{
    http->mhd.run(http->daemon);
    arm_timer(http);
}

static void on_ready(void *ctx, int fd)
{
    (void)fd;
    run_library(ctx);
}

static void on_timer(void *ctx, int fd)
{
    atv312d_http_t *http = ctx;
    uint64_t expirations;
    if (read(fd, &expirations, sizeof expirations) < 0 && errno != EAGAIN)
        co_log(CO_LOG_WARN, "http: timer: %s", strerror(errno));
    co_time_t now = co_linux_now();
    if (http->stream_count > 0 && now >= http->next_event)
        publish_event(http, now);
    enforce_deadlines(http, now);
    run_library(http);
}

int atv312d_http_init(atv312d_http_t *http, co_linux_loop_t *loop,
                      const atv312d_http_settings_t *settings, const atv312d_control_t *control)
{
    *http = (atv312d_http_t){.loop = loop,
                             .control = control,
                             .settings = *settings,
                             .mhd_fd = -1,
                             .timer_fd = -1,
                             .next_event = CO_TIME_NEVER,
                             .rate_time = loop->now,
                             .rate_frames = loop->stats.rx + loop->stats.tx};
    http->buf = malloc(ATV312D_HTTP_STATE_MAX);
    http->event = malloc(EVENT_MAX);
    http->reply = malloc(ATV312D_CONTROL_REPLY_MAX);
    if (http->buf && http->event && http->reply)
        return 0;
    atv312d_http_close(http);
    return EX_OSERR;
}

static int open_failed(atv312d_http_t *http, const char *what, int status)
{
    co_log(CO_LOG_ERROR, "--http %s: %s: %s", http->settings.address.text, what, strerror(errno));
    atv312d_http_close(http);
    return status;
}

int atv312d_http_open(atv312d_http_t *http, co_linux_loop_t *loop,
                      const atv312d_http_settings_t *settings, const atv312d_control_t *control)
{
    int rc = atv312d_http_init(http, loop, settings, control);
    if (rc != 0)
        return rc;
    char err[512];
    rc = atv312d_mhd_load(&http->mhd, err, sizeof err);
    if (rc != 0) {
        co_log(CO_LOG_ERROR, "--http: %s", err);
        atv312d_http_close(http);
        return rc;
    }
    const atv312d_http_address_t *address = &settings->address;
    unsigned flags = MHD_USE_EPOLL | MHD_ALLOW_SUSPEND_RESUME | MHD_USE_ERROR_LOG;
    if (address->addr.ss_family == AF_INET6)
        flags |= MHD_USE_IPv6;
    uint16_t port = ntohs(((const struct sockaddr_in *)(const void *)&address->addr)->sin_port);
    /* The library's own cap on connections is one above the server's, which accept_policy
     * applies first and logs. */
    http->daemon = http->mhd.start_daemon(
        flags, port, accept_policy, http, on_request, http, MHD_OPTION_EXTERNAL_LOGGER, log_library,
        http, MHD_OPTION_SOCK_ADDR, &address->addr, MHD_OPTION_CONNECTION_LIMIT,
        (unsigned)ATV312D_HTTP_CONNECTIONS_MAX + 1, MHD_OPTION_URI_LOG_CALLBACK, on_request_line,
        http, MHD_OPTION_CONNECTION_MEMORY_LIMIT, (size_t)ATV312D_HTTP_CONNECTION_MEMORY,
        MHD_OPTION_CONNECTION_TIMEOUT, (unsigned)ATV312D_HTTP_TIMEOUT_S,
        MHD_OPTION_NOTIFY_CONNECTION, on_connection, http, MHD_OPTION_NOTIFY_COMPLETED,
        on_completed, http, MHD_OPTION_SIGPIPE_HANDLED_BY_APP, 1, MHD_OPTION_END);
    if (!http->daemon)
        return open_failed(http, "cannot listen (in use, or not an address of this machine?)",
                           EX_CANTCREAT);
    const union MHD_DaemonInfo *info =
        http->mhd.get_daemon_info(http->daemon, MHD_DAEMON_INFO_EPOLL_FD);
    http->mhd_fd = info ? info->epoll_fd : -1;
    info = http->mhd.get_daemon_info(http->daemon, MHD_DAEMON_INFO_BIND_PORT);
    http->port = info ? info->port : port;
    http->timer_fd = timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
    if (http->mhd_fd < 0 || co_linux_loop_watch(loop, http->mhd_fd, on_ready, http) != 0)
        return open_failed(http, "epoll", EX_OSERR);
    if (http->timer_fd < 0 || co_linux_loop_watch(loop, http->timer_fd, on_timer, http) != 0) {
        co_linux_loop_unwatch(loop, http->mhd_fd);
        return open_failed(http, "timer", EX_OSERR);
    }
    char shown_address[sizeof address->text];
    snprintf(shown_address, sizeof shown_address, "%s", address->text);
    char *colon = strrchr(shown_address, ':');
    if (colon)
        snprintf(colon, sizeof shown_address - (size_t)(colon - shown_address), ":%u", http->port);
    co_log(CO_LOG_INFO, "http: listening on http://%s/ (actions %s%s)", shown_address,
           settings->actions ? "on" : "off",
           settings->actions && settings->token[0] ? ", token required" : "");
    return 0;
}

void atv312d_http_close(atv312d_http_t *http)
{
    if (http->daemon) {
        if (http->mhd_fd >= 0)
            co_linux_loop_unwatch(http->loop, http->mhd_fd);
        /* Suspended streams must be resumed for the library to close them. */
        for (atv312d_http_stream_t *s = http->streams; s; s = s->next) {
            if (s->suspended)
                http->mhd.resume_connection(s->connection);
            s->suspended = false;
        }
        http->mhd.stop_daemon(http->daemon);
        http->daemon = NULL;
    }
    atv312d_mhd_unload(&http->mhd);
    if (http->timer_fd >= 0) {
        co_linux_loop_unwatch(http->loop, http->timer_fd);
        close(http->timer_fd);
    }
    http->timer_fd = http->mhd_fd = -1;
    free(http->buf);
    free(http->event);
    free(http->reply);
    http->buf = http->event = http->reply = NULL;
}
