//! The computations of `qemu_tests::run` on an emulated Cortex-M4F (QEMU netduinoplus2, whose
//! STM32F405 has the F411's flash and RAM addresses; tests/qemu/memory.x names them) against the
//! same code on the host.
//!
//! Needs the on-target binary (`cargo build -p qemu-tests --release --target thumbv7em-none-eabihf`)
//! and `qemu-system-arm` (Debian package); `.ci/run` provides both. Without them each test is
//! reported as ignored with its reason (tests/qemu/build.rs finds them when the crate is built),
//! except under CI=true, where their absence is a failure.

mod common;

use common::CORTEX_M4F;

use std::collections::BTreeMap;
use std::process::Stdio;
use std::time::{Duration, Instant};

/// Runs the binary under QEMU; its `name hex...` lines as f32 values, by name.
fn on_target() -> BTreeMap<String, Vec<u32>> {
    let elf = CORTEX_M4F.runnable("qemu-tests");
    let mut qemu = CORTEX_M4F
        .qemu()
        .arg("-kernel")
        .arg(&elf)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("qemu starts");
    let started = Instant::now();
    // NOTE: a bound on a hang, not a timing measurement; the run takes well under a second.
    while qemu.try_wait().expect("qemu runs").is_none() {
        if started.elapsed() > Duration::from_secs(120) {
            let _ = qemu.kill();
            panic!("the emulated board did not finish within 120 s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let output = qemu.wait_with_output().expect("qemu output");
    let text = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success() && text.lines().any(|l| l == "done"),
        "on target:\n{text}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    text.lines()
        .filter(|l| *l != "done")
        .map(|line| {
            let mut words = line.split_whitespace();
            let name = words.next().unwrap_or_default().to_owned();
            (name, words.map(|w| u32::from_str_radix(w, 16).expect("hex")).collect())
        })
        .collect()
}

#[test]
#[cfg_attr(not(on_target_runnable), ignore = "needs qemu-system-arm and the on-target binaries (tests/qemu/build.rs)")]
fn shared_math_and_the_firmware_library_give_the_host_s_results_on_a_cortex_m4f() {
    let target = on_target();
    let mut host = BTreeMap::new();
    assert!(qemu_tests::run(&mut |r| {
        host.insert(r.name.to_owned(), r.values.iter().map(|v| v.to_bits()).collect::<Vec<_>>());
    }));
    assert_eq!(target.keys().collect::<Vec<_>>(), host.keys().collect::<Vec<_>>());
    let (mut identical, mut total) = (0, 0);
    for (name, on_host) in &host {
        let on_chip = &target[name];
        assert_eq!(on_chip.len(), on_host.len(), "{name}");
        for (k, (&a, &b)) in on_chip.iter().zip(on_host).enumerate() {
            total += 1;
            if a == b {
                identical += 1;
                continue;
            }
            let (a, b) = (f32::from_bits(a), f32::from_bits(b));
            // NOTE: + - * / and sqrt are correctly rounded on both; only transcendental functions
            // (the noise generator's exp/ln, from libm on the chip and the C library on the host)
            // may differ in the last bit, and the six-position path has none.
            assert!(!name.starts_with("phone"), "{name}[{k}]: chip {a:e} vs host {b:e}: the same code path differs");
            assert!((a - b).abs() <= 1e-6 * b.abs().max(1.0), "{name}[{k}]: chip {a:e} vs host {b:e}");
        }
    }
    println!("{identical} of {total} values bit-identical on the emulated Cortex-M4F and the host");
}

/// The temperature correction as the host computes it, in f64 straight from DESIGN.md's convention:
/// a = M diag(1 + d(T))^-1 (m - o(T)), w = G (w_raw - b(T)), with dT = T - T_ref.
fn host_thermal_correction(raw: &firmware::sensor::RawSample) -> [f64; 7] {
    let calibration = qemu_tests::thermal_calibration();
    let model = calibration.temperature.expect("a temperature model");
    let temp_c = f64::from(raw.temp) / 340.0 + 36.53;
    let dt = temp_c - f64::from(model.ref_temp_c);
    let poly =
        |c: &[[f32; 3]; 3], axis: usize| (0..3).map(|k| f64::from(c[k][axis]) * dt.powi(k as i32 + 1)).sum::<f64>();
    let centred: Vec<f64> = (0..3)
        .map(|k| {
            let m = f64::from(raw.accel[k]) / 16384.0;
            (m - f64::from(calibration.offset_g[k]) - poly(&model.offset_g, k)) / (1.0 + poly(&model.scale, k))
        })
        .collect();
    let rate: Vec<f64> = (0..3)
        .map(|k| {
            f64::from(raw.gyro[k]) / 32.8 - f64::from(calibration.gyro.bias_dps[k]) - poly(&model.gyro_bias_dps, k)
        })
        .collect();
    let row = |m: &[[f32; 3]; 3], v: &[f64], i: usize| (0..3).map(|j| f64::from(m[i][j]) * v[j]).sum::<f64>();
    let mut out = [temp_c, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
    for i in 0..3 {
        out[1 + i] = row(&calibration.matrix, &centred, i);
        out[4 + i] = row(&calibration.gyro.matrix, &rate, i);
    }
    out
}

#[test]
#[cfg_attr(not(on_target_runnable), ignore = "needs qemu-system-arm and the on-target binaries (tests/qemu/build.rs)")]
fn the_chip_s_temperature_correction_equals_the_host_s_computation_at_15_to_45_degc() {
    let target = on_target();
    let on_chip = &target["thermal-corrected-samples"];
    for (i, raw) in qemu_tests::THERMAL_RAW.iter().enumerate() {
        let expected = host_thermal_correction(raw);
        for (k, want) in expected.iter().enumerate() {
            let got = f64::from(f32::from_bits(on_chip[7 * i + k]));
            // f32 on the chip against f64 on the host: a few units in the last place of values near 1.
            assert!(
                (got - want).abs() <= 2e-6 * want.abs().max(1.0),
                "sample {i} value {k}: chip {got} vs host {want}"
            );
        }
    }
    // The correction is not a no-op: at 45 degC the offset moved by tens of mg.
    let z45 = f64::from(f32::from_bits(on_chip[7 * 3 + 3]));
    let uncorrected_model = f64::from(qemu_tests::thermal_calibration().matrix[2][2]) * (-2100.0 / 16384.0 + 78.3e-3);
    assert!((z45 - uncorrected_model).abs() > 0.02, "z at 45 degC: {z45} vs {uncorrected_model} without the model");
}

#[test]
#[cfg_attr(not(on_target_runnable), ignore = "needs qemu-system-arm and the on-target binaries (tests/qemu/build.rs)")]
fn the_chip_s_ortho9_fit_of_a_simulated_session_equals_the_host_s_f64_fit_within_f32_tolerance() {
    let target = on_target();
    let on_chip: Vec<f64> = target["ortho9-session-params"].iter().map(|&b| f64::from(f32::from_bits(b))).collect();
    let readings: Vec<[f64; 3]> = qemu_tests::ortho9_session_readings().iter().map(|m| m.map(f64::from)).collect();
    let host = shared::ortho9::fit(&readings).expect("the host fits the session");
    for (k, (chip, host)) in on_chip.iter().zip(&host.params).enumerate() {
        // M is near the identity (1e-4 on its parameters is 1e-4 relative), o in g to 1e-5 g.
        let tolerance = if k < 6 { 1e-4 } else { 1e-5 };
        assert!((chip - host).abs() <= tolerance, "parameter {k}: chip {chip} vs host {host}");
    }
    // Not the start: the published sensor's z scale is 0.983.
    assert!((on_chip[5] - 1.0).abs() > 0.01, "s_z = {}", on_chip[5]);
    let iterations = f32::from_bits(target["ortho9-session-iterations"][0]);
    println!("chip: {iterations} iterations; host: {} iterations", host.iterations);
}

#[test]
#[cfg_attr(not(on_target_runnable), ignore = "needs qemu-system-arm and the on-target binaries (tests/qemu/build.rs)")]
fn the_chip_s_fit_on_request_equals_the_host_s_f64_fit_of_the_same_captures() {
    let target = on_target();
    let values = |name: &str| -> Vec<f64> { target[name].iter().map(|&b| f64::from(f32::from_bits(b))).collect() };
    let means = values("device-ortho9-means");
    let readings: Vec<[f64; 3]> = means.chunks_exact(3).map(|m| [m[0], m[1], m[2]]).collect();
    let host = shared::ortho9::fit(&readings).expect("the host fits the chip's captures");
    let (matrix, offset) = (host.matrix(), host.offset());
    let chip = values("device-ortho9-fit");
    // f32 against f64 over 200 problems: M within 5.6e-7, o within 7.2e-7 g (README); 1e-5 each
    // here leaves room for the capture means' own f32 rounding.
    for k in 0..9 {
        let want = matrix[k / 3][k % 3];
        assert!((chip[k] - want).abs() <= 1e-5, "M[{k}]: chip {} vs host {want}", chip[k]);
    }
    for k in 0..3 {
        assert!((chip[9 + k] - offset[k]).abs() <= 1e-5, "o[{k}]: chip {} g vs host {} g", chip[9 + k], offset[k]);
    }
    let [residual_mg, captures, iterations] = values("device-ortho9-residual-captures-iterations")[..] else {
        panic!("three values")
    };
    let host_residual_mg = (host.cost / readings.len() as f64).sqrt() * 1000.0;
    assert!(
        (residual_mg - host_residual_mg).abs() <= 0.01,
        "residual chip {residual_mg} mg vs host {host_residual_mg} mg"
    );
    assert_eq!(captures, 10.0);
    // Not the start: the realistic sensor's z offset is tens of mg.
    assert!(chip[11].abs() > 0.05, "o_z = {}", chip[11]);
    let worst_m = (0..9).map(|k| (chip[k] - matrix[k / 3][k % 3]).abs()).fold(0.0, f64::max);
    let worst_o = (0..3).map(|k| (chip[9 + k] - offset[k]).abs()).fold(0.0, f64::max);
    println!(
        "chip: {iterations} iterations, residual {residual_mg:.4} mg; host: {} iterations, {host_residual_mg:.4} mg; \
         M within {worst_m:.1e}, o within {worst_o:.1e} g",
        host.iterations
    );
}

/// The chip's gyro correction of a fast turn against the host's: per sample against w = G (w_raw -
/// b) in f64 (32.8 LSB per deg/s at +-1000 deg/s, Product Specification 6.1), and the turn's angle
/// integrated by the host's gyro fit from the chip's corrected rates against the same from the raw
/// rates with the host applying G and b.
#[test]
#[cfg_attr(not(on_target_runnable), ignore = "needs qemu-system-arm and the on-target binaries (tests/qemu/build.rs)")]
fn the_chip_s_gyro_correction_of_a_fast_turn_equals_the_host_s() {
    let target = on_target();
    let on_chip: Vec<f64> = target["gyro-turn-corrected"].iter().map(|&b| f64::from(f32::from_bits(b))).collect();
    let calibration = qemu_tests::gyro_calibration();
    // G as the chip computed it (the sim's f32 inverse) equals the host's build of the same truth.
    let chip_g: Vec<f32> = target["gyro-matrix"].iter().map(|&b| f32::from_bits(b)).collect();
    assert_eq!(chip_g, calibration.gyro.matrix.as_flattened(), "the chip's G and the host's");
    let g = nalgebra::Matrix3::from_fn(|i, j| f64::from(calibration.gyro.matrix[i][j]));
    let bias = calibration.gyro.bias_dps.map(f64::from);
    let raw: Vec<[f64; 3]> = qemu_tests::gyro_turn_raw().iter().map(|s| s.gyro.map(|c| f64::from(c) / 32.8)).collect();
    for (i, w) in raw.iter().enumerate() {
        let want = g * nalgebra::Vector3::from_fn(|k, _| w[k] - bias[k]);
        for k in 0..3 {
            let got = on_chip[3 * i + k];
            // f32 on the chip against f64: rates up to 750 deg/s to a few units in f32's last place.
            assert!(
                (got - want[k]).abs() <= 2e-6 * want[k].abs().max(1.0),
                "sample {i} axis {k}: chip {got} vs host {}",
                want[k]
            );
        }
    }
    let turn = |rates_dps: Vec<[f64; 3]>, bias_dps: [f64; 3]| accelcal::fit::gyro::Turn {
        rates_dps,
        interval_s: 0.01,
        bias_before_dps: bias_dps,
        bias_after_dps: bias_dps,
        up_before: [0.0, 0.0, 1.0],
        up_after: [0.0, 0.0, 1.0],
    };
    let chip_rates: Vec<[f64; 3]> = on_chip.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    let chip_deg = accelcal::fit::gyro::turned_deg(&turn(chip_rates, [0.0; 3]), &nalgebra::Matrix3::identity());
    let host_deg = accelcal::fit::gyro::turned_deg(&turn(raw.clone(), bias), &g);
    assert!((chip_deg - host_deg).abs() < 1e-4, "chip {chip_deg} deg vs host {host_deg} deg");
    // Not a no-op: G moves this turn's angle by tenths of a degree from the raw one.
    let uncorrected = accelcal::fit::gyro::turned_deg(&turn(raw, bias), &nalgebra::Matrix3::identity());
    assert!((host_deg - uncorrected).abs() > 0.1, "G changed the turn from {uncorrected} to {host_deg} deg only");
    println!("the fast turn: {chip_deg:.5} deg on the chip, {host_deg:.5} deg on the host, {uncorrected:.5} deg raw");
}
