//! On an emulated Cortex-M4F, a Cortex-M0 (the Pico's instruction set) or a generic RV32IMC (the
//! ESP32-C3's): the chip's `ortho9` fit of the quick calibration's ten captures alone, between two
//! calls of a marker whose address it prints (`marker 0x...`), for an instruction count from QEMU's
//! trace (tests/fit_instructions.rs); then the fit's iterations and `done`.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(not(target_os = "none"))]
fn main() {}

#[cfg(target_os = "none")]
mod target {
    use qemu_tests::entry;
    use qemu_tests::semihosting::hprintln;

    /// Marks a point in the instruction trace; never inlined, so every call executes its address.
    #[inline(never)]
    fn marker() {
        qemu_tests::nop();
    }

    #[entry]
    fn main() -> ! {
        let readings = qemu_tests::quick_readings();
        hprintln!("marker {:#x}", marker as *const () as usize & !1);
        marker();
        let fit = core::hint::black_box(shared::ortho9::fit(core::hint::black_box(&readings)));
        marker();
        let ok = match fit {
            Ok(fit) => {
                hprintln!("iterations {}", fit.iterations);
                true
            }
            Err(_) => false,
        };
        qemu_tests::finish(ok)
    }
}
