/* SPDX-License-Identifier: Apache-2.0 */
/* A minimal model of the CiA 402 velocity drive, for the drive layer's tests: the dictionary of
 * minimal_model.eds (parameters at 3000h, outputs at 3001h, no manufacturer copies of the CiA 402
 * words) and a profile whose control word bits and fast ramp differ from every Altivar's, so that
 * a test passing here passes on what the profile says, not on an Altivar's habits. */
#ifndef MINIMAL_MODEL_H
#define MINIMAL_MODEL_H

#include "drive_bench.h"
#include "minimal_od.h" /* generated */

extern const drive_profile_t minimal_profile;

/* The profile's manufacturer-specific bits (bits 11-15 of the control word, 14 of the status). */
#define CW_REVERSE 0x8000u
#define CW_RAMP_STOP 0x0800u
#define CW_FAST_STOP 0x1000u
#define SW_REVERSE 0x4000u
#define SW_STOP_KEY 0x0100u

/* Its parameters (3000h) and outputs (3001h). */
#define PARAMS 0x3000
#define ACC 1               /* 0.1 s, default 30 */
#define DEC 2               /* 0.1 s, default 30: the fast ramp is DEC / 2 */
#define LSP 3               /* 0.1 Hz, default 0 */
#define HSP 4               /* 0.1 Hz, default 500 */
#define FRS 5               /* 0.1 Hz, default 500 */
#define NSP 6               /* rpm, default 1500 */
#define NCR 7               /* 0.1 A, default 40 */
#define STOP_TYPE 8         /* DRIVE_STOP_*, default ramp */
#define CHANNEL_MODE 9      /* 0 separate (default), 1 following the reference, 2 I/O */
#define COMMAND_1 10        /* command channel 1: 0 network (default), 1 local */
#define COMMAND_2 11        /* command channel 2: default 1, local */
#define COMMAND_SELECT 12   /* 0 channel 1 (default), 1 channel 2 */
#define REFERENCE 13        /* reference channel: 0 network (default), 1 local */
#define FREQUENCY_REF 14    /* 0.1 Hz, a view of 6042h */
#define AUTO_TUNE 15        /* DRIVE_AUTO_TUNE_* */
#define RAMP_SWITCH 16      /* 0 none, or a switching source: the second ramp pair */
#define ACC_2 17            /* 0.1 s, default 10 */
#define DEC_2 18            /* 0.1 s, default 10 */
#define ACCESS 19           /* access level: 0 basic, 1 full (default) */
#define REFERENCE_SELECT 20 /* 0 reference channel 1, 1 channel 2 (local) */
/* Its logic inputs: LI1 and LI2. */
#define INPUTS 2
#define OUTPUTS 0x3001
#define CURRENT 1   /* 0.1 A */
#define TORQUE 2    /* % */
#define FREQUENCY 3 /* 0.1 Hz, the output frequency */

/* Its faults: code, EMCY code, 1001h class, reset class; all freewheel but the last two. */
enum minimal_fault {
    FAULT_HOT, /* "HoT" 0x4210 temperature, reset by command once the cause is gone */
    FAULT_LOW, /* "LoW" 0x3120 voltage, resets itself when the cause goes */
    FAULT_NET, /* "NeT" 0x8130 communication: the communication loss */
    FAULT_CPU, /* "CpU" 0x6100, only a reset node (power cycle) */
    FAULT_EXT, /* "ExT" 0x9000, reset by command: stops on the deceleration ramp */
    FAULT_FAN  /* "FaN" 0x4310 temperature, resets itself: stops on the fast ramp */
};

/* Boots node 4 of the minimal model at time 0 and consumes its boot-up frame. */
static inline void bench_start(bench_t *b)
{
    bench_start_model(b, &minimal_profile, NULL);
}

#endif
