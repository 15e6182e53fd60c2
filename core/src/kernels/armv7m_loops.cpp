// The ARMv7E-M unit loops (see armv7m_loops.h for what they compute and why they are assembly).
// Empty on every other target. Each function takes one ArmPointsBlock or ArmColumnsBlock, keeps
// all of it in registers (r0-r12 and lr, s0-s16), and walks the block's units once: a unit's
// position as scalar_loops.h computes it (HESAI_XYZ below), kept (the output advanced) iff
// raw >= min_distance, the carry out of raw << 16 + keep_bias.
#include "armv7m_loops.h"

#if defined(HESAI_KERNELS_ARMV7M)

#define HESAI_STRING(x) #x
#define HESAI_STRING_OF(x) HESAI_STRING(x)

// Every table is read from the walked pointer of dir_cos or sin_el, which the post-increment has
// already moved to the next channel: the channel's entry of the table k tables on is at
// k * TABLE - 4. The loops take two units a step (every sensor's blocks have an even number of
// units: 16 to 128) and count the steps down in the high bits of a register whose low byte is
// stored with each point (the block index, the channel), so that one SUBS both steps the count
// and ends the loop (on the sign): no end pointer and no compare.
asm(".equ HESAI_ARMV7M_TABLE, " HESAI_STRING_OF(HESAI_ARMV7M_TABLE) R"(
    .syntax unified
    .thumb

    @ The start of a function of its own section (for --gc-sections).
    .macro HESAI_FUNCTION name
    .pushsection .text.\name, "ax", %progbits
    .global \name
    .type \name, %function
    .thumb_func
    .p2align 2
\name:
    .endm

    @ A unit's position (scalar_loops.h's unit_xyz): x = r (sin_a dc + cos_a ds),
    @ y = r (cos_a dc - sin_a ds), z = r se; dc, ds, se: the channel's dir_cos, dir_sin, sin_el.
    .macro HESAI_XYZ x, y, z, r, dc, ds, se, sin_a, cos_a
    vmul.f32 \x, \sin_a, \dc
    vmla.f32 \x, \cos_a, \ds
    vmul.f32 \x, \x, \r
    vmul.f32 \y, \cos_a, \dc
    vmls.f32 \y, \sin_a, \ds
    vmul.f32 \y, \y, \r
    vmul.f32 \z, \r, \se
    .endm

    @ One unit to a Point. unit: 3 or 4 bytes; loop: the firing loop (its fire_ns table is 2 + loop
    @ tables after sin_el). Registers: r0 units, r1 out, r2 dir_cos, r3 sin_el, r4 tag, r5 keep_bias,
    @ r6 block and steps, r7 raw, r8 fire_ns, r9 r10 temporaries; s0-s5 the Point's six floats (one
    @ VSTM), s6-s9 the channel's dir_cos, dir_sin, sin_el, azimuth, s10-s16 the block's constants.
    @ scan (issue #43; 0: none): 1 also sets the Q flag where a unit needs the exact scan in C:
    @ beyond: a distance beyond the rated range (QADD of raw and r11 = 0x7FFFFFFF - limit
    @ saturates); markers: not kept and not 0, a blockage marker or 1..min-1 (SSAT #1 saturates). 2
    @ also compares the unit with the first return's, r12 bytes on (distance and reflectivity: the
    @ low 24 bits of the words) and shifts "repeated" (equal and kept) into lr from the top (RRX);
    @ without beyond, the unit is read as a word (its distance converted from bits 0-15).
    .macro HESAI_POINT unit, loop, scan=0, beyond=0, markers=0
    .if \scan == 2 && \beyond == 0
    ldr      r7, [r0], #\unit         @ the unit's word: distance, reflectivity, ...
    vmov     s3, r7
    vcvt.f32.u16 s3, s3, #0           @ the distance, bits 0-15
    .else
    ldrh     r7, [r0], #\unit         @ raw distance
    .if \beyond
    qadd     r8, r7, r11              @ Q: raw > the rated range's limit
    .endif
    vmov     s3, r7
    vcvt.f32.u32 s3, s3
    .endif
    vmul.f32 s3, s3, s12              @ r, the Point's distance_m
    vldmia   r2!, {s6}                @ dir_cos
    vldr     s7, [r2, #(HESAI_ARMV7M_TABLE - 4)]      @ dir_sin
    vldr     s9, [r2, #(2 * HESAI_ARMV7M_TABLE - 4)]  @ beam azimuth
    vldmia   r3!, {s8}                @ sin_el
    vldr     s5, [r3, #(HESAI_ARMV7M_TABLE - 4)]      @ elevation_deg, stored as is
    HESAI_XYZ s0, s1, s2, s3, s6, s7, s8, s10, s11
    vadd.f32 s4, s13, s9              @ azimuth: block + beam, both in [0, 360)
    vcmp.f32 s4, s14
    vmrs     APSR_nzcv, fpscr
    it       ge
    vsubge.f32 s4, s4, s14
    vstmia   r1, {s0-s5}
    ldr      r8, [r3, #((2 + \loop) * HESAI_ARMV7M_TABLE - 4)]  @ fire_ns
    vmov     r9, r10, s15, s16
    adds     r9, r9, r8
    adc      r10, r10, r8, asr #31    @ block time + fire_ns, 64 bits
    strd     r9, r10, [r1, #24]
    ldrb     r9, [r0, #(2 - \unit)]   @ intensity (left in r9, 0..255, for the comparison below)
    .if \unit == 4
    ldrb     r10, [r0, #-1]           @ confidence
    orr      r10, r9, r10, lsl #24
    orr      r10, r10, r4
    .else
    orr      r10, r9, r4
    .endif
    str      r10, [r1, #32]           @ intensity, channel, return index, confidence
    add      r4, r4, #256             @ the next channel
    strb     r6, [r1, #36]            @ block
    .if \scan == 0
    adds     r7, r5, r7, lsl #16
    it       cs
    addcs    r1, r1, #40              @ kept: the next Point
    .elseif \scan == 1 && \markers == 0
    adds     r7, r5, r7, lsl #16
    it       cs
    addcs    r1, r1, #40              @ kept: the next Point
    .elseif \scan == 1
    adds     r10, r5, r7, lsl #16     @ carry: kept (r7, raw, left for the SSAT)
    ite      cs
    addcs    r1, r1, #40              @ kept: the next Point
    ssatcc   r10, #1, r7              @ not kept: Q if raw >= 1
    .else
    .if \beyond
    ldr      r8, [r0, #-\unit]        @ this unit's word: distance, reflectivity, a byte beyond
    ldr      r10, [r0, r12]           @ the first return's unit's
    eor      r8, r8, r10              @ bits 0-23 clear: the same distance and reflectivity
    .else
    ldr      r10, [r0, r12]           @ the first return's unit's
    eor      r8, r7, r10              @ bits 0-23 clear: the same distance and reflectivity
    .endif
    adds     r10, r5, r7, lsl #16     @ carry: kept
    .if \markers
    itet     cs
    addcs    r1, r1, #40              @ kept: the next Point
    ssatcc   r10, #1, r7              @ not kept: Q if raw >= 1
    .else
    itt      cs
    addcs    r1, r1, #40              @ kept: the next Point
    .endif
    cmpcs    r9, r8, lsl #8           @ kept: carry iff bits 0-23 are clear (0..255 >= a multiple of 256)
    rrx      lr, lr                   @ repeated (carry) into bit 31
    .endif
    .endm

    .macro HESAI_POINTS name, unit, loop, scan=0, beyond=0, markers=0
    HESAI_FUNCTION \name
    .if \scan
    push     {r4-r11, lr}
    .else
    push     {r4-r10, lr}
    .endif
    vpush    {s16}
    add      r12, r0, #28
    vldmia   r12, {s10-s16}
    .if \scan
    ldrd     r11, r12, [r0, #56]      @ limit_bias, first_offset
    .endif
    ldmia    r0, {r0-r6}
1:
    HESAI_POINT \unit, \loop, \scan, \beyond, \markers
    HESAI_POINT \unit, \loop, \scan, \beyond, \markers
    subs     r6, r6, #256             @ steps left - 1, in bits 8-31
    bpl      1b
    mov      r0, r1
    .if \scan == 2
    mov      r1, lr                   @ the repeated bits, the last unit's in bit 31
    .endif
    vpop     {s16}
    .if \scan
    pop      {r4-r11, pc}
    .else
    pop      {r4-r10, pc}
    .endif
    .size \name, . - \name
    .popsection
    .endm

    @ One unit to the columns. Registers: r0 units, r1 return index, r2 n, r3-r7 the columns x, y,
    @ z, time_ns, intensity, r8 dir_cos, r9 sin_el, r10 keep_bias, r11 channel and steps, r12 lr
    @ temporaries; s0 r, s1-s3 the channel's dir_cos, dir_sin, sin_el, s4-s6 x, y, z, s7-s12 the
    @ block's constants and the last two columns. The carry of the ADDS (kept) lasts to the ADC:
    @ nothing between sets the flags.
    .macro HESAI_COLUMN unit, loop
    ldrh     r12, [r0], #\unit        @ raw distance
    vmov     s0, r12
    adds     r12, r10, r12, lsl #16   @ carry: kept
    vcvt.f32.u32 s0, s0
    vmul.f32 s0, s0, s9               @ r
    vldmia   r8!, {s1}                @ dir_cos
    vldr     s2, [r8, #(HESAI_ARMV7M_TABLE - 4)]  @ dir_sin
    vldmia   r9!, {s3}                @ sin_el
    HESAI_XYZ s4, s5, s6, s0, s1, s2, s3, s7, s8
    vmov     r12, lr, s4, s5
    str      r12, [r3, r2, lsl #2]
    str      lr, [r4, r2, lsl #2]
    vmov     r12, s6
    str      r12, [r5, r2, lsl #2]
    ldr      r12, [r9, #((2 + \loop) * HESAI_ARMV7M_TABLE - 4)]  @ fire_ns
    vmov     lr, s10
    add      r12, r12, lr             @ + the block's offset
    str      r12, [r6, r2, lsl #2]
    ldrb     r12, [r0, #(2 - \unit)]  @ intensity
    strb     r12, [r7, r2]
    vmov     r12, lr, s11, s12        @ the channel and return index columns
    strb     r11, [r12, r2]
    strb     r1, [lr, r2]
    adc      r2, r2, #0               @ kept: the next index
    .endm

    .macro HESAI_COLUMNS name, unit, loop
    HESAI_FUNCTION \name
    push     {r4-r11, lr}
    add      r12, r0, #48
    vldmia   r12, {s7-s12}
    ldmia    r0, {r0-r11}
1:
    HESAI_COLUMN \unit, \loop
    add      r11, r11, #1             @ the next channel
    HESAI_COLUMN \unit, \loop
    subs     r11, r11, #255           @ the next channel (+1), steps left - 1 (bits 8-31)
    bpl      1b
    mov      r0, r2
    pop      {r4-r11, pc}
    .size \name, . - \name
    .popsection
    .endm

    HESAI_POINTS  hesai_armv7m_points_u3_l0, 3, 0
    HESAI_POINTS  hesai_armv7m_points_u3_l1, 3, 1
    HESAI_POINTS  hesai_armv7m_points_u4_l0, 4, 0
    HESAI_POINTS  hesai_armv7m_points_u4_l1, 4, 1
    @ The unit scan's: u3 (the Pandars: a rated range, no blockage markers), u4m (the QT128C2X:
    @ both) and u4 (the PandarQT64 and XT: neither, so the first returns take the loops above).
    HESAI_POINTS  hesai_armv7m_points_scan_u3_l0, 3, 0, 1, 1, 0
    HESAI_POINTS  hesai_armv7m_points_scan_u3_l1, 3, 1, 1, 1, 0
    HESAI_POINTS  hesai_armv7m_points_scan_u4m_l0, 4, 0, 1, 1, 1
    HESAI_POINTS  hesai_armv7m_points_scan_u4m_l1, 4, 1, 1, 1, 1
    HESAI_POINTS  hesai_armv7m_points_repeat_u3_l0, 3, 0, 2, 1, 0
    HESAI_POINTS  hesai_armv7m_points_repeat_u3_l1, 3, 1, 2, 1, 0
    HESAI_POINTS  hesai_armv7m_points_repeat_u4_l0, 4, 0, 2, 0, 0
    HESAI_POINTS  hesai_armv7m_points_repeat_u4m_l0, 4, 0, 2, 1, 1
    HESAI_POINTS  hesai_armv7m_points_repeat_u4m_l1, 4, 1, 2, 1, 1
    HESAI_COLUMNS hesai_armv7m_columns_u3_l0, 3, 0
    HESAI_COLUMNS hesai_armv7m_columns_u3_l1, 3, 1
    HESAI_COLUMNS hesai_armv7m_columns_u4_l0, 4, 0
    HESAI_COLUMNS hesai_armv7m_columns_u4_l1, 4, 1
)");

#endif  // HESAI_KERNELS_ARMV7M
