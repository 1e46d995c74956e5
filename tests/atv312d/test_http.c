/* SPDX-License-Identifier: Apache-2.0 */
/* The web surface's handler, request by request, as the server calls it: the status, the headers
 * and the exact JSON of every answer; who may run a command (the option, the token, the origin,
 * the content type, the body's size and shape); the page's files; --http's address and the token
 * file. One ATV312 at node 4, a device of an unopened loop: nothing here reaches a socket (the
 * server on a socket: test_http_server.c). */
#include "atv312/atv312.h"
#include "atv312/atv312_devicenet.h"
#include "atv312d/http.h"
#include "atv312d/options.h"
#include "check_main.h"
#include "co_linux/log.h"

#include <check.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sysexits.h>
#include <unistd.h>

#define NODE 4

static co_linux_loop_t loop;
static uint8_t od_data[ATV312_OD_DATA_SIZE];
static drive_t drive;
static co_linux_device_t device;
static atv312d_counters_t counters;
static atv312d_control_node_t node;
static atv312d_control_t control;
static atv312d_http_t http;
static atv312d_http_answer_t answer;
static char body[ATV312D_HTTP_STATE_MAX];

static void no_send(void *user, const co_frame_t *frame)
{
    (void)user, (void)frame;
}

static co_time_t canopen_process(void *ctx, co_time_t now)
{
    return drive_process(ctx, now);
}

static const co_linux_device_ops_t canopen_ops = {.process = canopen_process};

/* The bench on 127.0.0.1:8080 (or the address given), actions on or off, with or without a
 * token. */
static void start_at(const char *address, bool actions, const char *token)
{
    memset(&loop, 0, sizeof loop);
    snprintf(loop.iface, sizeof loop.iface, "vcan0");
    drive_config_t config = {
        .profile = &atv312_profile, .od_data = od_data, .node_id = NODE, .send = no_send};
    ck_assert_int_eq(drive_init(&drive, &config), 0);
    drive_start(&drive, loop.now);
    co_linux_loop_add(&loop, &device, &canopen_ops, &drive);
    node = (atv312d_control_node_t){
        .id = NODE, .model = "atv312", .drive = &drive, .device = &device, .counters = &counters};
    control = (atv312d_control_t){.nodes = &node, .count = 1};
    atv312d_http_settings_t settings = {.actions = actions};
    char err[256];
    ck_assert_int_eq(atv312d_parse_http_address(address, &settings.address, err, sizeof err), 0);
    snprintf(settings.token, sizeof settings.token, "%s", token ? token : "");
    ck_assert_int_eq(atv312d_http_init(&http, &loop, &settings, &control), 0);
}

static void start(bool actions, const char *token)
{
    start_at("8080", actions, token);
}

static void stop(void)
{
    atv312d_http_close(&http);
}

/* The answer's body as a string. */
static const char *answer_body(void)
{
    ck_assert_uint_lt(answer.body_len, sizeof body);
    if (answer.body_len > 0)
        memcpy(body, answer.body, answer.body_len);
    body[answer.body_len] = '\0';
    return body;
}

static const char *get(const char *path)
{
    atv312d_http_request_t request = {.method = "GET", .path = path, .host = "127.0.0.1:8080"};
    ck_assert(!atv312d_http_handle(&http, &request, &answer));
    return answer_body();
}

/* A command request as a browser on the page sends it: POST, JSON, its own origin. */
static atv312d_http_request_t command_request(const char *json)
{
    return (atv312d_http_request_t){.method = "POST",
                                    .path = "/api/command",
                                    .host = "127.0.0.1:8080",
                                    .origin = "http://127.0.0.1:8080",
                                    .fetch_site = "same-origin",
                                    .content_type = "application/json",
                                    .body = json,
                                    .body_len = json ? strlen(json) : 0};
}

/* The request's headers are checked first (true: read the body), then the whole request. */
static const char *post(atv312d_http_request_t request)
{
    const char *json = request.body;
    request.body = NULL;
    if (!atv312d_http_handle(&http, &request, &answer))
        return answer_body();
    ck_assert_ptr_nonnull(json);
    request.body = json;
    ck_assert(!atv312d_http_handle(&http, &request, &answer));
    return answer_body();
}

START_TEST(bench_describes_each_drive)
{
    start(false, NULL);
    const char *json = get("/api/bench");
    ck_assert_uint_eq(answer.status, 200);
    ck_assert_str_eq(answer.content_type, "application/json");
    ck_assert_str_eq(answer.cache_control, "no-store");
    const char *head = "{\"interface\":\"vcan0\",\"protocol\":\"canopen\",\"actions\":false,"
                       "\"token_required\":false,\"drives\":[{\"node\":4,\"model\":\"ATV312\","
                       "\"faults\":[";
    ck_assert_mem_eq(json, head, strlen(head));
    ck_assert_ptr_nonnull(strstr(json, "{\"code\":\"OHF\",\"name\":\"drive overheating\"}"));
    ck_assert_ptr_nonnull(strstr(json, "{\"code\":\"USF\",\"name\":\"line supply undervoltage\"}"));
    const char *tail = "],\"inputs\":[\"LI1\",\"LI2\",\"LI3\"],\"leds\":[\"RUN\",\"ERR\"]}]}";
    ck_assert_str_eq(json + strlen(json) - strlen(tail), tail);
    stop();
}
END_TEST

static drive_dn_t dn;

static co_time_t devicenet_process(void *ctx, co_time_t now)
{
    return drive_dn_process(ctx, now);
}

static const co_linux_device_ops_t devicenet_ops = {.process = devicenet_process};

/* On DeviceNet the drives are MAC IDs and their LEDs the card's MS and NS. */
START_TEST(bench_on_devicenet)
{
    start(false, NULL);
    memset(&loop, 0, sizeof loop);
    snprintf(loop.iface, sizeof loop.iface, "vcan1");
    drive_config_t config = {
        .profile = &atv312_profile, .od_data = od_data, .node_id = 1, .send = drive_dn_drop_frame};
    ck_assert_int_eq(drive_init(&drive, &config), 0);
    drive_dn_config_t dn_config = {.drive = &drive,
                                   .profile = &atv312_devicenet_profile,
                                   .mac_id = 25,
                                   .serial_number = 0x31200019,
                                   .send = no_send};
    ck_assert_int_eq(drive_dn_init(&dn, &dn_config), 0);
    drive_dn_start(&dn, loop.now);
    co_linux_loop_add(&loop, &device, &devicenet_ops, &dn);
    node = (atv312d_control_node_t){.id = 25,
                                    .model = "atv312",
                                    .drive = &drive,
                                    .devicenet = &dn,
                                    .device = &device,
                                    .counters = &counters};
    const char *json = get("/api/bench");
    const char *head = "{\"interface\":\"vcan1\",\"protocol\":\"devicenet\",\"actions\":false,"
                       "\"token_required\":false,\"drives\":[{\"node\":25,\"model\":\"ATV312\",";
    ck_assert_mem_eq(json, head, strlen(head));
    const char *tail = "],\"inputs\":[\"LI1\",\"LI2\",\"LI3\"],\"leds\":[\"MS\",\"NS\"]}]}";
    ck_assert_str_eq(json + strlen(json) - strlen(tail), tail);
    get("/api/state");
    ck_assert_ptr_nonnull(strstr(body, "\"nodes\":[{\"node\":25,\"ms\":"));
    stop();
}
END_TEST

START_TEST(bench_says_actions_and_token)
{
    start(true, "s3cret");
    get("/api/bench");
    ck_assert_ptr_nonnull(strstr(body, "\"actions\":true,\"token_required\":true,"));
    stop();
}
END_TEST

/* The bus, then each node exactly as the control surface's `--json state` formats it. */
START_TEST(state_is_the_bus_and_the_control_surface_nodes)
{
    start(false, NULL);
    loop.now = 5127000;
    loop.stats.rx = 12;
    loop.stats.tx = 30;
    char expected[4096], node_json[2048];
    atv312d_format_state(&node, true, node_json, sizeof node_json);
    snprintf(expected, sizeof expected,
             "{\"ok\":true,\"time_ms\":5127,\"bus\":{\"state\":\"down\",\"frames_received\":12,"
             "\"frames_sent\":30,\"frames_per_second\":8.2},\"nodes\":[%s]}",
             node_json);
    ck_assert_str_eq(get("/api/state"), expected);
    ck_assert_uint_eq(answer.status, 200);
    ck_assert_ptr_nonnull(strstr(node_json, "\"statusword\":1600,\"reference_rpm\":0,"));
    stop();
}
END_TEST

/* frames_per_second: the frames over the time since the last reading a second or more ago;
 * between two such readings the rate stays. */
START_TEST(frame_rate_over_a_second_or_more)
{
    start(false, NULL);
    loop.now = 1000000;
    loop.stats.tx = 100;
    get("/api/state");
    ck_assert_ptr_nonnull(strstr(body, "\"frames_per_second\":100.0}"));
    loop.now = 1500000;
    loop.stats.tx = 1000;
    get("/api/state");
    ck_assert_ptr_nonnull(strstr(body, "\"frames_per_second\":100.0}"));
    loop.now = 3000000;
    loop.stats.rx = 500;
    get("/api/state");
    ck_assert_ptr_nonnull(strstr(body, "\"frames_per_second\":700.0}"));
    stop();
}
END_TEST

START_TEST(events_start_a_stream)
{
    start(false, NULL);
    get("/api/events");
    ck_assert_uint_eq(answer.status, 200);
    ck_assert(answer.events);
    ck_assert_str_eq(answer.content_type, "text/event-stream");
    atv312d_http_request_t head = {.method = "HEAD", .path = "/api/events"};
    ck_assert(!atv312d_http_handle(&http, &head, &answer));
    ck_assert_uint_eq(answer.status, 405);
    ck_assert_str_eq(answer.allow, "GET");
    stop();
}
END_TEST

START_TEST(page_files_with_their_type_and_etag)
{
    start(false, NULL);
    get("/");
    ck_assert_uint_eq(answer.status, 200);
    ck_assert_str_eq(answer.content_type, "text/html; charset=utf-8");
    ck_assert_str_eq(answer.cache_control, "no-cache");
    ck_assert_ptr_nonnull(answer.etag);
    ck_assert_mem_eq(body, "<!DOCTYPE html>", 15);
    size_t len = answer.body_len;
    const char *etag = answer.etag;
    get("/index.html");
    ck_assert_uint_eq(answer.body_len, len);
    atv312d_http_request_t again = {.method = "GET", .path = "/", .if_none_match = etag};
    ck_assert(!atv312d_http_handle(&http, &again, &answer));
    ck_assert_uint_eq(answer.status, 304);
    ck_assert_uint_eq(answer.body_len, 0);
    ck_assert_str_eq(get("/nope.js"), "{\"ok\":false,\"error\":\"no such page: /nope.js\"}");
    ck_assert_uint_eq(answer.status, 404);
    ck_assert_str_eq(get("/api/nope"),
                     "{\"ok\":false,\"error\":\"no such path: /api/nope (the API: docs/web.md)\"}");
    ck_assert_uint_eq(answer.status, 404);
    stop();
}
END_TEST

START_TEST(wrong_methods_get_405)
{
    start(true, NULL);
    ck_assert_str_eq(get("/api/command"),
                     "{\"ok\":false,\"error\":\"GET /api/command: this path takes POST\"}");
    ck_assert_uint_eq(answer.status, 405);
    ck_assert_str_eq(answer.allow, "POST");
    atv312d_http_request_t request = command_request(NULL);
    request.path = "/api/state";
    ck_assert_str_eq(post(request),
                     "{\"ok\":false,\"error\":\"POST /api/state: this path takes GET, HEAD\"}");
    ck_assert_uint_eq(answer.status, 405);
    request.path = "/";
    post(request);
    ck_assert_uint_eq(answer.status, 405);
    stop();
}
END_TEST

START_TEST(command_runs_as_ctl_runs_it)
{
    start(true, NULL);
    ck_assert_str_eq(post(command_request("{\"command\":\"fault 4 OHF\"}")),
                     "{\"ok\":true,\"reply\":\"ok node 4: OHF (drive overheating), EMCY 4210\"}");
    ck_assert_uint_eq(answer.status, 200);
    ck_assert_ptr_nonnull(drive_fault_latched(&drive));
    ck_assert_str_eq(post(command_request(" {\t\"command\" : \"clear 4 \\u004fHF\" }\n")),
                     "{\"ok\":true,\"reply\":\"ok node 4: cause of OHF removed\"}");
    stop();
}
END_TEST

START_TEST(refused_command_is_400_with_its_reply)
{
    start(true, NULL);
    ck_assert_str_eq(post(command_request("{\"command\":\"fault 9 OHF\"}")),
                     "{\"ok\":false,\"error\":\"node 9 is not present: this daemon runs node-id "
                     "4\",\"reply\":\"error: node 9 is not present: this daemon runs node-id 4\"}");
    ck_assert_uint_eq(answer.status, 400);
    ck_assert_str_eq(post(command_request("{\"command\":\"json state\"}")),
                     "{\"ok\":false,\"error\":\"give the command without 'json ': its reply is a "
                     "line\"}");
    ck_assert_uint_eq(answer.status, 400);
    stop();
}
END_TEST

/* Anything but {"command":"<printable line>"} is 400 and runs nothing. */
START_TEST(malformed_bodies_are_400)
{
    start(true, NULL);
    const char *bodies[] = {
        "",
        "fault 4 OHF",
        "{\"command\":\"fault 4 OHF\"",
        "{\"command\":\"fault 4 OHF\"}x",
        "{\"cmd\":\"fault 4 OHF\"}",
        "{\"command\":\"fault 4 OHF\",\"x\":1}",
        "{\"command\":\"fault 4 OHF\\nfault 4 OCF\"}",
        "{\"command\":\"fault 4 \\u00e9\"}",
        "{\"command\":4}",
        "[\"fault 4 OHF\"]",
    };
    for (size_t i = 0; i < sizeof bodies / sizeof bodies[0]; i++) {
        ck_assert_str_eq(
            post(command_request(bodies[i])),
            "{\"ok\":false,\"error\":\"the body must be {\\\"command\\\":\\\"...\\\"}: "
            "one command line of printable characters, at most 255\"}");
        ck_assert_uint_eq(answer.status, 400);
    }
    ck_assert_ptr_null(drive_fault_latched(&drive));
    stop();
}
END_TEST

START_TEST(actions_off_is_403)
{
    start(false, NULL);
    ck_assert_str_eq(post(command_request("{\"command\":\"fault 4 OHF\"}")),
                     "{\"ok\":false,\"error\":\"actions are off: start atv312d with --http-actions "
                     "to allow them\"}");
    ck_assert_uint_eq(answer.status, 403);
    ck_assert_ptr_null(drive_fault_latched(&drive));
    stop();
}
END_TEST

START_TEST(token_missing_or_wrong_is_403)
{
    start_at("0.0.0.0:8080", true, "s3cret");
    atv312d_http_request_t request = command_request("{\"command\":\"fault 4 OHF\"}");
    ck_assert_str_eq(post(request), "{\"ok\":false,\"error\":\"this server needs its token: send "
                                    "the secret of --http-token in the header "
                                    "X-Atv312d-Token\"}");
    ck_assert_uint_eq(answer.status, 403);
    const char *wrong[] = {"", "s3cre", "s3cret2", "S3CRET"};
    for (size_t i = 0; i < sizeof wrong / sizeof wrong[0]; i++) {
        request.token = wrong[i];
        ck_assert_str_eq(post(request),
                         "{\"ok\":false,\"error\":\"wrong token in X-Atv312d-Token\"}");
        ck_assert_uint_eq(answer.status, 403);
    }
    ck_assert_ptr_null(drive_fault_latched(&drive));
    request.token = "s3cret";
    post(request);
    ck_assert_uint_eq(answer.status, 200);
    stop();
}
END_TEST

/* Another origin, or the browser saying the request is another site's, is refused; no Origin
 * (curl) or the server's own is not. */
START_TEST(cross_site_is_403)
{
    start(true, NULL);
    atv312d_http_request_t request = command_request("{\"command\":\"local 4 on\"}");
    request.origin = "http://evil.example";
    ck_assert_str_eq(post(request),
                     "{\"ok\":false,\"error\":\"cross-site request refused: Origin "
                     "http://evil.example is not this server (http://127.0.0.1:8080)\"}");
    ck_assert_uint_eq(answer.status, 403);
    request.origin = "http://127.0.0.1:8081";
    post(request);
    ck_assert_uint_eq(answer.status, 403);
    request.origin = "null";
    post(request);
    ck_assert_uint_eq(answer.status, 403);
    request.origin = NULL;
    request.fetch_site = "cross-site";
    post(request);
    ck_assert_uint_eq(answer.status, 403);
    request.fetch_site = "same-site";
    post(request);
    ck_assert_uint_eq(answer.status, 403);
    ck_assert(!drive.local);
    request.fetch_site = NULL;
    post(request);
    ck_assert_uint_eq(answer.status, 200);
    ck_assert(drive.local);
    stop();
}
END_TEST

/* A loopback server answers its loopback names only: a site renamed to 127.0.0.1 (DNS
 * rebinding) sends its own name as Host. */
START_TEST(foreign_host_on_loopback_is_403)
{
    start(true, NULL);
    atv312d_http_request_t request = command_request("{\"command\":\"local 4 on\"}");
    request.host = "evil.example:8080";
    request.origin = "http://evil.example:8080";
    ck_assert_str_eq(post(request), "{\"ok\":false,\"error\":\"Host evil.example:8080 is not this "
                                    "server: it answers on loopback as http://127.0.0.1:8080/\"}");
    ck_assert_uint_eq(answer.status, 403);
    atv312d_http_request_t page = {.method = "GET", .path = "/", .host = "evil.example"};
    ck_assert(!atv312d_http_handle(&http, &page, &answer));
    ck_assert_uint_eq(answer.status, 403);
    const char *names[] = {"localhost:8080", "127.0.0.1:8080", "127.1.2.3", "[::1]:8080"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        page.host = names[i];
        ck_assert(!atv312d_http_handle(&http, &page, &answer));
        ck_assert_uint_eq(answer.status, 200);
    }
    stop();
}
END_TEST

START_TEST(other_content_type_is_415)
{
    start(true, NULL);
    atv312d_http_request_t request = command_request("{\"command\":\"local 4 on\"}");
    request.content_type = "text/plain";
    ck_assert_str_eq(post(request), "{\"ok\":false,\"error\":\"Content-Type text/plain: send "
                                    "application/json, {\\\"command\\\":\\\"...\\\"}\"}");
    ck_assert_uint_eq(answer.status, 415);
    request.content_type = "application/x-www-form-urlencoded";
    post(request);
    ck_assert_uint_eq(answer.status, 415);
    request.content_type = "application/jsonp";
    post(request);
    ck_assert_uint_eq(answer.status, 415);
    request.content_type = NULL;
    post(request);
    ck_assert_uint_eq(answer.status, 415);
    request.content_type = "application/json; charset=utf-8";
    post(request);
    ck_assert_uint_eq(answer.status, 200);
    stop();
}
END_TEST

/* Too long, by its Content-Length (refused before the body is read) or as it comes. */
START_TEST(long_body_is_413)
{
    start(true, NULL);
    atv312d_http_request_t request = command_request(NULL);
    request.content_length = "1025";
    ck_assert(!atv312d_http_handle(&http, &request, &answer));
    ck_assert_str_eq(answer_body(),
                     "{\"ok\":false,\"error\":\"the body is longer than 1024 bytes\"}");
    ck_assert_uint_eq(answer.status, 413);
    request.content_length = "1024";
    ck_assert(atv312d_http_handle(&http, &request, &answer));
    request.content_length = NULL;
    request.body = "{\"command\":\"local 4 on\"}";
    request.body_len = strlen(request.body);
    request.body_too_long = true;
    ck_assert(!atv312d_http_handle(&http, &request, &answer));
    ck_assert_uint_eq(answer.status, 413);
    ck_assert(!drive.local);
    stop();
}
END_TEST

static int parse_address(const char *text, atv312d_http_address_t *address)
{
    char err[256];
    return atv312d_parse_http_address(text, address, err, sizeof err);
}

/* ---- refusals: each logged once at warn ---- */

static char logged[4096];

/* Handles the request with the log going to `logged`; the answer's body. */
static const char *handle_logged(const atv312d_http_request_t *request)
{
    FILE *log = tmpfile();
    ck_assert_ptr_nonnull(log);
    fflush(stderr);
    int saved_err = dup(STDERR_FILENO);
    dup2(fileno(log), STDERR_FILENO);
    co_log_setup("atv312d", CO_LOG_WARN);
    atv312d_http_request_t headers_only = *request;
    headers_only.body = NULL;
    bool wants_body = atv312d_http_handle(&http, &headers_only, &answer);
    if (wants_body)
        ck_assert(!atv312d_http_handle(&http, request, &answer));
    dup2(saved_err, STDERR_FILENO);
    close(saved_err);
    rewind(log);
    size_t len = fread(logged, 1, sizeof logged - 1, log);
    logged[len] = '\0';
    fclose(log);
    return answer_body();
}

/* A request target or head longer than the server takes: 414, 431, before anything else. */
START_TEST(long_target_414_long_head_431)
{
    start(true, NULL);
    atv312d_http_request_t request = {.method = "GET",
                                      .path = "/api/state",
                                      .host = "evil.example",
                                      .target_len = ATV312D_HTTP_TARGET_MAX + 1,
                                      .peer = "127.0.0.1:40422"};
    ck_assert_str_eq(handle_logged(&request),
                     "{\"ok\":false,\"error\":\"the request target is 2049 bytes, longer than "
                     "2048: no path of this server is\"}");
    ck_assert_uint_eq(answer.status, 414);
    ck_assert_str_eq(answer.content_type, "application/json");
    ck_assert_str_eq(logged, "atv312d: warn: http 127.0.0.1:40422: GET /api/state: refused, 414: "
                             "the request target is 2049 bytes, longer than 2048: no path of this "
                             "server is\n");
    request.target_len = ATV312D_HTTP_TARGET_MAX;
    request.head_len = ATV312D_HTTP_HEAD_MAX + 1;
    ck_assert_str_eq(handle_logged(&request),
                     "{\"ok\":false,\"error\":\"the request head is 8193 bytes, longer than 8192: "
                     "send fewer or shorter headers (cookies?)\"}");
    ck_assert_uint_eq(answer.status, 431);
    /* At the limits: the next check (the Host) answers. */
    request.head_len = ATV312D_HTTP_HEAD_MAX;
    handle_logged(&request);
    ck_assert_uint_eq(answer.status, 403);
    stop();
}
END_TEST

/* The event streams have their own budget: past it a stream is 503, the rest still answers. */
START_TEST(streams_past_their_budget_503)
{
    start(false, NULL);
    http.stream_count = ATV312D_HTTP_STREAMS_MAX;
    atv312d_http_request_t events = {
        .method = "GET", .path = "/api/events", .host = "127.0.0.1:8080", .peer = "[::1]:5000"};
    ck_assert_str_eq(handle_logged(&events),
                     "{\"ok\":false,\"error\":\"busy: 16 event streams are open, the most at once; "
                     "try again in a few seconds (the page and the API still answer)\"}");
    ck_assert_uint_eq(answer.status, 503);
    ck_assert(!answer.events);
    ck_assert_str_eq(logged, "atv312d: warn: http [::1]:5000: GET /api/events: refused, 503: busy: "
                             "16 event streams are open, the most at once; try again in a few "
                             "seconds (the page and the API still answer)\n");
    atv312d_http_request_t page = {.method = "GET", .path = "/", .host = "127.0.0.1:8080"};
    handle_logged(&page);
    ck_assert_uint_eq(answer.status, 200);
    ck_assert_str_eq(logged, "");
    http.stream_count = ATV312D_HTTP_STREAMS_MAX - 1;
    handle_logged(&events);
    ck_assert(answer.events);
    http.stream_count = 0;
    stop();
}
END_TEST

/* A foreign Host and a malformed body are logged, once each; a command's own refusal is the
 * command's line (info), not a second one. */
START_TEST(refusals_logged_once)
{
    start(true, NULL);
    atv312d_http_request_t request = command_request("{\"command\":\"local 4 on\"}");
    request.host = "evil.example:8080";
    request.origin = NULL;
    request.peer = "10.0.0.9:33000";
    handle_logged(&request);
    ck_assert_uint_eq(answer.status, 403);
    ck_assert_str_eq(logged, "atv312d: warn: http 10.0.0.9:33000: POST /api/command: refused, "
                             "403: Host evil.example:8080 is not this server: it answers on "
                             "loopback as http://127.0.0.1:8080/\n");
    request = command_request("{\"command\":");
    request.peer = "127.0.0.1:33001";
    handle_logged(&request);
    ck_assert_uint_eq(answer.status, 400);
    ck_assert_str_eq(logged, "atv312d: warn: http 127.0.0.1:33001: POST /api/command: refused, "
                             "400: the body must be {\"command\":\"...\"}: one command line of "
                             "printable characters, at most 255\n");
    request = command_request("{\"command\":\"fault 9 OHF\"}");
    handle_logged(&request);
    ck_assert_uint_eq(answer.status, 400);
    ck_assert_str_eq(logged, "");
    stop();
}
END_TEST

START_TEST(addresses)
{
    atv312d_http_address_t a;
    ck_assert_int_eq(parse_address("8080", &a), 0);
    ck_assert_str_eq(a.text, "127.0.0.1:8080");
    ck_assert(a.loopback);
    ck_assert_int_eq(parse_address("0.0.0.0:80", &a), 0);
    ck_assert_str_eq(a.text, "0.0.0.0:80");
    ck_assert(!a.loopback);
    ck_assert_int_eq(parse_address("[::1]:8080", &a), 0);
    ck_assert_str_eq(a.text, "[::1]:8080");
    ck_assert(a.loopback);
    ck_assert_uint_eq(a.addr.ss_family, AF_INET6);
    ck_assert_int_eq(parse_address("[::]:0", &a), 0);
    ck_assert(!a.loopback);
    ck_assert_int_eq(parse_address("localhost:8080", &a), 0);
    ck_assert_str_eq(a.text, "127.0.0.1:8080");
    ck_assert_int_eq(parse_address("127.0.0.2:1", &a), 0);
    ck_assert(a.loopback);
    char err[256];
    ck_assert_int_eq(atv312d_parse_http_address("65536", &a, err, sizeof err), EX_USAGE);
    ck_assert_str_eq(err, "--http 65536: '65536' is not a port: give [ADDRESS:]PORT with PORT "
                          "0..65535, e.g. --http 8080 (127.0.0.1) or --http 0.0.0.0:8080");
    ck_assert_int_eq(atv312d_parse_http_address("example.com:80", &a, err, sizeof err), EX_USAGE);
    ck_assert_str_eq(err, "--http example.com:80: 'example.com' is not an IPv4 or IPv6 address: "
                          "give one such as 127.0.0.1, 0.0.0.0, [::1] or [::] (names are not "
                          "resolved)");
    ck_assert_int_eq(atv312d_parse_http_address("::1:80", &a, err, sizeof err), EX_USAGE);
    ck_assert_int_eq(atv312d_parse_http_address("[::1]80", &a, err, sizeof err), EX_USAGE);
    ck_assert_str_eq(err, "--http [::1]80: write an IPv6 address in brackets with its port, e.g. "
                          "[::1]:8080");
    ck_assert_int_eq(atv312d_parse_http_address("127.0.0.1:", &a, err, sizeof err), EX_USAGE);
    ck_assert_int_eq(atv312d_parse_http_address("-1", &a, err, sizeof err), EX_USAGE);
}
END_TEST

static int read_token(const char *content, char *token, size_t len, char *err)
{
    char path[] = "/tmp/atv312d-token-XXXXXX";
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(write(fd, content, strlen(content)), (int)strlen(content));
    close(fd);
    int rc = atv312d_http_read_token(path, token, len, err, 256);
    unlink(path);
    return rc;
}

START_TEST(token_files)
{
    char token[ATV312D_HTTP_TOKEN_MAX + 1], err[256];
    ck_assert_int_eq(read_token("s3cret\n", token, sizeof token, err), 0);
    ck_assert_str_eq(token, "s3cret");
    ck_assert_int_eq(read_token("s3cret\r\nsecond line\n", token, sizeof token, err), 0);
    ck_assert_str_eq(token, "s3cret");
    ck_assert_int_eq(read_token("no newline", token, sizeof token, err), 0);
    ck_assert_str_eq(token, "no newline");
    ck_assert_int_eq(read_token("\nsecret on line 2\n", token, sizeof token, err), EX_DATAERR);
    ck_assert_int_eq(read_token("", token, sizeof token, err), EX_DATAERR);
    char longest[ATV312D_HTTP_TOKEN_MAX + 2];
    memset(longest, 'x', ATV312D_HTTP_TOKEN_MAX);
    longest[ATV312D_HTTP_TOKEN_MAX] = '\0';
    ck_assert_int_eq(read_token(longest, token, sizeof token, err), 0);
    longest[ATV312D_HTTP_TOKEN_MAX] = 'x';
    longest[ATV312D_HTTP_TOKEN_MAX + 1] = '\0';
    ck_assert_int_eq(read_token(longest, token, sizeof token, err), EX_DATAERR);
    ck_assert_int_eq(
        atv312d_http_read_token("/nonexistent/token", token, sizeof token, err, sizeof err),
        EX_NOINPUT);
    ck_assert_str_eq(err, "--http-token /nonexistent/token: cannot be read: No such file or "
                          "directory");
}
END_TEST

static int parse_args(const char *first, ...)
{
    static atv312d_options_t opts;
    static char err[512];
    char *argv[16] = {"atv312d", "vcan0", "--node-id", "4"};
    int argc = 4;
    va_list args;
    va_start(args, first);
    for (const char *a = first; a; a = va_arg(args, const char *))
        argv[argc++] = (char *)a;
    va_end(args);
    int rc = atv312d_parse_args(argc, argv, &opts, err, sizeof err);
    ck_assert_msg(rc == 0 || strlen(err) > 0, "no message");
    return rc;
}

/* The options' rules (the messages are in docs/web.md): the web surface's options need --http,
 * the token needs the actions, the actions off loopback need the token. */
START_TEST(http_options)
{
    ck_assert_int_eq(parse_args("--http", "8080", NULL), 0);
    ck_assert_int_eq(parse_args("--http", "8080", "--http-actions", NULL), 0);
    ck_assert_int_eq(parse_args("--http", "[::1]:8080", "--http-actions", NULL), 0);
    ck_assert_int_eq(parse_args("--http", "0.0.0.0:8080", NULL), 0);
    ck_assert_int_eq(
        parse_args("--http", "0.0.0.0:8080", "--http-actions", "--http-token", "f", NULL), 0);
    ck_assert_int_eq(parse_args("--http", "0.0.0.0:8080", "--http-actions", NULL), EX_USAGE);
    ck_assert_int_eq(parse_args("--http-actions", NULL), EX_USAGE);
    ck_assert_int_eq(parse_args("--http-token", "f", NULL), EX_USAGE);
    ck_assert_int_eq(parse_args("--http", "8080", "--http-token", "f", NULL), EX_USAGE);
    ck_assert_int_eq(parse_args("--http", "host:8080", NULL), EX_USAGE);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("atv312d_http");
    TCase *tc = tcase_create("handler");
    tcase_add_test(tc, bench_describes_each_drive);
    tcase_add_test(tc, bench_on_devicenet);
    tcase_add_test(tc, bench_says_actions_and_token);
    tcase_add_test(tc, state_is_the_bus_and_the_control_surface_nodes);
    tcase_add_test(tc, frame_rate_over_a_second_or_more);
    tcase_add_test(tc, events_start_a_stream);
    tcase_add_test(tc, page_files_with_their_type_and_etag);
    tcase_add_test(tc, wrong_methods_get_405);
    tcase_add_test(tc, command_runs_as_ctl_runs_it);
    tcase_add_test(tc, refused_command_is_400_with_its_reply);
    tcase_add_test(tc, malformed_bodies_are_400);
    tcase_add_test(tc, actions_off_is_403);
    tcase_add_test(tc, token_missing_or_wrong_is_403);
    tcase_add_test(tc, cross_site_is_403);
    tcase_add_test(tc, foreign_host_on_loopback_is_403);
    tcase_add_test(tc, other_content_type_is_415);
    tcase_add_test(tc, long_body_is_413);
    tcase_add_test(tc, long_target_414_long_head_431);
    tcase_add_test(tc, streams_past_their_budget_503);
    tcase_add_test(tc, refusals_logged_once);
    tcase_add_test(tc, addresses);
    tcase_add_test(tc, token_files);
    tcase_add_test(tc, http_options);
    suite_add_tcase(s, tc);
    return check_run_suite(s);
}
