//! The float types the fits run in, with the square root each target computes fastest.

use num_traits::Float;

/// A float type of the fits: `f64` on the host, `f32` on the chip.
pub trait Real: Float {
    /// The correctly rounded square root (IEEE 754), in hardware where the target has it.
    fn root(self) -> Self;
}

impl Real for f64 {
    fn root(self) -> f64 {
        self.sqrt()
    }
}

impl Real for f32 {
    /// NOTE: on a hard-float Cortex-M (M4F, M33) `vsqrt.f32` takes 14 cycles; libm's `sqrtf`, which
    /// `Float::sqrt` calls without std, computes it in software (about 30 % of the chip's ortho9 fit
    /// before this). Both are correctly rounded, so the chip and the host agree bit for bit.
    #[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
    fn root(self) -> f32 {
        vsqrt(self)
    }

    #[cfg(not(all(target_arch = "arm", target_abi = "eabihf")))]
    fn root(self) -> f32 {
        self.sqrt()
    }
}

/// The FPU's square root.
///
/// NOTE: a naked function, because inline assembly may name FPU registers only with the `vfp2`
/// target feature, which the single-precision FPUs of the M4F and M33 lack; the hard-float ABI
/// passes and returns the f32 in s0, and `.fpu` lets the assembler accept the instruction.
#[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
#[unsafe(naked)]
extern "C" fn vsqrt(x: f32) -> f32 {
    core::arch::naked_asm!(".fpu fpv4-sp-d16", "vsqrt.f32 s0, s0", "bx lr")
}

#[cfg(test)]
mod tests {
    use super::Real;

    #[test]
    fn roots_are_the_correctly_rounded_square_roots() {
        assert_eq!(2f32.root(), core::f32::consts::SQRT_2);
        assert_eq!(2f64.root(), core::f64::consts::SQRT_2);
        assert_eq!(0.0f32.root(), 0.0);
        assert!((-1f32).root().is_nan());
    }
}
