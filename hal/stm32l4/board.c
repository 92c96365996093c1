/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * STM32L476RG backend (Cortex-M4F, 1 MiB flash, 96 KiB SRAM1), register level,
 * no vendor headers. Register addresses and bits are from the STM32L4x6
 * reference manual RM0351 (section numbers as in its Rev 9), the STM32L476xx
 * datasheet DS10198 (alternate functions) and, for the core peripherals, the
 * ARMv7-M Architecture Reference Manual (DDI 0403).
 *
 *   clock     HSI16 as SYSCLK, AHB = APB1 = APB2 = 16 MHz, 0 flash wait states
 *   counter   DWT_CYCCNT (CPU cycles at 16 MHz) extended to 64 bits; SysTick
 *             samples it every 2^24 cycles so no 32-bit wrap is missed
 *   link      USART2, PA2 TX / PA3 RX (AF7), 115200 8N1, polled
 *             + I2C1 target at 0x42, PB8 SCL / PB9 SDA (AF4), interrupt driven:
 *             the register window of docs/I2C.md (firmware/link/bw_i2cwin.h),
 *             which offers the payload the application hands the board
 *             (the HAL's offer) in 32-byte pages
 *   drdy      PA5, push-pull output, high while a payload is offered on I2C
 *             (or while the application asks for it)
 *   sensor    none yet: sensor_open/sensor_read are NULL, so the HAL
 *             wrappers return -BW_HAL_ENOSYS and the application answers a
 *             job with an ERROR frame
 *   fault     code kept in the last 8 bytes of SRAM2, then a system reset
 *
 * On a NUCLEO-L476RG, PA2/PA3 are the ST-LINK virtual COM port, PA5 is the
 * green LED LD2 and PB8/PB9 are the Arduino D15/D14 (SCL/SDA) pins.
 */
#include <stdint.h>

#include "bw_crc32.h"
#include "bw_hal.h"
#include "bw_i2cwin.h"

#define REG(a) (*(volatile uint32_t *)(a))

#define SYSCLK_HZ 16000000u
#define LINK_BAUD 115200u
#define I2C_OWN_ADDR 0x42u

/* ---- core peripherals (ARMv7-M ARM B3.2 SCB, B3.3 SysTick, B3.4 NVIC,
 * C1.6.5 DEMCR, C1.8 DWT) ---------------------------------------------------- */
#define SYST_CSR REG(0xE000E010u)
#define SYST_RVR REG(0xE000E014u)
#define SYST_CVR REG(0xE000E018u)
#define NVIC_ISER0 REG(0xE000E100u)
#define NVIC_ISER1 REG(0xE000E104u)
#define SCB_VTOR REG(0xE000ED08u)
#define SCB_AIRCR REG(0xE000ED0Cu)
#define AIRCR_VECTKEY (0x05FAu << 16)
#define AIRCR_PRIGROUP (7u << 8)
#define AIRCR_SYSRESETREQ (1u << 2)
#define DEMCR REG(0xE000EDFCu)
#define DEMCR_TRCENA (1u << 24)
#define DWT_CTRL REG(0xE0001000u)
#define DWT_CTRL_CYCCNTENA (1u << 0)
#define DWT_CYCCNT REG(0xE0001004u)

/* ---- RCC (RM0351 §6.4; base 0x4002 1000 from the §2.2.2 memory map) ------------- */
#define RCC_BASE 0x40021000u
#define RCC_CR REG(RCC_BASE + 0x00u)
#define RCC_CR_HSION (1u << 8)
#define RCC_CR_HSIRDY (1u << 10)
#define RCC_CFGR REG(RCC_BASE + 0x08u)
#define RCC_CFGR_SW_MASK (3u << 0)
#define RCC_CFGR_SW_HSI16 (1u << 0)
#define RCC_CFGR_SWS_MASK (3u << 2)
#define RCC_CFGR_SWS_HSI16 (1u << 2)
#define RCC_AHB2ENR REG(RCC_BASE + 0x4Cu)
#define RCC_AHB2ENR_GPIOAEN (1u << 0)
#define RCC_AHB2ENR_GPIOBEN (1u << 1)
#define RCC_APB1ENR1 REG(RCC_BASE + 0x58u)
#define RCC_APB1ENR1_USART2EN (1u << 17)
#define RCC_APB1ENR1_I2C1EN (1u << 21)
/* RCC_CCIPR (0x88) is left at reset: USART2SEL = I2C1SEL = 00, PCLK1. */

/* ---- GPIO (RM0351 §8.5; ports at 0x4800 0000 + 0x400 n) ------------------ */
#define GPIOA_BASE 0x48000000u
#define GPIOB_BASE 0x48000400u
#define GPIO_MODER 0x00u
#define GPIO_OTYPER 0x04u
#define GPIO_OSPEEDR 0x08u
#define GPIO_PUPDR 0x0Cu
#define GPIO_BSRR 0x18u
#define GPIO_AFRL 0x20u
#define GPIO_AFRH 0x24u
#define MODE_OUTPUT 1u
#define MODE_AF 2u
#define PULL_UP 1u
#define SPEED_MEDIUM 1u
#define DRDY_PIN 5u /* PA5 */

/* ---- USART2 (RM0351 §40.8; base 0x4000 4400) ---------------------------- */
#define USART2_BASE 0x40004400u
#define USART2_CR1 REG(USART2_BASE + 0x00u)
#define USART2_CR2 REG(USART2_BASE + 0x04u)
#define USART2_CR3 REG(USART2_BASE + 0x08u)
#define USART2_BRR REG(USART2_BASE + 0x0Cu)
#define USART2_ISR REG(USART2_BASE + 0x1Cu)
#define USART2_ICR REG(USART2_BASE + 0x20u)
#define USART2_RDR REG(USART2_BASE + 0x24u)
#define USART2_TDR REG(USART2_BASE + 0x28u)
#define USART_CR1_UE (1u << 0)
#define USART_CR1_RE (1u << 2)
#define USART_CR1_TE (1u << 3)
#define USART_ISR_PE (1u << 0)
#define USART_ISR_FE (1u << 1)
#define USART_ISR_NF (1u << 2)
#define USART_ISR_ORE (1u << 3)
#define USART_ISR_RXNE (1u << 5)
#define USART_ISR_TXE (1u << 7)
#define USART_ICR_ERRORS 0xFu /* PECF, FECF, NCF, ORECF */

/* ---- I2C1 (RM0351 §39.7; base 0x4000 5400) ------------------------------- */
#define I2C1_BASE 0x40005400u
#define I2C1_CR1 REG(I2C1_BASE + 0x00u)
#define I2C1_OAR1 REG(I2C1_BASE + 0x08u)
#define I2C1_OAR2 REG(I2C1_BASE + 0x0Cu)
#define I2C1_TIMINGR REG(I2C1_BASE + 0x10u)
#define I2C1_ISR REG(I2C1_BASE + 0x18u)
#define I2C1_ICR REG(I2C1_BASE + 0x1Cu)
#define I2C1_RXDR REG(I2C1_BASE + 0x24u)
#define I2C1_TXDR REG(I2C1_BASE + 0x28u)
#define I2C_CR1_PE (1u << 0)
#define I2C_CR1_TXIE (1u << 1)
#define I2C_CR1_RXIE (1u << 2)
#define I2C_CR1_ADDRIE (1u << 3)
#define I2C_CR1_NACKIE (1u << 4)
#define I2C_CR1_STOPIE (1u << 5)
#define I2C_CR1_ERRIE (1u << 7)
#define I2C_OAR1_OA1EN (1u << 15)
#define I2C_ISR_TXE (1u << 0)
#define I2C_ISR_TXIS (1u << 1)
#define I2C_ISR_RXNE (1u << 2)
#define I2C_ISR_ADDR (1u << 3)
#define I2C_ISR_NACKF (1u << 4)
#define I2C_ISR_STOPF (1u << 5)
#define I2C_ISR_BERR (1u << 8)
#define I2C_ISR_ARLO (1u << 9)
#define I2C_ISR_OVR (1u << 10)
#define I2C_ISR_PECERR (1u << 11)
#define I2C_ISR_TIMEOUT (1u << 12)
#define I2C_ISR_ALERT (1u << 13)
#define I2C_ISR_DIR (1u << 16) /* 1: the host reads (we transmit) */
#define I2C_ISR_ERRORS                                                                          \
    (I2C_ISR_BERR | I2C_ISR_ARLO | I2C_ISR_OVR | I2C_ISR_PECERR | I2C_ISR_TIMEOUT | I2C_ISR_ALERT)
#define I2C_ICR_ADDRCF (1u << 3)
#define I2C_ICR_NACKCF (1u << 4)
#define I2C_ICR_STOPCF (1u << 5)
/* the error clear bits sit at the positions of their flags */
/* RM0351 §39.4.10, "Examples of timing settings for fI2CCLK = 16 MHz", the
 * Fast-mode column: PRESC 1, SCLDEL 3, SDADEL 2 (SCLH 3, SCLL 9 are master
 * only). As a target only the data hold (SDADEL: 250 ns) and setup (SCLDEL:
 * 500 ns) delays apply, which meet both Standard- and Fast-mode hosts. */
#define I2C_TIMING_16MHZ 0x10320309u
#define IRQ_I2C1_EV 31u /* RM0351 §13.3 Table 57: vector at 0x0000 00BC */
#define IRQ_I2C1_ER 32u /* 0x0000 00C0 */

/* ---- fault record ---------------------------------------------------------
 * SRAM2 (32 KiB at 0x1000 0000, RM0351 §2.4) lies outside the RAM region of
 * linker/stm32l476.ld, so the start-up code neither loads nor clears it, and
 * with the factory option bit FLASH_OPTR.SRAM2_RST = 1 (RM0351 §3.7.8) a
 * system reset keeps its contents: its last two words hold a marker and the
 * code. (With SRAM2 parity enabled, SRAM2_PE = 0, the words must be written
 * before they are read; the factory setting leaves parity off.) */
#define FAULT_REC ((volatile uint32_t *)0x10007FF8u)
#define FAULT_MARK 0xB5FA0170u
#define FAULT_EXCEPTION 0x80000000u /* code of a CPU exception: this | vector */

/* ---- I2C target state (docs/I2C.md) ---------------------------------------
 * The window (bw_i2cwin.h) serves the payload from the application's buffer;
 * the bytes it hands the application (FRAMES writes, the ACK frame of
 * CMD = ACK) wait in a ring that link_read empties after the UART's. */
#define IN_SIZE 512u /* bytes from the I2C host (FRAMES writes, ACKs) */

static bw_i2cwin_t win;
static uint8_t in_buf[IN_SIZE];
static volatile uint32_t in_head; /* written by the I2C interrupt */
static volatile uint32_t in_tail; /* written by link_read */
static volatile uint8_t drdy_wanted;

/* ---- interrupt masking ---------------------------------------------------- */
static inline uint32_t irq_save(void)
{
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n\tcpsid i" : "=r"(primask)::"memory");
    return primask;
}

static inline void irq_restore(uint32_t primask)
{
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
}

static inline void dsb(void) { __asm__ volatile("dsb 0xF" ::: "memory"); }

/* ---- clock ---------------------------------------------------------------- */
/* RM0351 §6.2 (HSI16, system clock switch), §6.4.1 RCC_CR, §6.4.3 RCC_CFGR:
 * start HSI16 and switch SYSCLK to it. The reset state is MSI 4 MHz, voltage
 * range 1, AHB/APB prescalers 1 and FLASH_ACR.LATENCY = 0, which RM0351
 * §3.3.3 allows up to 16 MHz in range 1, so nothing else changes. */
static void clock_init(void)
{
    RCC_CR |= RCC_CR_HSION;
    while (!(RCC_CR & RCC_CR_HSIRDY)) {
    }
    RCC_CFGR = (RCC_CFGR & ~RCC_CFGR_SW_MASK) | RCC_CFGR_SW_HSI16;
    while ((RCC_CFGR & RCC_CFGR_SWS_MASK) != RCC_CFGR_SWS_HSI16) {
    }
}

/* ---- counter -------------------------------------------------------------- */
static uint32_t cyc_high, cyc_last;

/* with interrupts masked, or from SysTick */
static uint64_t cyc_extend(void)
{
    uint32_t now = DWT_CYCCNT;
    if (now < cyc_last)
        cyc_high++;
    cyc_last = now;
    return (uint64_t)cyc_high << 32 | now;
}

void SysTick_Handler(void) { (void)cyc_extend(); }

static void counter_init(void)
{
    DEMCR |= DEMCR_TRCENA;
    DWT_CYCCNT = 0;
    DWT_CTRL |= DWT_CTRL_CYCCNTENA;
    /* SysTick from the processor clock, every 2^24 cycles (about 1 s), far
     * inside the 2^32-cycle (268 s) wrap of DWT_CYCCNT */
    SYST_RVR = 0x00FFFFFFu;
    SYST_CVR = 0;
    SYST_CSR = 0x7u; /* CLKSOURCE, TICKINT, ENABLE */
}

static uint64_t counter(void)
{
    uint32_t m = irq_save();
    uint64_t v = cyc_extend();
    irq_restore(m);
    return v;
}

/* ---- GPIO ----------------------------------------------------------------- */
static void gpio_field(uint32_t base, uint32_t off, unsigned pin, unsigned bits, uint32_t value)
{
    unsigned shift = pin * bits;
    uint32_t mask = ((1u << bits) - 1u) << shift;
    REG(base + off) = (REG(base + off) & ~mask) | (value << shift);
}

static void gpio_af(uint32_t base, unsigned pin, uint32_t af)
{
    gpio_field(base, pin < 8u ? GPIO_AFRL : GPIO_AFRH, pin & 7u, 4u, af);
    gpio_field(base, GPIO_MODER, pin, 2u, MODE_AF);
}

static void drdy_update(void) /* with interrupts masked, or from the I2C interrupt */
{
    int high = drdy_wanted || win.offered;
    REG(GPIOA_BASE + GPIO_BSRR) = high ? 1u << DRDY_PIN : 1u << (DRDY_PIN + 16u);
}

static void gpio_init(void)
{
    RCC_AHB2ENR |= RCC_AHB2ENR_GPIOAEN | RCC_AHB2ENR_GPIOBEN;
    (void)RCC_AHB2ENR; /* read back: the clock starts a few cycles after its enable bit */

    /* PA2 USART2_TX, PA3 USART2_RX: AF7 (DS10198, alternate functions);
     * RX pulled up */
    gpio_field(GPIOA_BASE, GPIO_PUPDR, 3u, 2u, PULL_UP);
    gpio_af(GPIOA_BASE, 2u, 7u);
    gpio_af(GPIOA_BASE, 3u, 7u);

    /* PA5 DRDY: push-pull output, low */
    REG(GPIOA_BASE + GPIO_BSRR) = 1u << (DRDY_PIN + 16u);
    gpio_field(GPIOA_BASE, GPIO_MODER, DRDY_PIN, 2u, MODE_OUTPUT);

    /* PB8 I2C1_SCL, PB9 I2C1_SDA: AF4 (DS10198, alternate functions), open drain. The
     * internal pull-ups (about 40 kOhm) only keep an unconnected bus idle:
     * the bus needs its external pull-ups. */
    for (unsigned pin = 8u; pin <= 9u; pin++) {
        gpio_field(GPIOB_BASE, GPIO_OTYPER, pin, 1u, 1u);
        gpio_field(GPIOB_BASE, GPIO_OSPEEDR, pin, 2u, SPEED_MEDIUM);
        gpio_field(GPIOB_BASE, GPIO_PUPDR, pin, 2u, PULL_UP);
        gpio_af(GPIOB_BASE, pin, 4u);
    }
}

/* ---- USART2 --------------------------------------------------------------- */
static void usart_init(void)
{
    RCC_APB1ENR1 |= RCC_APB1ENR1_USART2EN;
    (void)RCC_APB1ENR1;
    USART2_CR1 = 0;
    USART2_CR2 = 0; /* 1 stop bit */
    USART2_CR3 = 0;
    /* RM0351 §40.5 (baud rate generation): oversampling by 16,
     * BRR = f_CK / baud = 139, 115108 baud (-0.08 %) */
    USART2_BRR = (SYSCLK_HZ + LINK_BAUD / 2u) / LINK_BAUD;
    USART2_CR1 = USART_CR1_TE | USART_CR1_RE | USART_CR1_UE; /* M = 00: 8 data bits, no parity */
}

/* ---- the link ---------------------------------------------------------------- */
/* the window's bytes for the application (from the I2C interrupt) */
static void in_push(void *ctx, const uint8_t *p, size_t n)
{
    (void)ctx;
    uint32_t head = in_head;
    for (size_t i = 0; i < n; i++) {
        if (head - in_tail >= IN_SIZE) {
            bw_i2cwin_lost(&win);
            break;
        }
        in_buf[head++ & (IN_SIZE - 1u)] = p[i];
    }
    in_head = head;
}

static void ready_changed(void *ctx, int offered)
{
    (void)ctx;
    (void)offered;
    drdy_update();
}

static const bw_i2cwin_ops_t win_ops = {in_push, ready_changed, 0};

static int link_write(const uint8_t *buf, size_t len)
{
    for (size_t i = 0; i < len; i++) {
        while (!(USART2_ISR & USART_ISR_TXE)) {
        }
        USART2_TDR = buf[i];
    }
    return (int)len;
}

/* Bytes from the UART, then the bytes from the I2C host (FRAMES writes and
 * the ACK frames of CMD = ACK). */
static int link_read(uint8_t *buf, size_t cap)
{
    size_t n = 0;
    while (n < cap && (USART2_ISR & USART_ISR_RXNE))
        buf[n++] = (uint8_t)USART2_RDR;
    if (USART2_ISR & (USART_ISR_ORE | USART_ISR_FE | USART_ISR_NF | USART_ISR_PE))
        USART2_ICR = USART_ICR_ERRORS; /* a lost or bad byte: the frame CRC catches it */
    uint32_t tail = in_tail;
    while (n < cap && tail != in_head)
        buf[n++] = in_buf[tail++ & (IN_SIZE - 1u)];
    in_tail = tail;
    return (int)n;
}

/* the payload the application keeps, served on I2C; its CRC-32 is computed
 * before the window's interrupt is masked */
static int offer(uint32_t id, const uint8_t *payload, size_t len, int32_t status)
{
    uint32_t crc = status == 0 && len ? bw_crc32(payload, len) : 0u;
    uint32_t m = irq_save();
    if (status < 0)
        bw_i2cwin_job_failed(&win, status);
    bw_i2cwin_offer(&win, id, payload, status < 0 ? 0u : (uint32_t)len, crc);
    irq_restore(m);
    return 0;
}

static int drdy_set(int level)
{
    uint32_t m = irq_save();
    drdy_wanted = level != 0;
    drdy_update();
    irq_restore(m);
    return 0;
}

/* ---- I2C1 target ------------------------------------------------------------
 * The events of the peripheral, handed to the window (bw_i2cwin.h). */
void I2C1_EV_IRQHandler(void);
void I2C1_EV_IRQHandler(void)
{
    for (;;) {
        uint32_t isr = I2C1_ISR;
        if (isr & I2C_ISR_RXNE) {
            bw_i2cwin_received(&win, (uint8_t)I2C1_RXDR);
        } else if (isr & I2C_ISR_STOPF) {
            bw_i2cwin_stop(&win);
            I2C1_ICR = I2C_ICR_STOPCF;
        } else if (isr & I2C_ISR_ADDR) {
            if (isr & I2C_ISR_DIR)
                I2C1_ISR = I2C_ISR_TXE; /* flush a byte left in TXDR by the previous read */
            bw_i2cwin_addressed(&win, (isr & I2C_ISR_DIR) != 0);
            I2C1_ICR = I2C_ICR_ADDRCF;
        } else if (isr & I2C_ISR_NACKF) {
            I2C1_ICR = I2C_ICR_NACKCF; /* the host ends its read */
        } else if (isr & I2C_ISR_TXIS) {
            I2C1_TXDR = bw_i2cwin_transmit(&win);
        } else {
            break;
        }
    }
}

/* Bus error, arbitration loss, overrun: the transfer is abandoned (nothing
 * leaves the ring) and STATUS.error is raised. */
void I2C1_ER_IRQHandler(void);
void I2C1_ER_IRQHandler(void)
{
    uint32_t isr = I2C1_ISR & I2C_ISR_ERRORS;
    I2C1_ICR = isr;
    if (isr)
        bw_i2cwin_bus_error(&win);
}

/* RM0351 §39.4.5-§39.4.8: timing and own address with PE = 0, then enable. */
static void i2c_init(void)
{
    RCC_APB1ENR1 |= RCC_APB1ENR1_I2C1EN;
    (void)RCC_APB1ENR1;
    I2C1_CR1 = 0;
    I2C1_TIMINGR = I2C_TIMING_16MHZ;
    I2C1_OAR1 = 0;
    I2C1_OAR2 = 0;
    I2C1_OAR1 = I2C_OAR1_OA1EN | (I2C_OWN_ADDR << 1); /* 7-bit address in OA1[7:1] */
    /* analog filter on, no digital filter, clock stretching on */
    I2C1_CR1 = I2C_CR1_TXIE | I2C_CR1_RXIE | I2C_CR1_ADDRIE | I2C_CR1_NACKIE | I2C_CR1_STOPIE |
               I2C_CR1_ERRIE;
    I2C1_CR1 |= I2C_CR1_PE;
    NVIC_ISER0 = 1u << IRQ_I2C1_EV;
    NVIC_ISER1 = 1u << (IRQ_I2C1_ER - 32u);
}

/* ---- fault ----------------------------------------------------------------- */
__attribute__((noreturn)) static void system_reset(void)
{
    dsb();
    SCB_AIRCR = AIRCR_VECTKEY | (SCB_AIRCR & AIRCR_PRIGROUP) | AIRCR_SYSRESETREQ;
    dsb();
    for (;;) {
    }
}

static void fault(uint32_t code)
{
    __asm__ volatile("cpsid i" ::: "memory");
    FAULT_REC[1] = code;
    FAULT_REC[0] = FAULT_MARK;
    system_reset();
}

/* an exception (hal/cortex-m/startup.c) or an unexpected interrupt (vectors.c) */
void bw_board_fault(uint32_t vector) { fault(FAULT_EXCEPTION | vector); }

/* exit() after QUIT: start again, ready for the next host */
__attribute__((noreturn)) void _exit(int status);
void _exit(int status)
{
    (void)status;
    __asm__ volatile("cpsid i" ::: "memory");
    system_reset();
}

static void fault_load(void)
{
    if (FAULT_REC[0] == FAULT_MARK)
        bw_i2cwin_set_fault(&win, FAULT_REC[1]);
    FAULT_REC[0] = 0;
}

/* ---- board ----------------------------------------------------------------- */
static const bw_hal_t board = {
    .counter = counter,
    .link_write = link_write,
    .link_read = link_read,
    .drdy_set = drdy_set,
    .sensor_open = NULL, /* no sensor driver yet: -BW_HAL_ENOSYS */
    .sensor_read = NULL,
    .fault = fault,
    .offer = offer,
};

static int started;

const bw_hal_t *bw_board(void)
{
    if (!started) {
        started = 1;
        SCB_VTOR = 0x08000000u; /* the image's table, at the start of flash */
        bw_i2cwin_init(&win, &win_ops);
        fault_load();
        clock_init();
        counter_init();
        gpio_init();
        usart_init();
        i2c_init();
    }
    return &board;
}
