//! On an emulated Cortex-M4F (QEMU netduinoplus2, an STM32F405): runs the computations of the library and prints each
//! result over semihosting as `name hex hex ...` (f32 bit patterns), then `done`.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(not(target_os = "none"))]
fn main() {}

#[cfg(target_os = "none")]
mod target {
    use qemu_tests::entry;
    use qemu_tests::semihosting::{hprint, hprintln};

    #[entry]
    fn main() -> ! {
        let ok = qemu_tests::run(&mut |result| {
            hprint!("{}", result.name);
            for value in result.values {
                hprint!(" {:08x}", value.to_bits());
            }
            hprintln!("");
        });
        qemu_tests::finish(ok)
    }
}
