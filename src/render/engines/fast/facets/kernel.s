// The facet-row span kernels for Thumb-2 with the DSP extension (Cortex-M4, M7).
// Their specification is the portable Rust of kernel.rs (fill_one,
// fill_split_row): the same bits in the row, the record and the result.
// {LX} ... {FACE} are the record's field offsets (offset_of!). Called with the
// AAPCS: r0 the facet record, r1 the row's first cell, r2 the row's length;
// the spans filled in r0.

    .syntax unified
    .thumb

// Depth-tests the cells from \p up to \end (word pointers, \end - \p a multiple
// of 4) against the entries (\behind & 0xFFFF0000) | (\id & 0xFFFF), \behind
// stepping by \a a cell: a cell takes its entry plus \tie when the entry is
// greater. Leaves \p at \end; \c0, \c1, \e are scratch.
.macro PBUFFER_CELLS p, end, behind, a, id, tie, c0, c1, e
    sub     \c0, \end, \p
    tst     \c0, #4
    beq     2f
    // an odd count: one cell first
    ldr     \c0, [\p], #4
    PBUFFER_CELL \c0, -4, \p, \behind, \a, \id, \tie, \e
2:
    cmp     \p, \end
    beq     3f
1:
    ldrd    \c0, \c1, [\p], #8
    PBUFFER_CELL \c0, -8, \p, \behind, \a, \id, \tie, \e
    PBUFFER_CELL \c1, -4, \p, \behind, \a, \id, \tie, \e
    cmp     \p, \end
    bne     1b
3:
.endm

// One cell \cell (loaded from \p + \off, \p already past it) against the entry of
// \behind, which then steps by \a.
.macro PBUFFER_CELL cell, off, p, behind, a, id, tie, e
    pkhbt   \e, \id, \behind
    add     \behind, \behind, \a
    cmp     \e, \cell
    itt     hi
    addhi   \e, \e, \tie
    strhi   \e, [\p, #\off]
.endm

// Entry: steps the chains (and the diagonal when \diag), both planes, and loads
// l = r3, r = r4 (and the diagonal's xd = r5), drow r6, a r7, drow2 r8, a2 r9,
// tie r10, id r11 (the low half of ~face). Then x0 = r3, x1 = r12 clamped to
// the row, r0 = 0, and a branch to 9f (return 0) when x0 >= x1.
.macro PBUFFER_ENTER diag
    push    {{r4-r11, lr}}
    ldrd    r3, r4, [r0, #{LX}]
    add     r4, r4, r3
    str     r4, [r0, #{LX}]
    ldrd    r4, r5, [r0, #{RX}]
    add     r5, r5, r4
    str     r5, [r0, #{RX}]
.if \diag
    ldrd    r5, r6, [r0, #{DX}]
    add     r6, r6, r5
    str     r6, [r0, #{DX}]
    asr     r5, r5, #16
.endif
    asr     r3, r3, #16
    asr     r4, r4, #16
    ldrd    r6, r7, [r0, #{DROW}]
    add     r7, r7, r6
    str     r7, [r0, #{DROW}]
    ldrd    r8, r9, [r0, #{DROW2}]
    add     r9, r9, r8
    str     r9, [r0, #{DROW2}]
    ldr     r7, [r0, #{A}]
    ldr     r9, [r0, #{A2}]
    ldr     r10, [r0, #{TIE}]
    ldrh    r11, [r0, #{FACE}]
    mvn     r11, r11
    // x0 = max(min(l, r), 0), x1 = min(max(l, r), len): signed
    mov     r12, r4
    cmp     r3, r4
    itt     gt
    movgt   r12, r3
    movgt   r3, r4
    bic     r3, r3, r3, asr #31
    cmp     r12, r2
    it      gt
    movgt   r12, r2
    movs    r0, #0
    cmp     r3, r12
    bge     9f
.endm

// One span with the plane \d, \a.
.macro PBUFFER_FILL_ONE name, d, a
    .section .text.\name,"ax",%progbits
    .global \name
    .type   \name,%function
    .thumb_func
    .p2align 2
\name:
    PBUFFER_ENTER 0
    movs    r0, #1
    mla     \d, \a, r3, \d
    sub     \d, \d, r10
    add     r3, r1, r3, lsl #2
    add     r12, r1, r12, lsl #2
    PBUFFER_CELLS r3, r12, \d, \a, r11, r10, r4, r5, lr
9:
    pop     {{r4-r11, pc}}
    .size   \name, . - \name
.endm

// Two spans cut at the diagonal: x0..xd with the plane \d1, \a1, xd..x1 with
// \d2, \a2.
.macro PBUFFER_FILL_SPLIT name, d1, a1, d2, a2
    .section .text.\name,"ax",%progbits
    .global \name
    .type   \name,%function
    .thumb_func
    .p2align 2
\name:
    PBUFFER_ENTER 1
    // xd = clamp(xd, x0, x1); a span for each non-empty part
    cmp     r5, r3
    it      lt
    movlt   r5, r3
    cmp     r5, r12
    it      gt
    movgt   r5, r12
    cmp     r3, r5
    it      lt
    addlt   r0, r0, #1
    cmp     r5, r12
    it      lt
    addlt   r0, r0, #1
    mla     \d2, \a2, r5, \d2
    sub     \d2, \d2, r10
    mla     \d1, \a1, r3, \d1
    sub     \d1, \d1, r10
    add     r4, r1, r5, lsl #2
    add     r3, r1, r3, lsl #2
    add     r12, r1, r12, lsl #2
    PBUFFER_CELLS r3, r4, \d1, \a1, r11, r10, r2, r5, lr
    PBUFFER_CELLS r3, r12, \d2, \a2, r11, r10, r2, r5, lr
9:
    pop     {{r4-r11, pc}}
    .size   \name, . - \name
.endm

PBUFFER_FILL_ONE pbuffer_fill_one_first, r6, r7
PBUFFER_FILL_ONE pbuffer_fill_one_second, r8, r9
PBUFFER_FILL_SPLIT pbuffer_fill_split_first_left, r6, r7, r8, r9
PBUFFER_FILL_SPLIT pbuffer_fill_split_first_right, r8, r9, r6, r7

    .text
