/* SPDX-License-Identifier: Apache-2.0 */
/* The Altivar 58 CANopen card manual's EMCY code table (VW3-A58308, "Emergency Error Codes"),
 * mnemonic and meaning, for an EMCY consumer (co_emcy_code_text_in: cotrace --emcy-table atv58).
 * The same codes the model sends for its faults (atv58_faults.c); the manual lists several faults
 * under one code where its table had merged cells, and they share one text here.
 * tests/drive/models/atv58 checks that every fault of atv58_faults.c has its meaning in this table.
 */
#include "atv58/atv58_emcy.h"

#define EXACT CO_EMCY_MASK_EXACT
#define SUBCLASS CO_EMCY_MASK_SUBCLASS

static const co_emcy_meaning_t meanings[] = {
    {0x0000, SUBCLASS, "NOF: no fault"},
    {0x1000, SUBCLASS,
     "CRF: load relay fault, OLF: motor overload fault, SOF: overspeed fault (ATV58)"},
    {0x2310, EXACT, "OCF: overcurrent fault (ATV58)"},
    {0x2320, EXACT, "SCF: motor short-circuit fault (phase, earth) (ATV58)"},
    {0x3110, EXACT, "OSF: line supply overvoltage fault (ATV58)"},
    {0x3120, EXACT, "USF: line supply undervoltage fault (ATV58)"},
    {0x3130, EXACT, "PHF: line supply phase loss fault (ATV58)"},
    {0x3310, EXACT, "OBF: DC bus overvoltage fault, OPF: motor phase loss fault (ATV58)"},
    {0x4210, EXACT, "OHF: drive overheating fault (ATV58)"},
    {0x4310, EXACT, "OTF: motor overheating fault (ATV58)"},
    {0x5520, EXACT, "EEF: EEPROM memory fault (ATV58)"},
    {0x5530, EXACT, "EEF: EEPROM memory fault (ATV58)"},
    {0x6100, EXACT, "INF: internal fault (ATV58)"},
    {0x6300, EXACT, "CFF/CFI: configuration (parameters) incorrect or invalid (ATV58)"},
    {0x7300, EXACT, "ANF: load veering fault, LFF: loss of 4-20 mA, TSF: PTC probe fault (ATV58)"},
    {0x7310, EXACT, "SPF: speed feedback cut-off fault (ATV58)"},
    {0x7510, EXACT, "SLF: standard communication link fault (ATV58)"},
    {0x7520, EXACT, "ILF/CNF: fast communication link or network fault (ATV58)"},
    {0x8130, EXACT, "communication error (life guard time out) (ATV58)"},
    {0x9000, EXACT, "EPF: external fault (ATV58)"},
};

const co_emcy_code_table_t atv58_emcy_table = {meanings, sizeof meanings / sizeof meanings[0]};
