/* SPDX-License-Identifier: Apache-2.0 */
/* The command line of atv312d: `atv312d IFACE --node-id N [--model M] [options]`, or on a
 * DeviceNet bus `atv312d IFACE --devicenet [--mac-id N [--model M]...] [--baud RATE]`. Parsing is
 * separate from main() so the unit tests can check every error and its exit code. */
#ifndef ATV312D_OPTIONS_H
#define ATV312D_OPTIONS_H

#include "atv312d/catalogue.h"
#include "co_linux/log.h"

#include <netinet/in.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <sys/socket.h>

#define ATV312D_NODE_ID_MIN 1
#define ATV312D_NODE_ID_MAX ((int)CO_NODE_ID_MAX) /* an int, as the parser counts */
/* DeviceNet MAC IDs (--devicenet --mac-id), and the MAC ID of a DeviceNet drive given none: an
 * out-of-box DeviceNet device's (the Altivar 312 DeviceNet manual). */
#define ATV312D_MAC_ID_MIN 0
#define ATV312D_MAC_ID_MAX 63
#define ATV312D_MAC_ID_DEFAULT 63

/* The DeviceNet object's baud rate attribute (class 3, attribute 2): only information here, a
 * SocketCAN interface's bitrate is set with ip link. */
typedef enum atv312d_baud {
    ATV312D_BAUD_125K = 0,
    ATV312D_BAUD_250K = 1,
    ATV312D_BAUD_500K = 2
} atv312d_baud_t;

/* Where --http listens (the web surface, http.h): "8080" (127.0.0.1), "0.0.0.0:8080", "[::1]:8080".
 */
typedef struct atv312d_http_address {
    struct sockaddr_storage addr;
    socklen_t len;
    bool loopback; /* 127.0.0.0/8 or ::1: only this machine can connect */
    char text[80]; /* "127.0.0.1:8080", "[::1]:8080" */
} atv312d_http_address_t;

typedef struct atv312d_options {
    const char *iface;
    /* The nodes, drives or plain nodes: node-ids on CANopen, MAC IDs on DeviceNet; ascending,
     * each once, then the nodes of --unconfigured, each with node-id FFh (none). */
    uint8_t node_ids[ATV312D_NODE_ID_MAX];
    atv312d_model_t models[ATV312D_NODE_ID_MAX]; /* the model of node_ids[i] */
    /* --canopen-off: node_ids[i] is the drive's id in the daemon, its AdCO 0: silent on CAN. */
    bool can_off[ATV312D_NODE_ID_MAX];
    size_t node_count;
    bool devicenet;      /* --devicenet: the interface is a DeviceNet bus */
    atv312d_baud_t baud; /* --baud, DeviceNet only (default 125k) */
    bool baud_given;
    const char *store_path;   /* NULL: no storage, 1010h aborts */
    const char *trace_path;   /* NULL: no trace; "-": stdout */
    const char *control_path; /* NULL: no control socket */
    const char *status_path;  /* NULL: no status file (SIGUSR1 still logs the status) */
    const char *http;         /* --http's value; NULL: no web surface */
    atv312d_http_address_t http_address;
    bool http_actions;           /* --http-actions: POST /api/command runs commands */
    const char *http_token_path; /* --http-token FILE; NULL: no token */
    co_log_level_t log_level;
    bool help;
    bool version;
} atv312d_options_t;

/* Parses argv. Returns 0 (run, or print help / version when those flags are set) or EX_USAGE
 * with a message in err saying what is wrong and what would be right. */
int atv312d_parse_args(int argc, char *const argv[], atv312d_options_t *opts, char *err,
                       size_t err_len);

/* Parses --http's value; 0, or EX_USAGE with a message in err saying what would be right. */
int atv312d_parse_http_address(const char *text, atv312d_http_address_t *address, char *err,
                               size_t err_len);

void atv312d_print_usage(FILE *out);

#endif
