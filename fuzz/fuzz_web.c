/* SPDX-License-Identifier: Apache-2.0 */
/* libFuzzer harness of atv312d's web handler (apps/atv312d/http.c): atv312d_http_handle with
 * what sits in front of it in the daemon's own code, the checks of the request line's and the
 * head's lengths, the Host, Origin and Sec-Fetch-Site rules, the token, the Content-Type and
 * Content-Length, and the parser of the command's JSON body. The input's first byte sets the
 * server (bit 0 --http-actions, bit 1 a token "s3cret" required, bit 2 listening on 0.0.0.0
 * rather than loopback, bit 3 every event stream taken); the rest is an HTTP request as text,
 * split here as libmicrohttpd hands it over: method, target (the path before '?'), headers by
 * name (the first of a name), body. The handler is called as the server calls it: a POST on its
 * headers first, then with its body (at most 1024 bytes kept, the rest counted as too long).
 * Invariants: docs/fuzzing.md. Seeds: fuzz/seeds.py. */
#include "atv312/atv312.h"
#include "atv312d/control_commands.h"
#include "atv312d/http.h"
#include "co_linux/log.h"
#include "rig.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define TOKEN "s3cret"
#define HEADERS_MAX 32

static co_linux_loop_t loop;
static uint8_t od_data[ATV312_OD_DATA_SIZE];
static drive_t drive;
static co_linux_device_t device;
static atv312d_counters_t counters;
static atv312d_control_node_t node;
static atv312d_control_t control;
static atv312d_http_t http;
static atv312d_http_address_t loopback, every_address;
static size_t frames_sent;

static void count_frame(void *user, const co_frame_t *frame)
{
    (void)user, (void)frame;
    frames_sent++;
}

static co_time_t process(void *ctx, co_time_t now)
{
    return drive_process(ctx, now);
}

static const co_linux_device_ops_t ops = {.process = process};

static atv312d_http_address_t address(const char *text, bool is_loopback)
{
    atv312d_http_address_t a = {.len = sizeof(struct sockaddr_in), .loopback = is_loopback};
    a.addr.ss_family = AF_INET;
    snprintf(a.text, sizeof a.text, "%s", text);
    return a;
}

/* Once: the loop (never opened), one ATV312 at node 4 and the handler's buffers. */
static void setup(void)
{
    co_log_setup("fuzz_web", CO_LOG_ERROR); /* every refusal is a warning: not printed */
    snprintf(loop.iface, sizeof loop.iface, "vcan0");
    loopback = address("127.0.0.1:8080", true);
    every_address = address("0.0.0.0:8080", false);
    co_linux_loop_add(&loop, &device, &ops, &drive);
    node = (atv312d_control_node_t){
        .id = 4, .model = "atv312", .drive = &drive, .device = &device, .counters = &counters};
    control = (atv312d_control_t){.nodes = &node, .count = 1};
    atv312d_http_settings_t settings = {.address = loopback};
    rig_check(atv312d_http_init(&http, &loop, &settings, &control) == 0, "out of memory");
}

/* A fresh drive for each input: what one input's command did is not the next one's start. */
static void start_drive(void)
{
    drive_config_t config = {
        .profile = &atv312_profile, .od_data = od_data, .node_id = 4, .send = count_frame};
    rig_check(drive_init(&drive, &config) == 0, "drive_init");
    counters = (atv312d_counters_t){0};
    drive_start(&drive, 0);
    frames_sent = 0;
}

/* ---- the request as text ---- */

typedef struct parsed {
    atv312d_http_request_t request;
    char *names[HEADERS_MAX], *values[HEADERS_MAX];
    size_t headers;
    const char *body;
    size_t body_len;
} parsed_t;

/* Cuts the line at p (to "\n", a "\r" before it dropped); the next line, or NULL at the end. */
static char *cut_line(char *p, char *end)
{
    char *nl = memchr(p, '\n', (size_t)(end - p));
    if (!nl)
        return NULL;
    *nl = '\0';
    if (nl > p && nl[-1] == '\r')
        nl[-1] = '\0';
    return nl + 1;
}

static const char *header(const parsed_t *r, const char *name)
{
    for (size_t i = 0; i < r->headers; i++)
        if (strcasecmp(r->names[i], name) == 0)
            return r->values[i];
    return NULL;
}

/* "METHOD TARGET VERSION\r\n" then "Name: value\r\n"... "\r\n" then the body; false when the
 * request line has no method and target (the library would refuse it itself). */
static bool parse(char *text, size_t len, parsed_t *r)
{
    char *end = text + len, *line = text, *next = cut_line(line, end);
    char *space = strchr(line, ' ');
    if (!next || !space || space == line)
        return false;
    *space = '\0';
    char *target = space + 1;
    char *target_end = strchr(target, ' ');
    if (target_end)
        *target_end = '\0';
    if (target[0] == '\0')
        return false;
    size_t target_len = strlen(target);
    target[strcspn(target, "?")] = '\0';
    *r = (parsed_t){.request = {.method = line, .path = target, .target_len = target_len}};
    for (line = next; line && line < end; line = next) {
        next = cut_line(line, end);
        if (!next || line[0] == '\0')
            break;
        char *colon = strchr(line, ':');
        if (!colon || r->headers == HEADERS_MAX)
            continue;
        *colon = '\0';
        char *value = colon + 1;
        value += strspn(value, " \t");
        r->names[r->headers] = line;
        r->values[r->headers++] = value;
    }
    r->request.head_len = (size_t)((next ? next : end) - text);
    r->body = next ? next : end;
    r->body_len = (size_t)(end - r->body);
    return true;
}

/* ---- invariants ---- */

static const char *skip_ws(const char *p, const char *end)
{
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r'))
        p++;
    return p;
}

/* c is one of the characters of set (never its NUL). */
static bool is_one_of(char c, const char *set)
{
    return c != '\0' && strchr(set, c) != NULL;
}

/* One JSON value at p (RFC 8259, no depth beyond 16); the position after it, or NULL. */
static const char *json_value(const char *p, const char *end, int depth)
{
    p = skip_ws(p, end);
    if (p >= end || depth > 16)
        return NULL;
    if (*p == '"') {
        for (p++; p < end && *p != '"'; p++) {
            if ((unsigned char)*p < 0x20)
                return NULL;
            if (*p != '\\')
                continue;
            if (++p >= end)
                return NULL;
            if (*p == 'u') {
                for (int i = 0; i < 4; i++)
                    if (++p >= end || !is_one_of(*p, "0123456789abcdefABCDEF"))
                        return NULL;
            } else if (!is_one_of(*p, "\"\\/bfnrt"))
                return NULL;
        }
        return p < end ? p + 1 : NULL;
    }
    if (*p == '{' || *p == '[') {
        char close = *p == '{' ? '}' : ']';
        p = skip_ws(p + 1, end);
        if (p < end && *p == close)
            return p + 1;
        for (;;) {
            if (close == '}') {
                p = skip_ws(p, end);
                if (p >= end || *p != '"' || !(p = json_value(p, end, depth + 1)))
                    return NULL;
                p = skip_ws(p, end);
                if (p >= end || *p++ != ':')
                    return NULL;
            }
            if (!(p = json_value(p, end, depth + 1)))
                return NULL;
            p = skip_ws(p, end);
            if (p < end && *p == ',') {
                p++;
                continue;
            }
            return p < end && *p == close ? p + 1 : NULL;
        }
    }
    const char *start = p;
    while (p < end && is_one_of(*p, "-+.eE0123456789truefalsn"))
        p++;
    return p > start ? p : NULL;
}

static bool is_json_object(const char *body, size_t len)
{
    const char *end = body + len, *p = skip_ws(body, end);
    return p < end && *p == '{' && (p = json_value(p, end, 0)) && skip_ws(p, end) == end;
}

static bool known_status(unsigned status)
{
    static const unsigned statuses[] = {200, 304, 400, 403, 404, 405, 413, 414, 415, 431, 503};
    for (size_t i = 0; i < sizeof statuses / sizeof statuses[0]; i++)
        if (status == statuses[i])
            return true;
    return false;
}

static void check_answer(const parsed_t *r, const atv312d_http_answer_t *answer)
{
    rig_check(known_status(answer->status), "an answer's status is none the server gives");
    bool json = answer->content_type && strcmp(answer->content_type, "application/json") == 0;
    rig_check(answer->status < 400 || json, "a refusal without its JSON error");
    if (json) {
        const char *body = answer->body;
        rig_check(is_json_object(body, answer->body_len), "a JSON answer that is not JSON");
        const char *refused = "{\"ok\":false,\"error\":\"";
        bool says_refused =
            answer->body_len > strlen(refused) && strncmp(body, refused, strlen(refused)) == 0;
        rig_check(says_refused == (answer->status >= 400),
                  "a JSON answer that says it is an error when its status does not, or not when "
                  "it does");
    }
    if (answer->events)
        rig_check(answer->status == 200 && strcmp(r->request.path, "/api/events") == 0 &&
                      http.stream_count < ATV312D_HTTP_STREAMS_MAX,
                  "a stream started where none may");
}

/* A command ran (the drive's dictionary or its frames changed): only admitted, and answered
 * with the command's reply. */
static void check_command(const parsed_t *r, const atv312d_http_answer_t *answer, bool ran)
{
    if (!ran)
        return;
    const char *token = header(r, "X-Atv312d-Token");
    rig_check(http.settings.actions, "a command ran with actions off");
    rig_check(!http.settings.token[0] || (token && strcmp(token, TOKEN) == 0),
              "a command ran without the token");
    rig_check(strcmp(r->request.method, "POST") == 0 &&
                  strcmp(r->request.path, "/api/command") == 0 && r->request.body,
              "a command ran from another request than a POST /api/command with its body");
    rig_check(r->request.target_len <= ATV312D_HTTP_TARGET_MAX &&
                  r->request.head_len <= ATV312D_HTTP_HEAD_MAX,
              "a command ran from a request too long");
    rig_check(memmem(answer->body, answer->body_len, "\"reply\":", 8) != NULL,
              "a command ran without its reply in the answer");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static bool ready;
    if (!ready) {
        setup();
        ready = true;
    }
    if (size < 1)
        return 0;
    uint8_t flags = data[0];
    char *text = malloc(size); /* the request's bytes, then a NUL: what ASan guards */
    rig_check(text != NULL, "out of memory");
    memcpy(text, data + 1, size - 1);
    text[size - 1] = '\0';
    parsed_t r;
    if (!parse(text, size - 1, &r)) {
        free(text);
        return 0;
    }
    http.settings.actions = flags & 1;
    snprintf(http.settings.token, sizeof http.settings.token, "%s", flags & 2 ? TOKEN : "");
    http.settings.address = flags & 4 ? every_address : loopback;
    http.stream_count = flags & 8 ? ATV312D_HTTP_STREAMS_MAX : 0;
    r.request.host = header(&r, "Host");
    r.request.origin = header(&r, "Origin");
    r.request.fetch_site = header(&r, "Sec-Fetch-Site");
    r.request.content_type = header(&r, "Content-Type");
    r.request.content_length = header(&r, "Content-Length");
    r.request.token = header(&r, "X-Atv312d-Token");
    r.request.if_none_match = header(&r, "If-None-Match");
    r.request.peer = "127.0.0.1:40000";
    start_drive();
    static uint8_t before[ATV312_OD_DATA_SIZE];
    memcpy(before, od_data, sizeof before);
    atv312d_http_answer_t answer;
    bool wants_body =
        strcmp(r.request.method, "POST") == 0 && atv312d_http_handle(&http, &r.request, &answer);
    if (wants_body || strcmp(r.request.method, "POST") != 0) {
        /* The server keeps at most ATV312D_HTTP_BODY_MAX bytes of a body it reads. */
        size_t kept = r.body_len < ATV312D_HTTP_BODY_MAX ? r.body_len : ATV312D_HTTP_BODY_MAX;
        r.request.body = wants_body ? r.body : NULL;
        r.request.body_len = wants_body ? kept : 0;
        r.request.body_too_long = wants_body && r.body_len > ATV312D_HTTP_BODY_MAX;
        rig_check(!atv312d_http_handle(&http, &r.request, &answer),
                  "the handler asked for a body twice");
    }
    check_answer(&r, &answer);
    check_command(&r, &answer, frames_sent > 0 || memcmp(before, od_data, sizeof before) != 0);
    http.stream_count = 0;
    free(text);
    return 0;
}
