/* Startup code of the test image for Cortex-M (ARMv6-M and ARMv7E-M): the vector table, the reset
   handler (data and bss, FPU, alignment trap, static constructors, main) and a fault handler that
   reports through semihosting. */
#include <stdint.h>

#include "semihost.h"

extern uint32_t __data_start[], __data_end[], __data_load[], __bss_start[], __bss_end[], __stack_top[];
extern void (*__init_array_start[])(void);
extern void (*__init_array_end[])(void);
int main(void);

/* Set by main() around a load it makes unaligned on purpose: the fault handler then records the
   fault and resumes after the load, proving that the alignment trap is armed. */
volatile uint32_t firmware_expect_fault;
volatile uint32_t firmware_faults_seen;

#define SCB_CCR (*(volatile uint32_t*)0xE000ED14u)
#define SCB_CPACR (*(volatile uint32_t*)0xE000ED88u)
#define SCB_CFSR (*(volatile uint32_t*)0xE000ED28u)
#define CCR_UNALIGN_TRP (1u << 3)

void reset_handler(void) {
  const uint32_t* from = __data_load;
  for (uint32_t* to = __data_start; to < __data_end;) *to++ = *from++;
  for (uint32_t* to = __bss_start; to < __bss_end;) *to++ = 0;
#if defined(__ARM_FP)
  SCB_CPACR |= 0xFu << 20; /* full access to CP10 and CP11, the FPU */
  __asm volatile("dsb\n\tisb" ::: "memory");
#endif
#if defined(__ARM_ARCH_6M__)
  /* An ARMv6-M image faults on every unaligned access (on a Cortex-M0+ the bit reads as one; on
     the Cortex-M3 board that runs the image under qemu, setting it gives the same behaviour).
     Not for ARMv7E-M images: their compiler may merge byte loads into unaligned word loads, which
     that architecture allows. */
  SCB_CCR |= CCR_UNALIGN_TRP;
  __asm volatile("dsb\n\tisb" ::: "memory");
#endif
  for (void (**f)(void) = __init_array_start; f < __init_array_end; ++f) (*f)();
  semihost_exit(main() == 0);
}

static void write_hex(const char* name, uint32_t value) {
  char text[20];
  int i = 0;
  while (*name) text[i++] = *name++;
  for (int shift = 28; shift >= 0; shift -= 4) text[i++] = "0123456789abcdef"[(value >> shift) & 0xFu];
  text[i++] = '\n';
  text[i] = 0;
  semihost_write(text);
}

/* frame: the registers the core stacked on entry (r0-r3, r12, lr, pc, xpsr). */
void fault_report(uint32_t* frame) {
  if (firmware_expect_fault) {
    firmware_expect_fault = 0;
    ++firmware_faults_seen;
    frame[6] += 2; /* resume after the 16-bit load that faulted */
    return;
  }
  semihost_write("FAULT: unexpected processor fault\n");
  write_hex(" pc   ", frame[6]);
  write_hex(" lr   ", frame[5]);
#if __ARM_ARCH >= 7
  write_hex(" cfsr ", SCB_CFSR);
#endif
  semihost_exit(false);
}

__attribute__((naked)) void fault_handler(void) {
  __asm volatile(
      "mrs r0, msp\n\t"
      "ldr r1, =fault_report\n\t"
      "bx r1\n\t"
      ".ltorg");
}

__attribute__((section(".vectors"), used)) const void* const vector_table[16] = {
    __stack_top,   reset_handler, fault_handler, fault_handler, /* SP, reset, NMI, HardFault */
    fault_handler, fault_handler, fault_handler, 0, /* MemManage, BusFault, UsageFault */
    0,             0,             0,             fault_handler, /* SVCall */
    fault_handler, 0,             fault_handler, fault_handler, /* DebugMon, PendSV, SysTick */
};

/* Semihosting: r0 = operation, r1 = argument, BKPT 0xAB. */
static uint32_t semihost_call(uint32_t op, const void* arg) {
  register uint32_t r0 __asm("r0") = op;
  register const void* r1 __asm("r1") = arg;
  __asm volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

void semihost_write(const char* text) { (void)semihost_call(0x04u, text); }

void semihost_exit(bool ok) {
  /* ADP_Stopped_ApplicationExit ends qemu with status 0, ADP_Stopped_RunTimeErrorUnknown with 1. */
  (void)semihost_call(0x18u, (const void*)(uintptr_t)(ok ? 0x20026u : 0x20023u));
  for (;;) {
  }
}
